/**
 * The accel setting's CPU side: prepare builds the grid and packs it into bvh_nodes after the top
 * level (read back word for word as shaders/scene/grid.wgsl reads it), switching accel packs what a
 * fresh preparation packs, and a static move builds the grid again over the moved world.
 */
import { describe, expect, it } from 'vitest';
import { tileMapScene } from '../bvh/grid-test-scenes.ts';
import { traceGrid } from '../bvh/grid.ts';
import { sceneLayouts } from '../gpu/pack/scene-pack.ts';
import { translation } from '../math/mat4.ts';
import { prepareScene, updateGeometry, withAccel } from './prepare.ts';

describe('accel grid', () => {
  it('packs the grid after the top level, as the shader reads it', () => {
    const prepared = prepareScene(tileMapScene({ n: 16, seed: 2, moving: true }), undefined, { accel: 'grid' });
    const grid = prepared.grid!;
    const { layout, features } = prepared.packed;
    expect(features.staticGrid).toBe(true);
    expect(layout.gridBase).toBe(layout.tlasBase + layout.tlasCapacity);
    const stride = sceneLayouts().node.strideWords;
    const u32 = new Uint32Array(prepared.packed.bvh_nodes), f32 = new Float32Array(prepared.packed.bvh_nodes);
    const h = layout.gridBase * stride;
    expect([f32[h], f32[h + 1], f32[h + 2]]).toEqual([...grid.lo]);
    expect([f32[h + 4], f32[h + 5], f32[h + 6]]).toEqual([...grid.hi]);
    expect([f32[h + 8], f32[h + 9], f32[h + 10]]).toEqual([...grid.cellSize]);
    expect([u32[h + 3], u32[h + 7], u32[h + 11]]).toEqual([...grid.dims]);
    const cellsWord = u32[h + 12]!, itemsWord = u32[h + 13]!;
    for (let c = 0; c < grid.cellStart.length; c++) {
      expect(u32[cellsWord + 2 * c]).toBe(grid.cellStart[c]);
      expect(u32[cellsWord + 2 * c + 1]).toBe(grid.cellCount[c]);
    }
    expect(u32.slice(itemsWord, itemsWord + grid.items.length)).toEqual(grid.items);
    // The scene info points at it.
    const info = new Uint32Array(prepared.packed.scene_info);
    expect(info[sceneLayouts().sceneInfo.word('grid_base', 'u32')]).toBe(layout.gridBase);
  });

  it('switching accel packs what a fresh preparation packs', () => {
    const scene = tileMapScene({ n: 12, seed: 6, moving: true });
    const bvh = prepareScene(scene), grid = prepareScene(scene, undefined, { accel: 'grid' });
    const toGrid = withAccel(bvh, 'grid'), back = withAccel(toGrid, 'bvh');
    expect(new Uint8Array(toGrid.packed.bvh_nodes)).toEqual(new Uint8Array(grid.packed.bvh_nodes));
    expect(new Uint8Array(toGrid.packed.scene_info)).toEqual(new Uint8Array(grid.packed.scene_info));
    expect(new Uint8Array(back.packed.bvh_nodes)).toEqual(new Uint8Array(bvh.packed.bvh_nodes));
    expect(back.grid).toBeUndefined();
    expect(back.packed.features.staticGrid).toBe(false);
    expect(withAccel(grid, 'grid')).toBe(grid);
  });

  it('builds the grid again when the static world moves', () => {
    const prepared = prepareScene(tileMapScene({ n: 12, seed: 6 }), undefined, { accel: 'grid' });
    // Instance 1 (the ball, static) moves 3 units up: the grid must list it where it is now.
    const moved = updateGeometry(prepared, new Map([[1, { worldFromObject: translation([0, 3, 0]) }]]), new Map()).prepared;
    expect(moved.grid).not.toBe(prepared.grid);
    const ball = moved.triangles.count - 1;
    const p = moved.triangles.positions;
    const hit = traceGrid(moved.grid!, p, { origin: [p[ball * 9]!, 10, p[ball * 9 + 2]!], direction: [0, -1, 0] }, moved.triangles.kinds).hit;
    expect(hit?.triangle).toBe(ball);
    expect(hit?.t).toBeCloseTo(10 - 3.3 - 0.3, 4);
  });
});
