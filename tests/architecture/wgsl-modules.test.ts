/**
 * The shape of src/shaders (issue #28, docs/architecture.md "Shaders"): an entry file (one that
 * declares a @compute, @vertex or @fragment entry point) is a leaf of the import graph. What two
 * entry files share lives in a library module (integrator/dispatch, integrator/frame), so that a
 * kernel's module never drags another kernel's bindings and entry points into its own.
 */
import { describe, expect, it } from 'vitest';
import { SHADER_MODULES } from '../../src/shaders/index.ts';

const IMPORT = /^\s*#import\s+(\S+)\s*$/gm;
const ENTRY = /@(compute|vertex|fragment)\b/;

export function isEntryModule(source: string): boolean {
  return ENTRY.test(source.replace(/\/\/.*$/gm, ''));
}

/** "a imports b" for every entry module a that imports an entry module b. */
export function entryImports(modules: ReadonlyMap<string, string>): string[] {
  const out: string[] = [];
  for (const [name, source] of modules) {
    if (!isEntryModule(source)) continue;
    for (const m of source.matchAll(IMPORT)) {
      const imported = modules.get(m[1]!);
      if (imported !== undefined && isEntryModule(imported)) out.push(`${name} imports ${m[1]}`);
    }
  }
  return out.sort();
}

describe('the WGSL modules', () => {
  it('read the real shaders', () => {
    expect(SHADER_MODULES.size).toBeGreaterThan(50);
    expect(isEntryModule(SHADER_MODULES.get('passes/path-trace')!)).toBe(true);
    expect(isEntryModule(SHADER_MODULES.get('integrator/path')!)).toBe(false);
  });

  it('have no entry file importing another', () => {
    expect(entryImports(SHADER_MODULES)).toEqual([]);
  });

  it('catch an entry file importing another (the checker fails where it should)', () => {
    const modules = new Map([
      ['a', '#import b\n#import lib\n@compute @workgroup_size(1) fn a() {}'],
      ['b', '@compute @workgroup_size(1)\nfn b() {}'],
      ['lib', '// not an entry: @compute in a comment\nfn f() {}'],
    ]);
    expect(entryImports(modules)).toEqual(['a imports b']);
  });
});
