/** `lantern render <scene>`: a progressive render to PNG and/or EXR, with a progress bar. */
import { SingleBar } from 'cli-progress';
import type { Command } from 'commander';
import { renderProgressive } from '../../renderer/progressive.ts';
import {
  DEBUG_LAYOUTS, DEBUG_VIEWS, DEFAULT_SETTINGS, DENOISE_VIEWS, LIGHT_SAMPLING, MAX_WIREFRAME_DEPTH, TONE_MAPPERS,
  type DebugLayout, type DebugView, type LightSampling, type ToneMapper,
} from '../../renderer/settings.ts';
import { cameraFromOptions } from '../camera-option.ts';
import { choiceOption, integerOption, numberListOption, numberOption, withImageOptions, withSceneOptions } from '../options.ts';
import { writeDebugExr, writeExr, writePng } from '../output-files.ts';
import { sceneHelp } from '../scene-source.ts';
import { openSession } from '../session.ts';
import type { CliContext } from '../context.ts';
import { historyCapOption, isFrameMode, renderFrames, type FrameModeOptions } from './render-frames.ts';

interface RenderOptions extends FrameModeOptions {
  width: number;
  height: number;
  spp: number;
  bounces: number;
  seed: number;
  out?: string;
  exr?: string;
  exposure: number;
  tonemap: ToneMapper;
  lightSampling: LightSampling;
  camera?: number[];
  fov?: number;
  torch: 'on' | 'off';
  torchIntensity?: number;
  torchRange?: number;
  torchColor?: number[];
  lightTable?: string;
  json?: boolean;
  debug?: Exclude<DebugView, 'none'>;
  debugLayout: DebugLayout;
  wireframeDepth: number;
  heatMax: number | 'auto';
}

const SHOWN_DEBUG_VIEWS = DEBUG_VIEWS.filter((v): v is Exclude<DebugView, 'none'> => v !== 'none');

function heatMaxOption(value: string): number | 'auto' {
  return value === 'auto' ? 'auto' : numberOption('--heat-max', 1e-6, 1e12)(value);
}

export function registerRender(program: Command, context: CliContext): void {
  const command = program
    .command('render')
    .description('render a scene to a PNG (tone-mapped sRGB) and/or an EXR (linear radiance)')
    .argument('<scene>', sceneHelp());
  withSceneOptions(withImageOptions(command, { width: 512, height: 512 }))
    .option('-s, --spp <samples>', 'samples per pixel', integerOption('--spp', 1, 1_000_000), 64)
    .option('--seed <n>', 'random seed (same seed, same image)', integerOption('--seed', 0, 0xffffffff), DEFAULT_SETTINGS.seed)
    .option('-o, --out <file.png>', 'write the tone-mapped image as PNG (default: <scene>.png when no --exr is given)')
    .option('--exr <file.exr>', 'write the linear radiance estimate as OpenEXR (float32 RGB)')
    .option('--exposure <stops>', 'exposure in stops (PNG only)', numberOption('--exposure', -64, 64), DEFAULT_SETTINGS.exposureStops)
    .option('--tonemap <curve>', `tone curve: ${TONE_MAPPERS.join(', ')} (PNG only)`, choiceOption('--tonemap', TONE_MAPPERS), DEFAULT_SETTINGS.toneMapper)
    .option('--light-sampling <strategy>', `${LIGHT_SAMPLING.join(', ')}: BSDF sampling only, or next-event estimation with MIS`, choiceOption('--light-sampling', LIGHT_SAMPLING), DEFAULT_SETTINGS.lightSampling)
    .option('--camera <px,py,pz,tx,ty,tz>', 'camera position and look-at target in scene coordinates (Doom maps: x, height, -y)', numberListOption('--camera', [6]))
    .option('--fov <degrees>', 'vertical field of view', numberOption('--fov', 1, 179))
    .option('--torch <on|off>', 'the light carried at the camera (on by default where the scene has one, as Doom maps do)', choiceOption('--torch', ['on', 'off'] as const), 'on')
    .option('--torch-intensity <W/sr>', 'torch intensity (with --torch-range, gives any scene a torch)', numberOption('--torch-intensity', 0, 1e12))
    .option('--torch-range <distance>', 'distance at which the torch fades out', numberOption('--torch-range', 1e-6, 1e12))
    .option('--torch-color <r,g,b>', 'torch colour, linear RGB', numberListOption('--torch-color', [3]))
    .option('--debug <view>', `show a debug view: ${SHOWN_DEBUG_VIEWS.join(', ')} (from pixel-centre primary rays; the EXR then holds its raw values)`, choiceOption('--debug', SHOWN_DEBUG_VIEWS))
    .option('--debug-layout <layout>', `${DEBUG_LAYOUTS.join(', ')}: the debug view instead of the image (no path tracing), beside it, or over it`, choiceOption('--debug-layout', DEBUG_LAYOUTS), DEFAULT_SETTINGS.debugLayout)
    .option('--wireframe-depth <d>', 'wireframe view: the BVH depth whose boxes are drawn (0 = the scene bounds)', integerOption('--wireframe-depth', 0, MAX_WIREFRAME_DEPTH), DEFAULT_SETTINGS.wireframeDepth)
    .option('--heat-max <n|auto>', "heat views: the count at the top of the colour scale ('auto': the image's maximum)", heatMaxOption, DEFAULT_SETTINGS.heatMax)
    .option('--json', 'print what was done as JSON')
    .option('--temporal', 'frame mode: accumulate over frames with reprojection (temporal denoising)')
    .option('--denoise', 'frame mode: the edge-aware spatial (à-trous) filter')
    .option('--frames <n>', 'frame mode: frames to render, --spp samples each; with more than one, --out and --exr name folders', integerOption('--frames', 1, 100_000))
    .option('--path <path.json>', 'frame mode: a camera path (keyframes of position, target, fov over time; see the README)')
    .option('--history-cap <n|unlimited>', 'frame mode: longest temporal history in frames', historyCapOption)
    .option('--clamp-k <k>', 'frame mode: history clamp to mean ± k·σ of the 3×3 neighbourhood (0: off)', numberOption('--clamp-k', 0, 16))
    .option('--denoise-view <view>', `frame mode: ${DENOISE_VIEWS.join(', ')}`, choiceOption('--denoise-view', DENOISE_VIEWS))
    .action((sceneArg: string, options: RenderOptions) => context.run(() => render(sceneArg, options, context)));
}

