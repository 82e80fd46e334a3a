import { describe, expect, it } from 'vitest';
import { formatMaterialOverride, parseMaterialOverride, type MaterialOverride } from './material-link.ts';
import { formatViewParams, parseViewParams, type ViewParams } from './view-params.ts';

describe('material edits in links', () => {
  it('round-trip through the page URL with other parameters, names with separators included', () => {
    const materials: MaterialOverride[] = [
      { index: 1, name: 'red', edit: { color: [0.1, 0.25, 0.9], emission: [0, 0, 0] } },
      { index: 12, name: 'Glass: 50% / tinted;(B)', edit: { roughness: 0.05, metallic: 0, ior: 1.52, transmission: 1 } },
      { index: 3, name: 'lamp', edit: { emission: [170.5, 120, 40.25] } },
    ];
    const view: ViewParams = { scene: { kind: 'builtin', name: 'cornell' }, maxBounces: 4, materials };
    const link = formatViewParams(view).toString();
    const { view: back, problems } = parseViewParams(new URLSearchParams(link));
    expect(problems).toEqual([]);
    expect(back).toEqual(view);
    expect(formatMaterialOverride(materials[0]!)).toBe('1:1:red:c=0.1,0.25,0.9;e=0,0,0');
  });

  it('warn about malformed or out-of-range edits and keep the good ones', () => {
    const bad = ['2:1:red:c=1,1,1', '1:x:red:c=1,1,1', '1:1:red', '1:1:red:c=1,1', '1:1:red:q=3', '1:1:red:r=2', '1:1:red:c=1,1,1;c=0,0,0', '1:1:%E0%A4%A:r=0.5', '1:1:red:', '1:-1:red:r=0.5', '1:1:red:e=-1,0,0', '1:1:red:i=0.5'];
    for (const raw of bad) {
      const parsed = parseMaterialOverride(raw);
      expect(parsed.ok, raw).toBe(false);
      if (!parsed.ok) expect(parsed.problem).toContain(`mat=${raw}`);
    }
    const params = new URLSearchParams();
    for (const raw of [...bad, '1:2:green:r=0.5', '1:2:green:r=0.25']) params.append('mat', raw);
    params.append('mat', '1:4:white:c=0.5,0.5,0.5');
    const { view, problems } = parseViewParams(params);
    expect(problems).toHaveLength(bad.length + 1);
    expect(problems.at(-1)).toMatch(/material 2 is edited twice/);
    expect(view.materials).toEqual([
      { index: 2, name: 'green', edit: { roughness: 0.5 } },
      { index: 4, name: 'white', edit: { color: [0.5, 0.5, 0.5] } },
    ]);
  });
});
