/**
 * Workgroup sizes are set from TypeScript (issue #28): lib/workgroup declares PIXEL_TILE_X,
 * PIXEL_TILE_Y and RAY_GROUP without a value, gpu/kernel-variants.ts WORKGROUP gives them to every
 * pipeline whose module imports it and sizes the dispatch grids. Nothing else may state a size: an
 * entry point with a literal @workgroup_size (other than a single invocation) is one of the listed
 * kernels whose workgroup arrays are sized by it, and no pass keeps a number of its own.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { pixelGroups, WORKGROUP, WORKGROUP_CONSTANTS, workgroupConstants } from '../../src/gpu/kernel-variants.ts';
import { SHADER_MODULES } from '../../src/shaders/index.ts';

const SIZE = /@workgroup_size\(([^)]*)\)/g;
/** Modules whose kernels size workgroup arrays by their own constants (the BVH builder, the exposure reduction). */
const OWN_SIZES = /^(build\/|passes\/exposure$)/;

const withoutComments = (source: string) => source.replace(/\/\/.*$/gm, '');

describe('workgroup sizes', () => {
  it('are the overrides of lib/workgroup in every per-pixel and per-ray kernel', () => {
    const literal: string[] = [];
    let overridden = 0;
    for (const [name, source] of SHADER_MODULES) {
      if (OWN_SIZES.test(name)) continue;
      for (const m of withoutComments(source).matchAll(SIZE)) {
        const args = m[1]!.split(',').map((a) => a.trim());
        if (args.every((a) => /^[A-Z_]+$/.test(a))) {
          for (const a of args) expect(Object.keys(WORKGROUP_CONSTANTS), `${name}: ${a}`).toContain(a);
          expect(source, `${name} uses ${args.join(', ')} without importing lib/workgroup`).toMatch(/^#import lib\/workgroup$/m);
          overridden++;
        } else if (!(args.length === 1 && args[0] === '1')) literal.push(`${name}: @workgroup_size(${m[1]})`);
      }
    }
    expect(literal).toEqual([]);
    // The path tracers, the chain (whose à-trous the hybrid shares), the hybrid, the debug views, ReSTIR, the wavefront, trace-rays: 29 entry points.
    expect(overridden).toBeGreaterThanOrEqual(29);
  });

  it('have no value in WGSL: TypeScript sets every one', () => {
    const source = withoutComments(SHADER_MODULES.get('lib/workgroup')!);
    const declared = [...source.matchAll(/override\s+(\w+)\s*:\s*u32\s*([=;])/g)];
    expect(declared.map((d) => d[1]).sort()).toEqual(Object.keys(WORKGROUP_CONSTANTS).sort());
    expect(declared.map((d) => d[2])).toEqual(declared.map(() => ';'));
  });

  it('are given to the modules that import lib/workgroup and to no other', () => {
    expect(workgroupConstants(['lib/workgroup', 'passes/tonemap'])).toEqual({ PIXEL_TILE_X: 8, PIXEL_TILE_Y: 8, RAY_GROUP: 64 });
    expect(workgroupConstants(['build/morton'])).toEqual({});
  });

  it('size the grids: every pixel covered, no workgroup wholly outside', () => {
    for (const [w, h] of [[1, 1], [8, 8], [9, 7], [1920, 1080], [33, 64]] as const) {
      const [gx, gy] = pixelGroups(w, h);
      expect(gx * WORKGROUP.pixelX).toBeGreaterThanOrEqual(w);
      expect((gx - 1) * WORKGROUP.pixelX).toBeLessThan(w);
      expect(gy * WORKGROUP.pixelY).toBeGreaterThanOrEqual(h);
      expect((gy - 1) * WORKGROUP.pixelY).toBeLessThan(h);
    }
  });

  it('keep the benchmark\'s tile order: one trace-rays workgroup is one pixel tile', () => {
    expect(WORKGROUP.rays).toBe(WORKGROUP.pixelX * WORKGROUP.pixelY);
  });

  it('are stated by no pass of its own', () => {
    const dir = join(import.meta.dirname, '../../src/passes');
    const own = readdirSync(dir)
      .filter((f) => f.endsWith('.ts'))
      .filter((f) => /const \w*WORKGROUP\w* = \d/.test(readFileSync(join(dir, f), 'utf8')));
    expect(own).toEqual([]);
  });
});
