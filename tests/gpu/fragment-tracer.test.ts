/**
 * The fragment tracer (issue #30; docs/fragment-tracer.md) on WebGPU: the scene's records read back
 * through scene/bindings-textures at every index, lib/bits-es300 against the built-ins, and its
 * images against the compute kernel's at equal samples (the same sampler streams), the white
 * furnace, the materials scene and a textured Doom map.
 */
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { FRAGMENT_TRACER_SUBSTITUTES } from '../../src/gpu/fragment-tracer-wgsl.ts';
import { ComputeKernel } from '../../src/gpu/kernel.ts';
import { packSceneTextures, RECORD_TEXTURES } from '../../src/gpu/pack/scene-textures.ts';
import { sceneLayouts } from '../../src/gpu/pack/scene-pack.ts';
import { readBuffer } from '../../src/gpu/readback.ts';
import { linkWgsl } from '../../src/gpu/wgsl/linker.ts';
import { reflectLinked } from '../../src/gpu/wgsl/reflect.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { furnaceRadiance } from '../../src/loaders/builtin/furnace.ts';
import { loadDoomMap } from '../../src/loaders/doom/load.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { median } from '../../src/math/median.ts';
import { FragmentTracer, uploadSceneTextures } from '../../src/renderer/fragment-tracer.ts';
import type { Accumulation } from '../../src/renderer/image-readback.ts';
import { prepareScene, type PreparedScene } from '../../src/renderer/prepare.ts';
import { DEFAULT_SETTINGS, type RenderSettings } from '../../src/renderer/settings.ts';
import { SHADER_MODULES } from '../../src/shaders/index.ts';
import { outputBuffer, runOnce, storageBuffer } from './compute.ts';
import { testGpu } from './gpu-context.ts';
import { lum, renderScene } from './scene-render.ts';

type Settings = Pick<RenderSettings, 'maxBounces' | 'lightSampling' | 'seed' | 'sampler' | 'torch' | 'spectral'>;
const settings = (s: Partial<Settings> = {}): Settings => ({ maxBounces: 8, lightSampling: 'mis', seed: 1, sampler: 'auto', torch: { ...DEFAULT_SETTINGS.torch, enabled: false }, spectral: false, ...s });

async function fragmentImage(prepared: PreparedScene, width: number, height: number, spp: number, s: Settings, perDraw = 4): Promise<Accumulation> {
  const tracer = await FragmentTracer.create((await testGpu()).device, prepared, { width, height, settings: s });
  try {
    tracer.accumulate(spp, perDraw);
    return await tracer.readAccumulation();
  } finally {
    tracer.destroy();
  }
}

const computeImage = (prepared: PreparedScene, width: number, height: number, spp: number, s: Settings) =>
  renderScene(prepared, { width, height, spp, maxBounces: s.maxBounces, lightSampling: s.lightSampling, seed: s.seed }, (r) => r.updateSettings({ sampler: s.sampler }));

/** Largest |a − b| over every channel of every pixel, relative to the image's largest value. */
function largestDifference(a: Accumulation, b: Accumulation): number {
  // Not two black images.
  expect(Math.max(...channelMeans(b))).toBeGreaterThan(1e-3);
  let worst = 0, top = 0;
  for (let i = 0; i < a.radiance.length; i++) {
    worst = Math.max(worst, Math.abs(a.radiance[i]! - b.radiance[i]!));
    top = Math.max(top, Math.abs(a.radiance[i]!));
  }
  return worst / top;
}

function channelMeans(a: Accumulation): number[] {
  const m = [0, 0, 0];
  for (let i = 0; i < a.width * a.height; i++) for (let c = 0; c < 3; c++) m[c]! += a.radiance[i * 3 + c]!;
  return m.map((v) => v / (a.width * a.height));
}

/** Median over b × b blocks of the block-mean luminance ratio a / b (blocks where b is dark skipped). */
function blockRatioMedian(a: Accumulation, b: Accumulation, block: number): number {
  const ratios: number[] = [];
  for (let by = 0; by + block <= a.height; by += block) {
    for (let bx = 0; bx + block <= a.width; bx += block) {
      let sa = 0, sb = 0;
      for (let y = by; y < by + block; y++) for (let x = bx; x < bx + block; x++) {
        sa += lum(a, y * a.width + x);
        sb += lum(b, y * a.width + x);
      }
      if (sb > 1e-3 * block * block) ratios.push(sa / sb);
    }
  }
  return median(ratios);
}

