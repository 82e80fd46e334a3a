/**
 * Issue #28: one contract for every pass (src/passes/pass.ts). Every class named *Pass exported from
 * src/passes implements Pass<its frame>, has encode(encoder, frame) with two parameters and no
 * other public encode* method, and destroy(). Read from the syntax tree (vite's parseAst, as
 * layers.ts reads imports), so a comment or a string that looks like a class does not count.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseAst } from 'vite';
import { describe, expect, it } from 'vitest';

const PASSES = join(import.meta.dirname, '../../src/passes');

interface Node {
  readonly type: string;
  readonly [key: string]: unknown;
}

const nameOf = (n: unknown): string | undefined => ((n as Node | null)?.type === 'Identifier' ? ((n as Node)['name'] as string) : undefined);

/** What is wrong with the exported *Pass classes of one file, one line each. */
function passContractProblems(text: string, path: string): string[] {
  const ast = parseAst(text, { lang: 'ts' }, path) as unknown as { body: Node[] };
  const problems: string[] = [];
  for (const statement of ast.body) {
    const declaration = statement.type === 'ExportNamedDeclaration' || statement.type === 'ExportDefaultDeclaration' ? (statement['declaration'] as Node | null) : null;
    if (declaration?.type !== 'ClassDeclaration') continue;
    const name = nameOf(declaration['id']);
    if (!name?.endsWith('Pass')) continue;
    const where = `${path}: ${name}`;
    const implemented = ((declaration['implements'] as Node[] | null) ?? []).filter((i) => nameOf(i['expression']) === 'Pass');
    if (implemented.length === 0) problems.push(`${where} does not implement Pass`);
    else if (!(implemented[0]!['typeArguments'] as Node | null)) problems.push(`${where} implements Pass without its frame type`);
    const members = ((declaration['body'] as Node)['body'] as Node[]).filter((m) => m.type === 'MethodDefinition' && !m['static']);
    const method = (m: Node) => nameOf(m['key']);
    const encode = members.find((m) => method(m) === 'encode' && m['kind'] === 'method');
    if (!encode) problems.push(`${where} has no encode method`);
    else {
      const params = ((encode['value'] as Node)['params'] as Node[]).length;
      if (params !== 2) problems.push(`${where}.encode takes ${params} parameters, not (encoder, frame)`);
    }
    for (const m of members) {
      const n = method(m);
      if (n && n !== 'encode' && /^encode/.test(n) && m['accessibility'] !== 'private') problems.push(`${where}.${n}: a second public encode (put what it records in the frame)`);
    }
    if (!members.some((m) => method(m) === 'destroy')) problems.push(`${where} has no destroy method`);
  }
  return problems;
}

describe('the pass contract', () => {
  it('holds for every *Pass class exported from src/passes', () => {
    const files = readdirSync(PASSES).filter((f) => f.endsWith('.ts') && !f.endsWith('.test.ts'));
    let classes = 0;
    const problems = files.flatMap((f) => {
      const text = readFileSync(join(PASSES, f), 'utf8');
      classes += (text.match(/^export class \w+Pass\b/gm) ?? []).length;
      return passContractProblems(text, `src/passes/${f}`);
    });
    expect(problems).toEqual([]);
    // The checker saw the passes (fifteen when the contract was made).
    expect(classes).toBeGreaterThanOrEqual(15);
  });

  it('flags a pass without the contract, or with an encode of other parameters', () => {
    const good = `import type { Pass, PassFrame } from './pass.ts';
      export class GoodPass implements Pass<PassFrame> { encode(encoder: GPUCommandEncoder, frame: PassFrame): void {} private encodeHalf(): void {} destroy(): void {} }`;
    expect(passContractProblems(good, 'good.ts')).toEqual([]);
    const bad = `export class LoosePass { encode(encoder: GPUCommandEncoder, view: ViewUniform, timer?: GpuTimer): void {} destroy(): void {} }
      export class BarePass implements Pass { encode(e: GPUCommandEncoder, f: F): void {} encodeMore(e: GPUCommandEncoder): void {} }
      export class Helper { encode(a: number): void {} }`;
    expect(passContractProblems(bad, 'bad.ts')).toEqual([
      'bad.ts: LoosePass does not implement Pass',
      'bad.ts: LoosePass.encode takes 3 parameters, not (encoder, frame)',
      'bad.ts: BarePass implements Pass without its frame type',
      'bad.ts: BarePass.encodeMore: a second public encode (put what it records in the frame)',
      'bad.ts: BarePass has no destroy method',
    ]);
  });
});
