/**
 * The debug views through the Renderer facade against independent CPU answers: the heat map's
 * counts against the CPU oracle (bvh/traverse.ts) ray for ray, leaf size, leaf depth and triangle id
 * against the oracle's hit, the wireframe's drawn pixels against a CPU projection of the boxes'
 * edges, the teaching scene's hot and cool regions, and the layouts' composition.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { nodeDepths, nodesAtDepth } from '../../src/bvh/depths.ts';
import { traceClosest } from '../../src/bvh/traverse.ts';
import type { Bvh } from '../../src/bvh/types.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import type { Vec3 } from '../../src/math/vec3.ts';
import { prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import type { CameraBasis } from '../../src/gpu/view.ts';
import { cameraRay, expectCountsMatchOracle, f32Basis } from './accel-rays.ts';
import { testGpu } from './gpu-context.ts';

const W = 64, H = 48;

let renderer: Renderer;
let teaching: PreparedScene;

beforeAll(async () => {
  renderer = await Renderer.create(await testGpu());
  teaching = prepareScene(builtinScene('bvh-teaching'));
  await renderer.setScene(teaching);
  await renderer.resize(W, H);
});

afterAll(() => renderer.destroy());

/** The leaf holding leaf-order triangle `leafIndex`. */
function leafOf(bvh: Bvh, leafIndex: number): number {
  for (let node = 0; node < bvh.nodeCount; node++) {
    const count = bvh.triCount[node]!, first = bvh.leftFirst[node]!;
    if (count > 0 && leafIndex >= first && leafIndex < first + count) return node;
  }
  throw new Error(`no leaf holds ${leafIndex}`);
}

async function debugValues(settings: Parameters<Renderer['updateSettings']>[0]): Promise<Float32Array> {
  renderer.updateSettings({ debugLayout: 'replace', ...settings });
  return renderer.readDebugValues();
}

describe('heat map', () => {
  it('counts exactly the nodes and triangles the CPU oracle counts for each pixel-centre ray', async () => {
    const nodes = await debugValues({ debugView: 'heat-nodes' });
    const triangles = await debugValues({ debugView: 'heat-triangles' });
    const b = f32Basis(teaching, W / H);
    const { bvh, triangles: list } = teaching;
    for (let i = 0; i < W * H; i++) expect([nodes[i * 4 + 1], triangles[i * 4 + 1]]).toEqual([triangles[i * 4], nodes[i * 4]]);
    // The GPU builds the ray and runs the slab tests in f32 (and may fuse operations), the oracle
    // in f64: where turning the ray by a hundredth of a pixel changes the CPU's count, the ray
    // grazes a box or a triangle edge and either count is right.
    expectCountsMatchOracle(
      W,
      H,
      (i) => `${nodes[i * 4]},${triangles[i * 4]}`,
      (px, py, dx, dy) => traceClosest(bvh, list.positions, cameraRay(b, W, H, px, py, dx, dy)),
      0.02,
    );
    // Not a trivially uniform image: the counts spread.
    const distinct = new Set(Array.from({ length: W * H }, (_, i) => nodes[i * 4]!));
    expect(distinct.size).toBeGreaterThan(10);
  });

  it('leaf size, leaf depth and triangle id are those of the leaf and triangle the oracle hits', async () => {
    const size = await debugValues({ debugView: 'leaf-size' });
    const depth = await debugValues({ debugView: 'bvh-depth' });
    const id = await debugValues({ debugView: 'triangle-id' });
    const b = f32Basis(teaching, W / H);
    const { bvh } = teaching;
    const depths = nodeDepths(bvh);
    let compared = 0;
    const failures: string[] = [];
    for (let i = 0; i < W * H; i++) {
      const hit = traceClosest(bvh, teaching.triangles.positions, cameraRay(b, W, H, (i % W) + 0.5, Math.floor(i / W) + 0.5)).hit;
      if (!hit) {
        if (id[i * 4] !== -1 || size[i * 4 + 3] !== 0) failures.push(`pixel ${i}: the oracle misses, the gpu hits`);
        continue;
      }
      if (id[i * 4] !== hit.triangle) continue; // a tie between two triangles on a shared edge
      const leaf = leafOf(bvh, hit.leafIndex);
      compared++;
      if (size[i * 4] !== bvh.triCount[leaf] || depth[i * 4] !== depths[leaf]) failures.push(`pixel ${i}: gpu ${size[i * 4]}/${depth[i * 4]}, cpu ${bvh.triCount[leaf]}/${depths[leaf]}`);
    }
    expect(failures.slice(0, 10)).toEqual([]);
    expect(compared).toBeGreaterThan(0.7 * W * H);
  });

  it('is hotter over the dense cluster and the slab than over the separated cubes (bvh-teaching)', async () => {
    const heat = await debugValues({ debugView: 'heat-nodes' });
    const id = await debugValues({ debugView: 'triangle-id' });
    const mesh = teaching.scene.meshes[0]!;
    const sums = new Map<string, { sum: number; n: number }>();
    for (let i = 0; i < W * H; i++) {
      if (id[i * 4 + 3] === 0) continue;
      const group = teaching.scene.materials[mesh.materialIds[id[i * 4]!]!]!.name;
      const s = sums.get(group) ?? { sum: 0, n: 0 };
      s.sum += heat[i * 4]!;
      s.n++;
      sums.set(group, s);
    }
    const mean = (g: string) => {
      const s = sums.get(g);
      expect(s?.n ?? 0, `pixels showing '${g}'`).toBeGreaterThan(20);
      return s!.sum / s!.n;
    };
    const separated = mean('separated');
    expect(mean('cluster')).toBeGreaterThan(1.2 * separated);
    expect(mean('slab')).toBeGreaterThan(1.2 * separated);
    renderer.updateSettings({ debugView: 'heat-nodes' });
    const legend = await renderer.debugLegend();
    expect(legend.scale).toMatchObject({ min: 0, auto: true, max: Math.max(...Array.from({ length: W * H }, (_, i) => heat[i * 4]!)) });
  });
});