describe('the fragment tracer', () => {
  it('reads every record of the scene textures as the storage buffers hold it (the dungeon)', async () => {
    const { device } = await testGpu();
    const packed = prepareScene(builtinScene('dungeon')).packed;
    const textures = packSceneTextures(packed, { maxTextureDimension2D: device.limits.maxTextureDimension2D });
    const structs: Record<string, string> = { bvh_nodes: 'BvhNode', triangles_hot: 'TriangleHot', triangles_shading: 'TriangleShading', materials: 'Material', light_slots: 'LightSlot', texture_refs: 'TextureRef' };
    const accessors: Record<string, string> = { bvh_nodes: 'scene_bvh_node', triangles_hot: 'scene_triangle_hot', triangles_shading: 'scene_triangle_shading', materials: 'scene_material', light_slots: 'scene_light_slot', texture_refs: 'scene_texture_ref' };
    const layouts = sceneLayouts();
    const uploaded = uploadSceneTextures(device, textures);
    try {
      for (const r of RECORD_TEXTURES) {
        const stride = layouts[r.layout].stride;
        const count = packed[r.name].byteLength / stride;
        const code = `#import scene/bindings
@group(2) @binding(0) var<storage, read_write> out: array<${structs[r.name]}>;
@group(2) @binding(1) var<storage, read_write> parts: array<vec4u>;
@compute @workgroup_size(64)
fn read_back(@builtin(global_invocation_id) id: vec3u) {
  if (id.x < ${count}u) {
    out[id.x] = ${accessors[r.name]}(id.x);
    ${r.name === 'bvh_nodes' ? 'parts[2u * id.x] = scene_bvh_node_low(id.x); parts[2u * id.x + 1u] = scene_bvh_node_high(id.x);' : ''}
    ${r.name === 'triangles_hot' ? 'parts[id.x] = vec4u(scene_triangle_flags(id.x));' : ''}
    ${r.name === 'triangles_shading' ? 'parts[id.x] = vec4u(scene_triangle_material(id.x));' : ''}
  }
}`;
        const sources = new Map(SHADER_MODULES).set('test/read-back', code);
        const linked = fragmentLinked(sources);
        const kernel = await ComputeKernel.create(device, { module: reflectLinked(linked), entryPoint: 'read_back' });
        const out = outputBuffer(device, 'records', count * stride);
        const parts = storageBuffer(device, 'parts', new Uint8Array(Math.max(16, count * 32)));
        const group0 = kernel.bindGroup(0, { ...uploaded.views });
        await runOnce(device, kernel, { 0: group0, 2: kernel.bindGroup(2, { out, parts }) }, [Math.ceil(count / 64)], out);
        const got = new Uint8Array(await readBuffer(device, out));
        const want = new Uint8Array(packed[r.name]);
        // Padding bytes are never written by the shader: compare the fields' bytes.
        const fields = [...layouts[r.layout].fields.values()];
        let mismatches = 0;
        for (let i = 0; i < count; i++) for (const f of fields) for (let b = f.offset; b < f.offset + f.size; b++) if (got[i * stride + b] !== want[i * stride + b]) mismatches++;
        expect(mismatches, `${r.name}: ${count} records`).toBe(0);
        const words = new Uint32Array(await readBuffer(device, parts));
        const w = new Uint32Array(packed[r.name]);
        if (r.name === 'bvh_nodes') for (let i = 0; i < count * 8; i++) expect(words[i]).toBe(w[i]);
        const field = r.name === 'triangles_hot' ? 'flags' : r.name === 'triangles_shading' ? 'material' : undefined;
        if (field) for (let i = 0; i < count; i++) expect(words[i * 4]).toBe(w[(i * stride + layouts[r.layout].field(field).offset) / 4]);
        out.destroy();
        parts.destroy();
      }
    } finally {
      uploaded.destroy();
    }
  });

  it('does bit operations without the built-ins GLSL ES 3.00 lacks, bit for bit (lib/bits-es300)', async () => {
    const { device } = await testGpu();
    const n = 4096;
    const input = new Uint32Array(n);
    let s = 12345;
    for (let i = 0; i < n; i++) {
      s = (Math.imul(s, 747796405) + 2891336453) >>> 0;
      input[i] = i < 64 ? (i < 33 ? (i === 32 ? 0 : 1 << i) >>> 0 : (0xffffffff >>> (i - 33)) >>> 0) : s >>> (s & 15);
    }
    const code = `#import lib/bits
@group(2) @binding(0) var<storage, read> words: array<u32>;
@group(2) @binding(1) var<storage, read_write> out: array<vec4u>;
@compute @workgroup_size(64)
fn bits(@builtin(global_invocation_id) id: vec3u) {
  let x = words[id.x];
  out[id.x] = vec4u(bits_reverse(x), bits_first_trailing(x), bits_count_ones(x), (reverseBits(x) ^ bits_reverse(x)) | (firstTrailingBit(x) ^ bits_first_trailing(x)) | (countOneBits(x) ^ bits_count_ones(x)));
}`;
    const sources = new Map(SHADER_MODULES).set('test/bits', code);
    const kernel = await ComputeKernel.create(device, { module: reflectLinked(fragmentLinked(sources, 'test/bits')), entryPoint: 'bits' });
    const words = storageBuffer(device, 'words', input);
    const out = outputBuffer(device, 'out', n * 16);
    const got = new Uint32Array(await runOnce(device, kernel, { 2: kernel.bindGroup(2, { words, out }) }, [n / 64], out));
    let bad = 0;
    for (let i = 0; i < n; i++) {
      const x = input[i]!;
      let rev = 0;
      for (let b = 0; b < 32; b++) if ((x >>> b) & 1) rev |= 1 << (31 - b);
      let ones = 0;
      for (let b = 0; b < 32; b++) ones += (x >>> b) & 1;
      const trailing = x === 0 ? 0xffffffff : 31 - Math.clz32(x & -x);
      if (got[i * 4] !== rev >>> 0 || got[i * 4 + 1] !== trailing || got[i * 4 + 2] !== ones || got[i * 4 + 3] !== 0) bad++;
    }
    expect(bad).toBe(0);
    words.destroy();
    out.destroy();
  });

  for (const sampler of ['random', 'sobol'] as const) {
    it(`draws the compute kernel's samples: the Cornell box at 16 spp (${sampler})`, async () => {
      const prepared = prepareScene(builtinScene('cornell'));
      const s = settings({ sampler });
      const [fragment, compute] = [await fragmentImage(prepared, 48, 48, 16, s), await computeImage(prepared, 48, 48, 16, s)];
      const diff = largestDifference(fragment, compute);
      console.log(`cornell ${sampler}: largest difference ${diff.toExponential(2)} of the brightest value; means ${channelMeans(fragment).map((v) => v.toFixed(5))} vs ${channelMeans(compute).map((v) => v.toFixed(5))}`);
      // The same streams and the same arithmetic: equal up to the compilers' rounding (measured:
      // 1.0e-7 of the brightest value, PCG and Sobol alike).
      expect(diff).toBeLessThan(1e-5);
      const [mf, mc] = [channelMeans(fragment), channelMeans(compute)];
      for (let c = 0; c < 3; c++) expect(Math.abs(mf[c]! / mc[c]! - 1)).toBeLessThan(0.01);
      expect(Math.abs(blockRatioMedian(fragment, compute, 8) - 1)).toBeLessThan(0.03);
    });
  }

  it('converges to the white furnace', async () => {
    const prepared = prepareScene(builtinScene('furnace'));
    const image = await fragmentImage(prepared, 16, 16, 256, settings({ maxBounces: 128, seed: 7 }), 16);
    let sum = 0;
    for (let i = 0; i < 256; i++) sum += lum(image, i);
    expect(Math.abs(sum / 256 / 5 - 1)).toBeLessThan(0.01);
    const two = await fragmentImage(prepared, 8, 8, 256, settings({ maxBounces: 2, seed: 7 }), 16);
    let s2 = 0;
    for (let i = 0; i < 64; i++) s2 += lum(two, i);
    expect(Math.abs(s2 / 64 / furnaceRadiance(2) - 1)).toBeLessThan(0.01);
  });

  it('renders the materials scene as the compute kernel does (every BSDF kind, the sky)', async () => {
    const prepared = prepareScene(builtinScene('materials'));
    const s = settings();
    const [fragment, compute] = [await fragmentImage(prepared, 32, 32, 8, s), await computeImage(prepared, 32, 32, 8, s)];
    const diff = largestDifference(fragment, compute);
    console.log(`materials: largest difference ${diff.toExponential(2)}`);
    // Measured: 7.4e-8.
    expect(diff).toBeLessThan(1e-5);
  });

  const wad = '/usr/share/games/doom/freedoom1.wad';
  it.skipIf(!existsSync(wad))("renders Freedoom's E1M1 as the compute kernel does (textures, alpha masks, moving instances)", async () => {
    const scene = loadDoomMap(new WadStack([readWad(readFileSync(wad), 'freedoom1.wad')]), 'E1M1').scene;
    const prepared = prepareScene(scene);
    const s = settings({ maxBounces: 4 });
    const [fragment, compute] = [await fragmentImage(prepared, 32, 32, 4, s), await computeImage(prepared, 32, 32, 4, s)];
    const diff = largestDifference(fragment, compute);
    console.log(`E1M1: largest difference ${diff.toExponential(2)}`);
    // Measured: 0 (the same bits).
    expect(diff).toBeLessThan(1e-5);
  }, 120_000);
});

/** `entry` of `sources` linked as the fragment tracer links: the scene's records from textures, bit operations of lib/bits-es300. */
function fragmentLinked(sources: ReadonlyMap<string, string>, entry = 'test/read-back') {
  return linkWgsl(entry, sources, FRAGMENT_TRACER_SUBSTITUTES);
}