async function render(sceneArg: string, o: RenderOptions, context: CliContext): Promise<void> {
  // A sequence of frames writes only what was asked for.
  const sequence = isFrameMode(o) && ((o.frames ?? 1) > 1 || o.path !== undefined);
  const png = o.out ?? (o.exr || sequence ? undefined : `${sceneArg.replace(/[^A-Za-z0-9_-]+/g, '_')}.png`);
  const { renderer, prepared, loadMs } = await openSession(sceneArg, context.note, o.lightTable);
  await renderer.resize(o.width, o.height);
  renderer.setCamera(cameraFromOptions(prepared.scene.camera, o.camera, o.fov));
  renderer.updateSettings({
    maxBounces: o.bounces,
    seed: o.seed,
    exposureStops: o.exposure,
    toneMapper: o.tonemap,
    lightSampling: o.lightSampling,
    torch: {
      enabled: o.torch === 'on',
      ...(o.torchIntensity !== undefined ? { intensity: o.torchIntensity } : {}),
      ...(o.torchRange !== undefined ? { range: o.torchRange } : {}),
      ...(o.torchColor ? { color: [o.torchColor[0]!, o.torchColor[1]!, o.torchColor[2]!] as const } : {}),
    },
    debugView: o.debug ?? 'none',
    debugLayout: o.debugLayout,
    wireframeDepth: o.wireframeDepth,
    heatMax: o.heatMax,
  });
  // A debug view that replaces the image needs no path tracing.
  const spp = o.debug && o.debugLayout === 'replace' ? 0 : o.spp;

  if (isFrameMode(o)) {
    const camera = renderer.camera!;
    const result = await renderFrames(renderer, camera, o.spp, o, { ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}) });
    const report = { scene: prepared.scene.name, width: o.width, height: o.height, sppPerFrame: o.spp, bounces: o.bounces, temporal: Boolean(o.temporal), denoise: Boolean(o.denoise), adapter: renderer.gpu.adapterName, ...result };
    const gpu = result.gpuMs ? `; GPU ms per frame: ${Object.entries(result.gpuMs).map(([k, v]) => `${k} ${v.toFixed(3)}`).join(', ')}` : '';
    context.print(o.json ? JSON.stringify(report, null, 2) : `${report.scene}: ${result.frames} frames of ${o.width}×${o.height} at ${o.spp} spp in ${result.seconds.toFixed(2)} s on ${report.adapter}${gpu}`);
    renderer.destroy();
    return;
  }
  const bar = !o.json && process.stderr.isTTY ? new SingleBar({ format: 'rendering [{bar}] {value}/{total} spp | {eta_formatted} left', hideCursor: true, stream: process.stderr }) : undefined;
  bar?.start(spp, 0);
  const { seconds } = await renderProgressive(renderer, { spp, onProgress: (done) => bar?.update(done) });
  bar?.stop();

  const rays = await renderer.readRayCounts();
  if (png) await writePng(renderer, png);
  if (o.exr) await (o.debug ? writeDebugExr(renderer, o.exr) : writeExr(renderer, o.exr));
  const legend = o.debug ? await renderer.debugLegend() : undefined;
  const total = rays.extension + rays.shadow;
  const report = {
    scene: prepared.scene.name,
    width: o.width,
    height: o.height,
    spp: renderer.sampleCount,
    bounces: o.bounces,
    seed: o.seed,
    lightSampling: o.lightSampling,
    adapter: renderer.gpu.adapterName,
    triangles: prepared.triangles.count,
    loadSeconds: loadMs / 1000,
    seconds,
    rays: { extension: rays.extension, shadow: rays.shadow, total },
    raysPerSecond: seconds > 0 ? total / seconds : 0,
    ...(legend ? { debug: { view: legend.view, layout: o.debugLayout, label: legend.label, ...(legend.scale ? { scale: { min: legend.scale.min, max: legend.scale.max, auto: legend.scale.auto } } : {}) } } : {}),
    outputs: { ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}) },
  };
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
  } else {
    const files = [png, o.exr].filter(Boolean).join(' and ');
    if (legend) {
      const range = legend.scale ? ` (colour scale ${legend.scale.min} to ${legend.scale.max}${legend.scale.auto ? ', the image maximum' : ''})` : '';
      context.print(`debug view ${legend.view}, ${o.debugLayout}: ${legend.label}${range}`);
    }
    context.print(
      `${report.scene}: ${o.width}×${o.height}, ${report.spp} spp, ${o.bounces} bounces in ${seconds.toFixed(2)} s on ${report.adapter} ` +
        `(${(report.raysPerSecond / 1e6).toFixed(1)} Mrays/s) -> ${files}`,
    );
  }
  renderer.destroy();
}
