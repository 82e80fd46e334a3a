/**
 * The WebGL2 host under a probe program (probe.wgsl), in the browser: built by
 * tests/e2e/webgl2-host.test.ts with the GLSL translation plugin (the probe translated beside the
 * backend's own programs) and driven through window.probeHost.
 */
import { reflectLinked, structLayout } from '../../../src/gpu/wgsl/reflect.ts';
import { StructArray } from '../../../src/gpu/pack/struct-array.ts';
import { translatedProgram } from '../../../src/webgl2/glsl.ts';
import { checkTexturesFit } from '../../../src/webgl2/textures.ts';
import { slot, WebGl2Renderer } from '../../../src/webgl2/webgl2-renderer.ts';
import PROBE from './probe.wgsl?raw';

const W = 4, H = 3, LAYERS = 2;

async function probeHost() {
  const canvas = document.getElementById('view') as HTMLCanvasElement;
  const renderer = await WebGl2Renderer.create(canvas);
  const layouts = reflectLinked({ entry: 'probe', code: PROBE, modules: ['probe'], lineMap: [] }).defs;
  await renderer.setTracer(translatedProgram('probe'), slot(2, 1), (struct) => structLayout(layouts, struct));
  const records = new Uint32Array(W * H * 4);
  const pages = new Uint8Array(W * H * LAYERS * 4);
  for (let y = 0; y < H; y++) {
    for (let x = 0; x < W; x++) {
      records.set([x + 10 * y, 7, 0, 0], (y * W + x) * 4);
      // Layer 1's red is 51 · x (0.2 · x); layer 0 stays 0.
      pages.set([51 * x, 0, 0, 255], ((W * H) + y * W + x) * 4);
    }
  }
  renderer.resize(W, H);
  renderer.setSceneTextures([
    { name: 'records', group: 0, binding: 1, format: 'rgba32uint', width: W, height: H, depthOrLayers: 1, data: records },
    { name: 'pages', group: 0, binding: 2, format: 'rgba8unorm', width: W, height: H, depthOrLayers: LAYERS, data: pages },
  ], 'probe');
  const params = new StructArray(structLayout(layouts, 'ProbeParams'), 1);
  params.vec3('add')(0, 0.1, 0.05, 0.01);
  params.f32Field('scale')(0, 0.02);
  params.u32Field('layer')(0, 1);
  params.u32Field('samples')(0, 1);
  const uniforms = new Map([[slot(0, 0), new Uint8Array(params.bytes)]]);
  for (let i = 0; i < 3; i++) renderer.accumulate({ uniforms, samples: 1 });
  const sums = [...renderer.readAccumulation()];
  renderer.tonemap(0, 'linear');
  const image = [...renderer.readImage()];
  renderer.present();
  const gl = renderer.gl;
  const canvasPixels = new Uint8Array(W * H * 4);
  gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, canvasPixels);
  let misfit = '';
  try {
    checkTexturesFit([{ name: 'too wide', group: 0, binding: 9, format: 'rgba32uint', width: renderer.ctx.limits.maxTextureSize + 1, height: 1, depthOrLayers: 1, data: new Uint8Array(0) }], renderer.ctx.limits, 'probe');
  } catch (e) {
    misfit = (e as Error).message;
  }
  return { sums, image, canvas: [...canvasPixels], samples: renderer.sampleCount, compiles: renderer.compiles, renderer: renderer.ctx.rendererName, parallel: renderer.ctx.parallelCompile !== null, misfit, adapter: navigator.gpu ? (await navigator.gpu.requestAdapter()) !== null : false };
}

(window as unknown as { probeHost: typeof probeHost }).probeHost = probeHost;