/** Pixel coordinates (centre-based, x right, y down) of a world point, or undefined behind the near plane. */
function project(b: CameraBasis, p: Vec3): { x: number; y: number; z: number } {
  const q = [p[0] - b.position[0], p[1] - b.position[1], p[2] - b.position[2]];
  const dot = (a: readonly number[], c: readonly number[]) => a[0]! * c[0]! + a[1]! * c[1]! + a[2]! * c[2]!;
  const z = dot(q, b.forward);
  const nx = dot(q, b.right) / dot(b.right, b.right) / z, ny = dot(q, b.up) / dot(b.up, b.up) / z;
  return { x: ((nx + 1) / 2) * W, y: ((1 - ny) / 2) * H, z };
}

type Segment = { ax: number; ay: number; bx: number; by: number; leaf: boolean };

/** The 12 edges of each box, clipped to z > near and projected to the image. */
function projectedEdges(b: CameraBasis, boxes: { min: Vec3; max: Vec3; leaf: boolean }[]): Segment[] {
  const out: Segment[] = [];
  for (const box of boxes) {
    const corner = (i: number): Vec3 => [i & 1 ? box.max[0] : box.min[0], i & 2 ? box.max[1] : box.min[1], i & 4 ? box.max[2] : box.min[2]];
    for (let i = 0; i < 8; i++) {
      for (const bit of [1, 2, 4]) {
        if (i & bit) continue;
        let p = corner(i), q = corner(i | bit);
        const near = 1e-3;
        const zp = project(b, p).z, zq = project(b, q).z;
        if (zp < near && zq < near) continue;
        const lerp = (t: number): Vec3 => [p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t, p[2] + (q[2] - p[2]) * t];
        if (zp < near) p = lerp((near - zp) / (zq - zp));
        else if (zq < near) q = lerp((near - zp) / (zq - zp));
        const a = project(b, p), c = project(b, q);
        out.push({ ax: a.x, ay: a.y, bx: c.x, by: c.y, leaf: box.leaf });
      }
    }
  }
  return out;
}

function distanceToSegment(px: number, py: number, s: Segment): number {
  const dx = s.bx - s.ax, dy = s.by - s.ay;
  const len2 = dx * dx + dy * dy;
  const t = len2 > 0 ? Math.min(1, Math.max(0, ((px - s.ax) * dx + (py - s.ay) * dy) / len2)) : 0;
  return Math.hypot(px - s.ax - t * dx, py - s.ay - t * dy);
}

async function wireframePixels(depth: number): Promise<{ line: boolean[]; leaf: boolean[] }> {
  renderer.updateSettings({ debugView: 'wireframe', debugLayout: 'replace', wireframeDepth: depth });
  const rgba = await renderer.readImage();
  // The backdrop is grey (r = g = b); interior lines are amber (r > b), leaf lines cyan (b > r).
  const line = Array.from({ length: W * H }, (_, i) => rgba[i * 4] !== rgba[i * 4 + 2]);
  const leaf = Array.from({ length: W * H }, (_, i) => rgba[i * 4 + 2]! > rgba[i * 4]!);
  return { line, leaf };
}

