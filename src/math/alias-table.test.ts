import { describe, expect, it } from 'vitest';
import { aliasTableProbabilities, buildAliasTable } from './alias-table.ts';

describe('alias table', () => {
  it.each([
    [[1]],
    [[1, 1, 1, 1]],
    [[5, 1, 0, 3]],
    [[1e-9, 1, 1e9]],
    [Array.from({ length: 1000 }, (_, i) => ((i * 7919) % 13) + (i % 3 === 0 ? 0 : 0.5))],
  ])('reproduces the weights exactly (%#)', (weights) => {
    const table = buildAliasTable(weights);
    const p = aliasTableProbabilities(table);
    const total = weights.reduce((a, b) => a + b, 0);
    weights.forEach((w, i) => expect(p[i]).toBeCloseTo(w / total, 12));
    for (const k of table.keep) expect(k).toBeGreaterThanOrEqual(0);
    for (const k of table.keep) expect(k).toBeLessThanOrEqual(1);
  });

  it('never aliases to a zero-weight outcome', () => {
    const table = buildAliasTable([0, 2, 0, 1]);
    table.alias.forEach((a, i) => {
      if (table.keep[i]! < 1) expect([1, 3]).toContain(a);
    });
  });

  it('rejects empty, all-zero and negative weights', () => {
    expect(() => buildAliasTable([])).toThrow();
    expect(() => buildAliasTable([0, 0])).toThrow();
    expect(() => buildAliasTable([1, -1])).toThrow();
  });
});
