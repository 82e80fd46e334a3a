import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { SHADER_MODULES } from '../../shaders/index.ts';
import { linkWgsl, sourceLocation } from './linker.ts';

const modules = new Map([
  ['a', '// a\n#import b\n#import c\nfn a() {}'],
  ['b', '#import c\nfn b() {}'],
  ['c', 'fn c() {}'],
  ['loop1', '#import loop2\n'],
  ['loop2', '#import loop1\n'],
  ['missing', '#import nowhere\n'],
]);

describe('WGSL linker', () => {
  it('emits each module once, dependencies first, without import lines', () => {
    const linked = linkWgsl('a', modules);
    expect(linked.modules).toEqual(['c', 'b', 'a']);
    expect(linked.code.match(/fn c\(\)/g)).toHaveLength(1);
    expect(linked.code).not.toMatch(/#import/);
  });

  it('maps output lines back to module and line', () => {
    const linked = linkWgsl('a', modules);
    const lines = linked.code.split('\n');
    const at = lines.indexOf('fn a() {}') + 1;
    expect(sourceLocation(linked, at)).toBe('a.wgsl:4');
    expect(sourceLocation(linked, lines.indexOf('fn b() {}') + 1)).toBe('b.wgsl:2');
  });

  it('names import cycles and missing modules', () => {
    expect(() => linkWgsl('loop1', modules)).toThrow(/cycle: loop1 -> loop2 -> loop1/);
    expect(() => linkWgsl('missing', modules)).toThrow(LanternError);
    expect(() => linkWgsl('missing', modules)).toThrow(/'nowhere' not found \(imported by 'missing'\)/);
  });

  it('links every pass module of the project', () => {
    const passes = [...SHADER_MODULES.keys()].filter((m) => m.startsWith('passes/'));
    expect(passes.length).toBeGreaterThanOrEqual(6);
    for (const p of passes) expect(() => linkWgsl(p)).not.toThrow();
  });
});

describe('linker substitutes', () => {
  it('links the substitute wherever the module is imported, once', () => {
    const sources = new Map([
      ['entry', '#import x\n#import y\nfn main() {}'],
      ['y', '#import x\nfn y() {}'],
      ['x', 'fn x_generic() {}'],
      ['x-fast', 'fn x_fast() {}'],
    ]);
    const linked = linkWgsl('entry', sources, new Map([['x', 'x-fast']]));
    expect(linked.modules).toEqual(['x-fast', 'y', 'entry']);
    expect(linked.code).not.toContain('x_generic');
    expect(linked.code.match(/fn x_fast/g)).toHaveLength(1);
  });
});
