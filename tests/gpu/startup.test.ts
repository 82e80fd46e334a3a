/**
 * Start-up laziness (issue #14, time to first image): a renderer told the scene's features compiles
 * the path tracer for that scene alone, with that scene's override constants, and no kernel the
 * render does not run; kernels left out (the denoiser's) are still made when first asked for.
 * The stage log (gpu/stage-log.ts) says what was compiled.
 */
import { afterEach, describe, expect, it } from 'vitest';
import { PLAIN_SCENE, TRACING_FEATURES } from '../../src/gpu/kernel.ts';
import { FEATURE_CONSTANTS, featureValue } from '../../src/gpu/kernel-variants.ts';
import type { SceneFeatures } from '../../src/gpu/pack/scene-pack.ts';
import { observeStages, type StageSpan } from '../../src/gpu/stage-log.ts';
import { builtinScene } from '../../src/loaders/builtin/index.ts';
import { prepareScene } from '../../src/renderer/prepare.ts';
import { Renderer } from '../../src/renderer/renderer.ts';
import { testGpu } from './gpu-context.ts';
import { resolveSampler, SAMPLERS } from '../../src/passes/variants.ts';

const PATH_TRACE_PIPELINE = 'pipeline passes/path-trace:path_trace';

/** Every stage reported for the test device from now on (until afterEach stops listening). */
async function recordStages(): Promise<StageSpan[]> {
  const spans: StageSpan[] = [];
  observeStages((await testGpu()).device, (s) => spans.push(s));
  return spans;
}

afterEach(async () => observeStages((await testGpu()).device, undefined));

const pipelines = (spans: readonly StageSpan[]) => spans.filter((s) => s.stage.startsWith('pipeline ')).map((s) => s.stage).sort();

/**
 * The override constants a scene with these features compiles with, as the stage's detail lists them,
 * and the sampler a kernel is compiled for where it has one (progressive: Sobol, SAMPLER=1; the real-time
 * path kernel: PCG, SAMPLER=0; the G-buffer pass draws no random numbers: none).
 */
const constantsOf = (f: SceneFeatures, sampler: number | null = 1) => [...TRACING_FEATURES.map((k) => `${FEATURE_CONSTANTS[k]}=${featureValue(k, f)}`), ...(sampler === null ? [] : [`SAMPLER=${sampler}`])];

