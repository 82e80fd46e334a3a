/** `lantern render <scene>`: a progressive render to PNG and/or EXR, with a progress bar. */
import { SingleBar } from 'cli-progress';
import type { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { parseCameraPath, type CameraPath } from '../../scene/camera-path.ts';
import { checkUserFile, readJsonFile } from '../user-files.ts';
import { checkOutputPath } from '../output-files.ts';
import { checkSceneOptionsApply, parseSceneArgument, readLightTable, sceneLoadOptions } from '../scene-source.ts';
import { CLI_SETTINGS, settingMode, settingOption } from '../setting-options.ts';
import { renderProgressive } from '../../renderer/progressive.ts';
import { mergeSettings } from '../../renderer/settings-schema.ts';
import { centreFocusDistance } from '../../renderer/focus.ts';
import { checkImageSize } from '../../renderer/image.ts';
import type { PreparedScene } from '../../renderer/prepare.ts';
import { cameraFromOptions, withCameraOptions } from '../camera-option.ts';
import { cameraWithLens, checkLensOptions, withLensOptions, type LensOptions } from '../lens-option.ts';
import { integerOption, numberOption, pathOption, withImageOptions, withKernelOption, withSceneOptions } from '../options.ts';
import type { KernelKind } from '../../renderer/specialisation-schedule.ts';
import { writeDebugExr, writeExr, writePng } from '../output-files.ts';
import { sceneHelp } from '../scene-source.ts';
import { openSession } from '../session.ts';
import type { CliContext } from '../context.ts';
import { environmentFromOptions, withEnvironmentOptions, type EnvironmentOptions } from '../environment-option.ts';
import { settingsFromOptions, withSettingOptions } from '../setting-options.ts';
import { DEFAULT_FRAME_SPP, DEFAULT_SPP, frameIntent, frameSelection, isFrameMode, recipeOf, renderFrames, samplesPerPixel, type FrameList, type FrameModeOptions } from './render-frames.ts';
import { InvalidArgumentError } from 'commander';
import { parseFrames, parseSampleRange } from '../../farm/frames.ts';
import { encodeShard, SHARD_VERSION } from '../../farm/shard.ts';
import { writeFile } from '../output-files.ts';
import { World } from '../../world/world.ts';
import { processSpans } from '../process-clock.ts';
import { Timeline } from '../timeline.ts';
import { escapeControls } from '../terminal-text.ts';

/** The options besides the render settings (those are read by settingsFromOptions, by their schema entries). */
interface RenderOptions extends FrameModeOptions, EnvironmentOptions, LensOptions, Readonly<Record<string, unknown>> {
  width: number;
  height: number;
  spp?: number;
  out?: string;
  exr?: string;
  camera?: number[];
  fov?: number;
  time: number;
  fps: number;
  lightTable?: string;
  skill?: number;
  json?: boolean;
  timings?: boolean;
  kernel: KernelKind;
  /** --chunk: samples per dispatch, fixed. */
  chunk?: number;
  /** --samples first-last: samples [start, end) of the sequence, into --shard. */
  samples?: { start: number; end: number };
  shard?: string;
}

/**
 * An estimate given instead of traced (`lantern merge`): per-pixel sums of `samples` samples, shown
 * and written as `render` would show and write its own.
 */
export interface GivenEstimate {
  readonly sums: Float32Array;
  readonly samples: number;
  /** Called with the files written, for the merge's own report. */
  readonly done: (outputs: { png?: string; exr?: string }, adapter: string) => void;
}

/** --frames: a count (30) or a list of frames (0-29, 1-30,47), checked as it is parsed. */
function framesOption(value: string): number | FrameList {
  try {
    return /^\s*\d+\s*$/.test(value) ? parseFrames(value).length : { list: parseFrames(value) };
  } catch (e) {
    throw new InvalidArgumentError((e as Error).message);
  }
}

function sampleRangeOption(value: string): { start: number; end: number } {
  try {
    return parseSampleRange(value, '--samples');
  } catch (e) {
    throw new InvalidArgumentError((e as Error).message);
  }
}

/**
 * `render`'s own arguments as a shard records them: what follows `render` on the command line,
 * without the options that say which samples and where the outputs go (--samples, --shard, --out,
 * --exr, --json, --timings), so that every shard of one render records the same.
 */
export function shardRenderArgs(argv: readonly string[]): string[] {
  const at = argv.indexOf('render');
  const rest = at >= 0 ? argv.slice(at + 1) : [...argv];
  const valued = new Set(['--samples', '--shard', '--out', '-o', '--exr']);
  const out: string[] = [];
  for (let i = 0; i < rest.length; i++) {
    const a = rest[i]!;
    const name = a.split('=')[0]!;
    if (valued.has(name)) {
      if (!a.includes('=')) i++;
      continue;
    }
    if (a === '--json' || a === '--timings' || a === '-v' || a === '--verbose') continue;
    out.push(a);
  }
  return out;
}

/**
 * What a kept scene is kept by (session-cache.ts): the render's arguments but those that say
 * which samples or frames a chunk renders and where they go. Two chunks of one job have the same key.
 */
export function sceneKey(argv: readonly string[]): string {
  const args = shardRenderArgs(argv);
  const out: string[] = [];
  for (let i = 0; i < args.length; i++) {
    if (args[i] === '--frames') i++;
    else if (!args[i]!.startsWith('--frames=')) out.push(args[i]!);
  }
  return JSON.stringify(out);
}

export function registerRender(program: Command, context: CliContext, given?: GivenEstimate): void {
  const command = program
    .command('render')
    .description('render a scene to a PNG (tone-mapped sRGB) and/or an EXR (linear radiance)')
    .argument('<scene>', sceneHelp());
  withKernelOption(
    withLensOptions(withSettingOptions(withEnvironmentOptions(withSceneOptions(withCameraOptions(withImageOptions(command, { width: 512, height: 512 })))))),
    'generic',
    'specialised compiles kernels for this scene while rendering starts with the generic ones and switches when they are ready (the same estimate); it pays on long renders on a GPU (docs/perf.md)',
  )
    .option('-s, --spp <samples>', `samples per pixel (default ${DEFAULT_SPP}; frame mode: each frame's, default ${DEFAULT_FRAME_SPP})`, integerOption('--spp', 1, 1_000_000))
    .option('-o, --out <file.png>', 'write the tone-mapped image as PNG (default: <scene>.png when no --exr is given)', pathOption('--out'))
    .option('--exr <file.exr>', 'write the linear radiance estimate as OpenEXR (float32 RGB)', pathOption('--exr'))
    .option('--json', 'print what was done as JSON')
    .option('--timings', 'report where the time went from process start to the written image (stderr; with --json, as "timeline")')
    .option('--frames <n|list>', 'frame mode: a count of frames (30: frames 0-29), or frames of the whole sequence (0-29, 1-30,47, 0-238:2; numbered from 0 as the files are, each the same as in the whole sequence), --spp samples each; with more than one frame or a list, --out and --exr name folders', framesOption)
    .option('--path-frames <n>', 'frame mode with --path and a list of --frames: how many frames the whole path is cut into (default 30)', integerOption('--path-frames', 1, 100_000))
    .option('--chunk <samples>', 'samples per dispatch, fixed (only the bands adapt to timing): the image then equals a farm job\'s shards of this chunk size merged, bit for bit (docs/farm.md)', integerOption('--chunk', 1, 1_000_000))
    .option('--samples <first-last>', 'render samples first to last of the one --spp sequence (their random streams are those samples\' in a whole render) in one dispatch, into --shard', sampleRangeOption)
    .option('--shard <file.shard>', 'with --samples: write the per-pixel sums and the sample range (not means) for `lantern merge`', pathOption('--shard'))
    .option('--path <path.json>', 'frame mode: a camera path (keyframes of position, target, fov over time; see the README)', pathOption('--path'))
    .option('--time <seconds>', "the moment of a moving scene to render (Doom's animated textures and lights, the dungeon's phantom); frame mode: the first frame's", numberOption('--time', 0, 1e6), 0)
    .option('--fps <n>', 'frame mode without --path: frames per second of scene time', numberOption('--fps', 0.001, 1000), 30)
    .option('--warmup <seconds>', 'frame mode: render frames for this long first and throw them away, so that the GPU clocks are up when the timed frames start (they fall again while each frame is read back and written: `bench --real-time` times passes with them up)', numberOption('--warmup', 0, 60))
    .action((sceneArg: string, options: RenderOptions, command: Command) =>
      context.run(() => render(sceneArg, options, context, (name) => command.getOptionValueSource(name) === 'cli', given)),
    );
}

/**
 * Everything that can be checked before the GPU starts and the scene loads: options given where they
 * do not apply, the scene's files, the camera path and light table (read and parsed), and that the
 * outputs can be written. A mistake then costs a moment, not a render. Returns the parsed path.
 */
export function checkRenderOptions(sceneArg: string, o: RenderOptions, given: (option: string) => boolean, png: string | undefined): CameraPath | undefined {
  const frameMode = isFrameMode(o);
  for (const entry of CLI_SETTINGS) {
    const mode = settingMode(entry);
    // A switch such as --temporal turns frame mode on; what else is given must fit the mode.
    if (!mode || entry.spec.cli?.switch || o[settingOption(entry).attributeName()] === undefined) continue;
    if (mode === 'frame' && !frameMode) throw new LanternError(`${entry.spec.cli!.flag} applies to frame mode only`, 'Add --frames, --path, --temporal, --denoise, --restir or --mode hybrid, or leave it out');
    if (mode === 'hybrid' && o.mode !== 'hybrid') throw new LanternError(`${entry.spec.cli!.flag} applies to the hybrid recipe only`, 'Add --mode hybrid, or leave it out');
  }
  if (!frameMode && given('warmup')) throw new LanternError('--warmup applies to frame mode only', 'Add --frames, --path, --temporal, --denoise, --restir or --mode hybrid, or leave it out');
  if (given('fps') && (!frameMode || o.path !== undefined)) throw new LanternError(o.path !== undefined ? '--fps does not apply with --path (the path\'s times set the frames)' : '--fps applies to frame mode only', 'Leave it out');
  if (o.samples !== undefined || o.shard !== undefined) {
    if (o.samples === undefined || o.shard === undefined) throw new LanternError(o.samples === undefined ? '--shard needs --samples first-last (which samples the shard holds)' : '--samples needs --shard file.shard (where their sums go)');
    if (frameMode) throw new LanternError('--samples and --shard split a progressive render by samples; frame mode splits by --frames', 'Leave out --frames, --path, --temporal, --denoise, --restir and --mode hybrid');
    if (o.spp !== undefined) throw new LanternError('--spp does not go with --samples (the range says how many)', 'Leave out --spp');
    if (o.chunk !== undefined) throw new LanternError('--chunk does not go with --samples (a shard is one dispatch of its samples)', 'Leave out --chunk');
  }
  if ((o.chunk !== undefined || o.samples !== undefined) && o.kernel === 'specialised') throw new LanternError(`--kernel specialised does not go with ${o.chunk !== undefined ? '--chunk' : '--samples'}: the render switches kernels when the compile is ready, at a moment that depends on timing, and an exact split needs every chunk traced by the same kernel`, 'Leave out --kernel specialised');
  if (o.chunk !== undefined && frameMode) throw new LanternError('--chunk applies to progressive renders (frame mode renders --spp samples a frame)', 'Leave it out');
  const argument = parseSceneArgument(sceneArg);
  // A file's format is known once its bytes are read (on the scene thread, which checks again).
  if (argument.kind === 'builtin') checkSceneOptionsApply(sceneLoadOptions(o), undefined);
  else for (const file of argument.paths) checkUserFile(file);
  if (o.lightTable !== undefined) readLightTable(o.lightTable);
  const path = o.path !== undefined ? parseCameraPath(readJsonFile(o.path, '--path'), o.path) : undefined;
  const sequence = frameMode && frameSelection(o).sequence;
  if (png !== undefined) checkOutputPath('--out', png, sequence ? 'folder' : 'file');
  if (o.shard !== undefined) checkOutputPath('--shard', o.shard, 'file');
  if (o.exr !== undefined) checkOutputPath('--exr', o.exr, sequence ? 'folder' : 'file');
  return path;
}

async function render(sceneArg: string, o: RenderOptions, context: CliContext, given: (option: string) => boolean, estimate?: GivenEstimate): Promise<void> {
  // A sequence of frames, or a shard, writes only what was asked for.
  const sequence = isFrameMode(o) && frameSelection(o).sequence;
  const png = o.out ?? (o.exr || sequence || o.shard ? undefined : `${sceneArg.replace(/[^A-Za-z0-9_-]+/g, '_')}.png`);
  checkLensOptions(o);
  const cameraPath = checkRenderOptions(sceneArg, o, given, png);
  const timeline = o.timings ? new Timeline() : undefined;
  for (const span of timeline ? processSpans() : []) timeline!.add(span);
  // The camera the options make of the scene's, with its lens.
  const renderCamera = (prepared: PreparedScene) => {
    const camera = cameraFromOptions(prepared.scene.camera, o.camera, o.fov);
    const target = o.camera ? ([o.camera[3]!, o.camera[4]!, o.camera[5]!] as const) : undefined;
    return cameraWithLens(camera, o, { scene: prepared.scene, ...(target ? { target } : {}), centreDistance: (c) => centreFocusDistance(prepared, c) });
  };
  const { renderer, prepared, loadMs } = await openSession(sceneArg, context, o, environmentFromOptions(o), {
    ...(timeline ? { timeline } : {}),
    // Only a progressive render accumulates: frame mode, a debug view alone and a merge's given
    // estimate never compile its path tracer.
    progressive: !estimate && recipeOf(o) === 'progressive',
    ...(context.sessions ? { sceneKey: sceneKey(context.argv) } : {}),
    // The image size against the GPU's limits and the lens against the scene's camera, before a kernel compiles.
    check: (loaded, limits) => {
      checkImageSize(o.width, o.height, limits);
      renderCamera(loaded);
    },
  });
  const setUp = performance.now();
  await renderer.resize(o.width, o.height);
  renderer.setCamera(renderCamera(prepared));
  renderer.updateSettings(mergeSettings(renderer.settings, settingsFromOptions(o)));
  await renderer.accelSettled();
  const s = renderer.settings;
  await renderer.compile({}, frameIntent(o));
  // A moving scene as it is at --time, seen from this camera (billboards turn toward it). Frame mode
  // plays the world on from there.
  const world = World.of(prepared.scene);
  if (world && !isFrameMode(o)) renderer.applySceneUpdate(world.advanceTo(o.time, renderer.camera!));
  const debug = s.debugView !== 'none';
  // A debug view that replaces the image needs no path tracing.
  const samples = o.samples ? o.samples.end - o.samples.start : samplesPerPixel(o);
  const spp = debug && s.debugLayout === 'replace' ? 0 : samples;
  if (o.samples && spp === 0) throw new LanternError('--samples renders paths; a debug view that replaces the image traces none', 'Leave out --debug, or use --debug-layout side-by-side');
  timeline?.end('image + camera + settings', setUp);

  if (isFrameMode(o)) {
    if (o.kernel === 'specialised') context.note('frame mode renders with the generic kernels (--kernel specialised applies to progressive renders)');
    const camera = renderer.camera!;
    const result = await renderFrames(renderer, camera, samples, { ...o, ...(cameraPath ? { cameraPath } : {}) }, { ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}) }, world ? { world, start: o.time, fps: o.fps } : undefined);
    // The integrator that traced the frames (the path recipe's --integrator), and what the wavefront's own buffers hold.
    const integrator = s.recipe === 'path' ? { integrator: renderer.frameIntegrator, ...(renderer.frameIntegrator === 'wavefront' ? { wavefrontBytes: renderer.wavefrontBytes } : {}) } : {};
    // The real-time chain's memory (the path recipe's): bytes per pixel in all and per buffer.
    const memory = s.recipe === 'path' ? { denoiserBytesPerPixel: renderer.denoiserMemory.bytesPerPixel, denoiserBuffers: renderer.denoiserMemory.buffers } : {};
    const report = { scene: prepared.scene.name, width: o.width, height: o.height, recipe: s.recipe, ...integrator, sppPerFrame: samples, bounces: s.maxBounces, temporal: s.temporal, denoise: s.denoise, adapter: renderer.gpu.adapterName, ...memory, ...result, ...(prepared.scene.lightingNote ? { notes: [prepared.scene.lightingNote] } : {}) };
    const gpu = result.gpuMs && Object.keys(result.gpuMs).length > 0 ? `; GPU ms per frame: ${Object.entries(result.gpuMs).map(([k, v]) => `${k} ${v.toFixed(3)}`).join(', ')}` : '';
    context.print(o.json ? JSON.stringify(report, null, 2) : `${report.scene}: ${result.frames} frames of ${o.width}×${o.height} at ${samples} spp in ${result.seconds.toFixed(2)} s on ${report.adapter}${gpu}`);
    renderer.destroy();
    return;
  }
  if (estimate) {
    // `lantern merge`: the estimate is given; everything after the tracing is render's own.
    renderer.loadAccumulation(estimate.sums, estimate.samples);
    if (png) await writePng(renderer, png);
    if (o.exr) await writeExr(renderer, o.exr);
    estimate.done({ ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}) }, renderer.gpu.adapterName);
    renderer.destroy();
    return;
  }
  // A shard's estimate starts at its first sample: its random streams are those samples' in a whole render.
  if (o.samples) renderer.resetAccumulation(o.samples.start);
  const bar = !o.json && process.stderr.isTTY ? new SingleBar({ format: 'rendering [{bar}] {value}/{total} spp | {eta_formatted} left', hideCursor: true, stream: process.stderr }) : undefined;
  bar?.start(spp, 0);
  // The scene never changes during a render: specialise up front, rendering on with the generic
  // kernels until the compile is ready (frame mode above keeps the generic ones).
  const specialising = o.kernel === 'specialised' && spp > 0 ? renderer.requestSpecialisation() : undefined;
  let specialisedAt: number | undefined;
  const renderStart = performance.now();
  let firstDispatch = false;
  const chunk = o.samples ? spp : o.chunk;
  const { seconds } = await renderProgressive(renderer, {
    spp,
    ...(chunk !== undefined ? { samplesPerDispatch: chunk } : {}),
    onProgress: (done) => {
      if (!firstDispatch) timeline?.end(`first dispatch (${done} spp)`, renderStart);
      firstDispatch = true;
      bar?.update(done);
      if (specialisedAt === undefined && renderer.kernel === 'specialised') specialisedAt = done;
    },
  });
  bar?.stop();
  // Wait for a compile still under way (it must not outlive the device); a render that ends first used the generic kernels throughout.
  const specialisation = specialising ? await specialising : undefined;
  timeline?.end(`render (${spp} spp)`, renderStart);

  const rays = timeline ? await timeline.time('read ray counts', () => renderer.readRayCounts()) : await renderer.readRayCounts();
  if (o.shard && o.samples) {
    const sums = await renderer.readAccumulationSums();
    const header = { version: SHARD_VERSION, render: shardRenderArgs(context.argv), width: o.width, height: o.height, start: o.samples.start, end: o.samples.end };
    writeFile(o.shard, encodeShard({ header, sums }));
  }
  if (png) await writePng(renderer, png, timeline);
  if (o.exr) await (debug ? writeDebugExr(renderer, o.exr) : writeExr(renderer, o.exr));
  const legend = debug ? await renderer.debugLegend() : undefined;
  const total = rays.extension + rays.shadow;
  const report = {
    scene: prepared.scene.name,
    width: o.width,
    height: o.height,
    spp: renderer.sampleCount,
    bounces: s.maxBounces,
    seed: s.seed,
    lightSampling: s.lightSampling,
    ...(renderer.camera?.lens ? { lens: renderer.camera.lens } : {}),
    adapter: renderer.gpu.adapterName,
    triangles: prepared.triangles.count,
    loadSeconds: loadMs / 1000,
    seconds,
    rays: { extension: rays.extension, shadow: rays.shadow, total },
    raysPerSecond: seconds > 0 ? total / seconds : 0,
    kernel: {
      requested: o.kernel,
      ...(specialisation ? { compileMs: specialisation.compileMs, specialisation: specialisation.description, ...(specialisedAt !== undefined ? { specialisedAfterSpp: specialisedAt } : {}) } : {}),
    },
    ...(legend ? { debug: { view: legend.view, layout: s.debugLayout, label: legend.label, ...(legend.scale ? { scale: { min: legend.scale.min, max: legend.scale.max, auto: legend.scale.auto } } : {}) } } : {}),
    ...(o.samples ? { samples: { first: o.samples.start, last: o.samples.end - 1 } } : {}),
    ...(chunk !== undefined ? { samplesPerDispatch: chunk } : {}),
    outputs: { ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}), ...(o.shard ? { shard: o.shard } : {}) },
    // Information (how the scene is lit and why), apart from warnings; also on stderr.
    ...(prepared.scene.lightingNote ? { notes: [prepared.scene.lightingNote] } : {}),
    ...(timeline ? { timeline: timeline.toJSON() } : {}),
  };
  if (timeline && !o.json) process.stderr.write(`${escapeControls(timeline.format(), { keepLines: true })}\n`);
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
  } else {
    const files = [png, o.exr, o.shard].filter(Boolean).join(' and ');
    if (legend) {
      const range = legend.scale ? ` (colour scale ${legend.scale.min} to ${legend.scale.max}${legend.scale.auto ? ', the image maximum' : ''})` : '';
      context.print(`debug view ${legend.view}, ${s.debugLayout}: ${legend.label}${range}`);
    }
    context.print(
      `${report.scene}: ${o.width}×${o.height}, ${o.samples ? `samples ${o.samples.start}-${o.samples.end - 1}` : `${report.spp} spp`}, ${s.maxBounces} bounces in ${seconds.toFixed(2)} s on ${report.adapter} ` +
        `(${megaRays(report.raysPerSecond)} Mrays/s) -> ${files}`,
    );
    if (specialisation) {
      const from = specialisedAt !== undefined ? `from sample ${specialisedAt}` : 'ready after the last sample';
      context.note(`specialised kernel (${specialisation.description}) compiled in ${specialisation.compileMs.toFixed(0)} ms, ${from}`);
    }
  }
  renderer.destroy();
}

/** Rays per second in millions with figures that fit: 4459, 12.3, 0.0523 (never 0.0 on a slow adapter). */
export function megaRays(raysPerSecond: number): string {
  const m = raysPerSecond / 1e6;
  return m >= 100 ? m.toFixed(0) : String(Number(m.toPrecision(3)));
}
