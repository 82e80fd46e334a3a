/**
 * The accel setting's CPU side: prepare builds the grid and packs it into bvh_nodes after the top
 * level (read back word for word as shaders/scene/grid.wgsl reads it), switching accel packs what a
 * fresh preparation packs, and a static move builds the grid again over the moved world; the same for
 * the wide trees (bvh/wide.ts).
 */
import { describe, expect, it } from 'vitest';
import { tileMapScene } from '../bvh/grid-test-scenes.ts';
import { traceGrid } from '../bvh/grid.ts';
import { traceWide } from '../bvh/wide.ts';
import { sceneLayouts, SHALLOW_STACK_ENTRIES } from '../gpu/pack/scene-pack.ts';
import { placeEachOnce } from '../scene/instances.ts';
import { diffuse, type Scene } from '../scene/types.ts';
import { translation } from '../math/mat4.ts';
import { accelOf, prepareScene, updateGeometry, withAccel, withPreparedEnvironment } from './prepare.ts';

describe('accel grid', () => {
  it('packs the grid after the top level, as the shader reads it', () => {
    const prepared = prepareScene(tileMapScene({ n: 16, seed: 2, moving: true }), undefined, { accel: 'grid' });
    const grid = prepared.grid!;
    const { layout, features } = prepared.packed;
    expect(features.staticAccel).toBe('grid');
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
    expect(back.packed.features.staticAccel).not.toBe('grid');
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

describe('accel bvh4 / cwbvh', () => {
  it.each(['bvh4', 'cwbvh'] as const)('%s: packs the wide tree after the top level as the shader reads it, and switching packs what a fresh preparation packs', (layout) => {
    const scene = tileMapScene({ n: 12, seed: 6, moving: true });
    const prepared = prepareScene(scene, undefined, { accel: layout });
    const wide = prepared.wide!;
    expect(wide.layout).toBe(layout);
    expect(prepared.grid).toBeUndefined();
    const { layout: packedLayout, features } = prepared.packed;
    expect(features.staticAccel).toBe(layout);
    expect(packedLayout.gridBase).toBe(packedLayout.tlasBase + packedLayout.tlasCapacity);
    const stride = sceneLayouts().node.strideWords;
    const u32 = new Uint32Array(prepared.packed.bvh_nodes);
    const h = packedLayout.gridBase * stride;
    const nodesWord = u32[h]!, tableWord = u32[h + 1]!;
    expect(u32.slice(nodesWord, nodesWord + wide.nodes.length)).toEqual(wide.nodes);
    expect(u32.slice(tableWord, tableWord + wide.leafTable.length)).toEqual(wide.leafTable);
    expect(prepared.packed.counts.nodes * stride).toBeGreaterThanOrEqual(tableWord + wide.leafTable.length);
    const info = new Uint32Array(prepared.packed.scene_info);
    expect(info[sceneLayouts().sceneInfo.word('grid_base', 'u32')]).toBe(packedLayout.gridBase);
    expect(accelOf(prepared)).toBe(layout);
    // Switching: to the layout from the BVH and from the grid, and back.
    const bvh = prepareScene(scene);
    for (const from of [bvh, withAccel(bvh, 'grid')]) {
      const to = withAccel(from, layout);
      expect(to.grid).toBeUndefined();
      expect(new Uint8Array(to.packed.bvh_nodes)).toEqual(new Uint8Array(prepared.packed.bvh_nodes));
      expect(new Uint8Array(to.packed.scene_info)).toEqual(new Uint8Array(prepared.packed.scene_info));
    }
    const back = withAccel(prepared, 'bvh');
    expect(back.wide).toBeUndefined();
    expect(new Uint8Array(back.packed.bvh_nodes)).toEqual(new Uint8Array(bvh.packed.bvh_nodes));
  });

  it('keeps the wide tree through a static move (collapsed again from the refitted BVH), an environment change and an emission edit', () => {
    const prepared = prepareScene(tileMapScene({ n: 12, seed: 6 }), undefined, { accel: 'cwbvh' });
    const moved = updateGeometry(prepared, new Map([[1, { worldFromObject: translation([0, 3, 0]) }]]), new Map()).prepared;
    expect(moved.wide).not.toBe(prepared.wide);
    expect(moved.packed.features.staticAccel).toBe('cwbvh');
    const ball = moved.triangles.count - 1;
    const p = moved.triangles.positions;
    const hit = traceWide(moved.wide!, p, { origin: [p[ball * 9]!, 10, p[ball * 9 + 2]!], direction: [0, -1, 0] }, moved.triangles.kinds).hit;
    expect(hit?.triangle).toBe(ball);
    expect(hit?.t).toBeCloseTo(10 - 3.3 - 0.3, 4);
    const lit = withPreparedEnvironment(moved, { kind: 'constant', radiance: [1, 1, 1] });
    expect(lit.packed.features.staticAccel).toBe('cwbvh');
    expect(new Uint8Array(lit.packed.bvh_nodes)).toEqual(new Uint8Array(moved.packed.bvh_nodes));
  });
});

describe('the shallow stack', () => {
  /** A mesh of tiny triangles at x = 1.3^k: each SAH split peels off the farthest, so the tree is a chain about as deep as the mesh is long. */
  function chainScene(n: number): Scene {
    const positions: number[] = [];
    for (let k = 0; k < n; k++) positions.push(1.3 ** k, 0, 0, 1.3 ** k + 0.1, 0, 0, 1.3 ** k, 0.1, 0);
    const mesh = { name: 'chain', positions: new Float32Array(positions), indices: Uint32Array.from({ length: 3 * n }, (_, i) => i), materialIds: new Uint32Array(n) };
    return { name: 'chain', meshes: [mesh], instances: placeEachOnce([mesh]), materials: [diffuse('white', [0.8, 0.8, 0.8])], camera: { position: [0, 0, -10], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 40 } };
  }

  it('is used exactly when no traversal can hold more than SHALLOW_STACK_ENTRIES nodes: nothing moving and the static tree at most that deep', () => {
    const still = prepareScene(tileMapScene({ n: 12, seed: 6, moving: false }));
    expect(still.bvh.stats.maxDepth).toBeLessThanOrEqual(SHALLOW_STACK_ENTRIES);
    expect(still.packed.features.shallowStack).toBe(true);
    expect(prepareScene(tileMapScene({ n: 12, seed: 6, moving: true })).packed.features.shallowStack).toBe(false);
    const deep = prepareScene(chainScene(320));
    expect(deep.bvh.stats.maxDepth).toBeGreaterThan(SHALLOW_STACK_ENTRIES);
    expect(deep.packed.features.shallowStack).toBe(false);
    const shallowChain = prepareScene(chainScene(20));
    expect(shallowChain.bvh.stats.maxDepth).toBeLessThanOrEqual(SHALLOW_STACK_ENTRIES);
    expect(shallowChain.packed.features.shallowStack).toBe(true);
  });
});