describe('start-up compiles', () => {
  it('compile the path tracer for the given scene alone, and the tone mapper; nothing else', async () => {
    const spans = await recordStages();
    const gpu = await testGpu();
    // General materials, spheres and a sky: not the plain scene that a renderer without features compiles first.
    const prepared = prepareScene(builtinScene('spheres'));
    expect(prepared.packed.features.generalMaterials).toBe(true);
    const renderer = await Renderer.create(gpu, { features: Promise.resolve(prepared.packed.features) });
    try {
      await renderer.resize(8, 8);
      await renderer.setScene(prepared);
      renderer.accumulate(1);
      const { radiance } = await renderer.readAccumulation();
      expect(radiance.every(Number.isFinite)).toBe(true);
      expect(radiance.some((v) => v > 0)).toBe(true);
      await renderer.readImage();
      expect(pipelines(spans)).toEqual([PATH_TRACE_PIPELINE, 'pipeline passes/tonemap:tonemap_image']);
      const detail = spans.find((s) => s.stage === PATH_TRACE_PIPELINE)!.detail!.split(' ');
      expect(detail).toEqual(expect.arrayContaining(constantsOf(prepared.packed.features)));
      expect(spans.some((s) => s.stage === 'upload scene')).toBe(true);
      for (const s of spans) expect(s.endMs).toBeGreaterThanOrEqual(s.startMs);
    } finally {
      renderer.destroy();
    }
  });

  it('leave the denoiser out until it is asked for: a denoised frame after a progressive render works', async () => {
    const spans = await recordStages();
    const gpu = await testGpu();
    const prepared = prepareScene(builtinScene('cornell'));
    const renderer = await Renderer.create(gpu, { features: prepared.packed.features });
    try {
      await renderer.resize(8, 8);
      await renderer.setScene(prepared);
      renderer.accumulate(1);
      await renderer.readAccumulation();
      expect(pipelines(spans).filter((p) => p !== PATH_TRACE_PIPELINE && !p.includes('tonemap'))).toEqual([]);
      await renderer.compile({}, { frames: true });
      renderer.renderFrame(1);
      const frame = await renderer.readFrame();
      expect(frame.radiance.every(Number.isFinite)).toBe(true);
      expect(frame.radiance.some((v) => v > 0)).toBe(true);
      expect(pipelines(spans).some((p) => p.endsWith(':path_trace_frame'))).toBe(true);
    } finally {
      renderer.destroy();
    }
  });

  it('made without the progressive path tracer (the CLI), compile it only for a progressive render, for the sampler setting (issue #29)', async () => {
    const spans = await recordStages();
    const gpu = await testGpu();
    const prepared = prepareScene(builtinScene('cornell'));
    const renderer = await Renderer.create(gpu, { features: prepared.packed.features, progressive: false });
    try {
      await renderer.resize(8, 8);
      await renderer.setScene(prepared);
      // A debug view that replaces the image, and a ray benchmark, trace no paths (the real-time chain's switches off, as the CLI's are).
      renderer.updateSettings({ temporal: false, denoise: false, debugView: 'heat-nodes', debugLayout: 'replace' });
      await renderer.compile();
      await renderer.compile({ debugView: 'none' }, { accumulate: false });
      expect(pipelines(spans).filter((p) => p === PATH_TRACE_PIPELINE)).toEqual([]);
      renderer.updateSettings({ debugView: 'none', sampler: 'random' });
      expect(() => renderer.accumulate(1)).toThrow(/compile\(\) the progressive recipe before accumulate\(\)/);
      await renderer.compile();
      renderer.accumulate(1);
      expect((await renderer.readAccumulation()).radiance.some((v) => v > 0)).toBe(true);
      const compiled = spans.filter((s) => s.stage === PATH_TRACE_PIPELINE);
      expect(compiled).toHaveLength(1);
      expect(compiled[0]!.detail!.split(' ')).toEqual(expect.arrayContaining(constantsOf(prepared.packed.features, SAMPLERS.indexOf('random'))));
    } finally {
      renderer.destroy();
    }
  });

  it('compile a recipe enabled before or after the scene for that scene alone, not a plain scene first (issue #27)', async () => {
    const gpu = await testGpu();
    // Not the plain scene (general materials), so that a plain variant compiled first would show.
    const prepared = prepareScene(builtinScene('materials'));
    expect(prepared.packed.features).not.toEqual(PLAIN_SCENE);
    const frameKernels = (spans: readonly StageSpan[]) => spans.filter((s) => /^pipeline .*:(path_trace_frame|frame_gbuffer)$/.test(s.stage));
    // The page's order: the renderer told the scene's features, the real-time chain enabled, then the scene set.
    for (const order of ['recipe first', 'scene first'] as const) {
      const spans = await recordStages();
      const renderer = await Renderer.create(gpu, { features: prepared.packed.features });
      try {
        await renderer.resize(8, 8);
        if (order === 'scene first') await renderer.setScene(prepared);
        await renderer.compile({}, { frames: true });
        if (order === 'recipe first') await renderer.setScene(prepared);
        renderer.renderFrame(1);
        expect((await renderer.readFrame()).radiance.some((v) => v > 0)).toBe(true);
        const compiled = frameKernels(spans);
        expect(compiled.map((s) => s.stage).sort(), order).toEqual(['pipeline passes/path-trace-frame:frame_gbuffer', 'pipeline passes/path-trace-frame:path_trace_frame']);
        for (const s of compiled) {
          const sampler = s.stage.endsWith(':path_trace_frame') ? SAMPLERS.indexOf(resolveSampler('auto', 'real-time')) : null;
          expect(s.detail!.split(' '), `${order}: ${s.stage}`).toEqual(expect.arrayContaining(constantsOf(prepared.packed.features, sampler)));
          if (sampler === null) expect(s.detail, s.stage).not.toMatch(/SAMPLER=/);
        }
      } finally {
        renderer.destroy();
        observeStages(gpu.device, undefined);
      }
    }
  });

  it('compile ReSTIR enabled before the scene for the features the renderer was told, not a plain scene\'s beside them (issue #29)', async () => {
    const spans = await recordStages();
    const gpu = await testGpu();
    const prepared = prepareScene(builtinScene('materials'));
    expect(prepared.packed.features).not.toEqual(PLAIN_SCENE);
    const renderer = await Renderer.create(gpu, { features: prepared.packed.features });
    try {
      await renderer.compile({ restir: true }, { frames: true });
      await renderer.setScene(prepared);
      const restir = spans.filter((s) => s.stage.startsWith('pipeline restir/restir:'));
      expect(restir.map((s) => s.stage).sort()).toEqual(['restir_initial', 'restir_lend', 'restir_spatial', 'restir_temporal'].map((e) => `pipeline restir/restir:${e}`));
      for (const s of restir) expect(s.detail!.split(' '), s.stage).toEqual(expect.arrayContaining(constantsOf(prepared.packed.features, null)));
    } finally {
      renderer.destroy();
    }
  });

  it('compile ReSTIR enabled after two scenes for the scene set now, not for every scene traced before (issue #29)', async () => {
    const gpu = await testGpu();
    const cornell = prepareScene(builtinScene('cornell'));
    const materials = prepareScene(builtinScene('materials'));
    expect(materials.packed.features).not.toEqual(cornell.packed.features);
    const renderer = await Renderer.create(gpu, { features: cornell.packed.features });
    try {
      await renderer.resize(8, 8);
      await renderer.compile({}, { frames: true });
      await renderer.setScene(cornell);
      await renderer.setScene(materials);
      const spans = await recordStages();
      renderer.updateSettings({ restir: true });
      await renderer.compile({ restir: true }, { frames: true });
      const restir = spans.filter((s) => s.stage.startsWith('pipeline restir/restir:'));
      expect(restir).toHaveLength(4);
      for (const s of restir) expect(s.detail!.split(' '), s.stage).toEqual(expect.arrayContaining(constantsOf(materials.packed.features, null)));
      // The Cornell box set again gets its own when it is set.
      await renderer.setScene(cornell);
      expect(spans.filter((s) => s.stage.startsWith('pipeline restir/restir:'))).toHaveLength(8);
    } finally {
      renderer.destroy();
    }
  });

  it('compile the frame kernels for the sampler set before the recipe, not the default\'s first (issue #29)', async () => {
    const spans = await recordStages();
    const gpu = await testGpu();
    const prepared = prepareScene(builtinScene('cornell'));
    const renderer = await Renderer.create(gpu, { features: prepared.packed.features });
    try {
      await renderer.resize(8, 8);
      // Not the real-time chain's default (PCG), whose kernels the renderer used to compile and then switch from.
      expect(resolveSampler('auto', 'real-time')).not.toBe('sobol');
      renderer.updateSettings({ sampler: 'sobol' });
      await renderer.compile({}, { frames: true });
      await renderer.setScene(prepared);
      await renderer.accelSettled();
      renderer.renderFrame(1);
      expect((await renderer.readFrame()).radiance.some((v) => v > 0)).toBe(true);
      const compiled = spans.filter((s) => s.stage === 'pipeline passes/path-trace-frame:path_trace_frame');
      expect(compiled.map((s) => s.detail!.split(' ').filter((c) => c.startsWith('SAMPLER=')))).toEqual([[`SAMPLER=${SAMPLERS.indexOf('sobol')}`]]);
    } finally {
      renderer.destroy();
    }
  });
});