/** Every drawn pixel lies on an edge of the expected boxes, and every edge is drawn. */
function expectDrawnExactly(drawn: { line: boolean[]; leaf: boolean[] }, edges: Segment[]): void {
  const stray: string[] = [];
  for (let i = 0; i < W * H; i++) {
    if (!drawn.line[i]) continue;
    const px = (i % W) + 0.5, py = Math.floor(i / W) + 0.5;
    const near = edges.filter((s) => distanceToSegment(px, py, s) < 1.5);
    if (near.length === 0) stray.push(`(${i % W}, ${Math.floor(i / W)}) is on no edge`);
    else if (!near.some((s) => s.leaf === drawn.leaf[i])) stray.push(`(${i % W}, ${Math.floor(i / W)}) has the wrong colour`);
  }
  expect(stray.slice(0, 10)).toEqual([]);
  const missing: string[] = [];
  for (const s of edges) {
    const steps = Math.ceil(Math.hypot(s.bx - s.ax, s.by - s.ay) * 4);
    for (let k = 0; k <= steps; k++) {
      const x = s.ax + ((s.bx - s.ax) * k) / Math.max(steps, 1), y = s.ay + ((s.by - s.ay) * k) / Math.max(steps, 1);
      if (x < 1 || y < 1 || x > W - 1 || y > H - 1) continue;
      const cx = Math.floor(x), cy = Math.floor(y);
      let found = false;
      for (let dy = -1; dy <= 1 && !found; dy++) for (let dx = -1; dx <= 1 && !found; dx++) found = drawn.line[(cy + dy) * W + cx + dx] === true;
      if (!found) missing.push(`(${x.toFixed(1)}, ${y.toFixed(1)})`);
    }
  }
  expect(missing.slice(0, 10)).toEqual([]);
}

describe('wireframe', () => {
  it('at depth 0 draws exactly the scene bounds', async () => {
    const p = teaching.triangles.positions;
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < p.length; i++) {
      min[i % 3] = Math.min(min[i % 3]!, p[i]!);
      max[i % 3] = Math.max(max[i % 3]!, p[i]!);
    }
    const edges = projectedEdges(f32Basis(teaching, W / H), [{ min: min as unknown as Vec3, max: max as unknown as Vec3, leaf: false }]);
    const drawn = await wireframePixels(0);
    expect(drawn.line.filter(Boolean).length).toBeGreaterThan(W);
    expectDrawnExactly(drawn, edges);
  });

  it('at depth d draws every node of depth d, leaves in their own colour', async () => {
    const { bvh } = teaching;
    const depths = nodeDepths(bvh);
    // The shallowest depth with both leaves and interior nodes, so both colours are checked.
    let d = 1;
    const leavesAt = (k: number) => Array.from(nodesAtDepth(depths, k)).filter((n) => bvh.triCount[n]! > 0).length;
    while (leavesAt(d) === 0 || leavesAt(d) === nodesAtDepth(depths, d).length) d++;
    const boxes = Array.from(nodesAtDepth(depths, d), (n) => ({
      min: [bvh.bounds[n * 6]!, bvh.bounds[n * 6 + 1]!, bvh.bounds[n * 6 + 2]!] as Vec3,
      max: [bvh.bounds[n * 6 + 3]!, bvh.bounds[n * 6 + 4]!, bvh.bounds[n * 6 + 5]!] as Vec3,
      leaf: bvh.triCount[n]! > 0,
    }));
    const drawn = await wireframePixels(d);
    expect(drawn.leaf.some(Boolean)).toBe(true);
    expectDrawnExactly(drawn, projectedEdges(f32Basis(teaching, W / H), boxes));
    // A different depth draws a different picture.
    const other = await wireframePixels(d + 1);
    expect(other.line.filter((l, i) => l !== drawn.line[i]).length).toBeGreaterThan(W);
  });
});

describe('layouts', () => {
  it('replace shows the view, overlay blends it over the image, side-by-side shows both at half size', async () => {
    renderer.updateSettings({ debugView: 'none' });
    renderer.accumulate(1);
    const image = await renderer.readImage();
    renderer.updateSettings({ debugView: 'normals', debugLayout: 'replace' });
    const view = await renderer.readImage();
    renderer.updateSettings({ debugLayout: 'overlay' });
    const overlay = await renderer.readImage();
    renderer.updateSettings({ debugLayout: 'side-by-side' });
    const sides = await renderer.readImage();
    const px = (img: Uint8Array, x: number, y: number, c: number) => img[(y * W + x) * 4 + c]!;
    const normals = await renderer.readDebugValues();
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const hit = normals[(y * W + x) * 4 + 3] === 1;
        for (let c = 0; c < 3; c++) {
          const expected = hit ? 0.4 * px(image, x, y, c) + 0.6 * px(view, x, y, c) : px(image, x, y, c);
          expect(Math.abs(px(overlay, x, y, c) - expected)).toBeLessThanOrEqual(1.5);
        }
      }
    }
    // Side by side: each pane is the whole frame halved (2×2 averages), centred vertically.
    const top = (H - H / 2) / 2;
    for (const [pane, source] of [[0, image], [1, view]] as const) {
      for (const [lx, ly] of [[5, 3], [20, 12], [31, 23]] as const) {
        for (let c = 0; c < 3; c++) {
          const mean = (px(source, 2 * lx, 2 * ly, c) + px(source, 2 * lx + 1, 2 * ly, c) + px(source, 2 * lx, 2 * ly + 1, c) + px(source, 2 * lx + 1, 2 * ly + 1, c)) / 4;
          expect(Math.abs(px(sides, pane * (W / 2) + lx, top + ly, c) - mean)).toBeLessThanOrEqual(1.5);
        }
      }
    }
    expect(px(sides, 10, 2, 0) + px(sides, 10, 2, 1) + px(sides, 10, 2, 2)).toBe(0);
  });
});
