/** `lantern bench <scene>`: BVH build, traversal and path-tracing throughput, GPU-timed. */
import type { Command } from 'commander';
import { runBenchmark } from '../../renderer/benchmark.ts';
import type { CliContext } from '../context.ts';
import { mergeSettings } from '../../renderer/settings-schema.ts';
import type { SettingEntry } from '../../renderer/settings-schema.ts';
import { choiceOption, integerOption, withImageOptions, withKernelOption, withSceneOptions } from '../options.ts';
import type { Renderer } from '../../renderer/renderer.ts';
import type { KernelKind } from '../../renderer/specialisation-schedule.ts';
import { SPECIALISATION_PARTS, UNROLL_PRIMITIVE_LIMIT, type SpecialisationPart } from '../../gpu/specialisation.ts';
import { LanternError } from '../../errors.ts';
import { environmentFromOptions, withEnvironmentOptions, type EnvironmentOptions } from '../environment-option.ts';
import { CLI_SETTINGS, settingMode, settingOption, settingsFromOptions, withSettingOptions } from '../setting-options.ts';
import { benchmarkFrames } from '../../renderer/frame-benchmark.ts';
import { DRAGON_ALIAS, sceneHelp } from '../scene-source.ts';
import { centreFocusDistance } from '../../renderer/focus.ts';
import { cameraWithLens, checkLensOptions, withLensOptions, type LensOptions } from '../lens-option.ts';
import { openSession } from '../session.ts';
import { benchmarkLevels } from '../../renderer/level-benchmark.ts';
import type { Scene } from '../../scene/types.ts';
import { cameraFromOptions, withCameraOptions } from '../camera-option.ts';
import { RAY_ORDERS, type RayOrder } from '../../passes/benchmark-rays-pass.ts';
import { BENCH_PROTOCOLS, tinybvhView, type BenchProtocol } from '../../renderer/bench-protocol.ts';
import { withoutStudio } from '../../scene/studio.ts';
import type { PreparedScene } from '../../renderer/prepare.ts';

interface BenchOptions extends EnvironmentOptions, LensOptions, Readonly<Record<string, unknown>> {
  width: number;
  height: number;
  repeats: number;
  warmups: number;
  camera?: number[];
  fov?: number;
  rayOrder: RayOrder;
  protocol?: BenchProtocol;
  pathTracing: boolean;
  reorder: boolean;
  lightTable?: string;
  skill?: number;
  json?: boolean;
  kernel: KernelKind;
  unrollLimit?: number;
  specialise?: string;
  levels: 'scene' | 'single' | 'two';
  billboards: boolean;
  tlasInstances: number;
  realTime: boolean;
  spp?: number;
}

/** --levels: the scene as it says (moving instances in a top level), nothing moving (one BVH), or every instance moving (every mesh its own bottom level). */
const LEVELS = ['scene', 'single', 'two'] as const;

/** The scene as --levels and --no-billboards ask (undefined: as loaded). */
function adjustScene(levels: BenchOptions['levels'], billboards: boolean): ((scene: Scene) => Scene) | undefined {
  if (levels === 'scene' && billboards) return undefined;
  return (loaded) => {
    let scene = loaded;
    if (!billboards && scene.dynamics?.billboards) {
      // Without Doom's things: what a map cost before it had them.
      const posed = new Set(scene.dynamics.billboards.map((b) => b.instance));
      const { billboards: _, ...dynamics } = scene.dynamics;
      scene = { ...scene, instances: scene.instances.filter((inst) => !posed.has(inst.id)), dynamics };
    }
    if (levels !== 'scene') scene = { ...scene, instances: scene.instances.map((inst) => ({ ...inst, moves: levels === 'two' })) };
    return scene;
  };
}

/** The settings that change what path tracing costs (those that change the estimate), and with --real-time the frame mode's. */
const benchSetting = (entry: SettingEntry) => entry.spec.restarts || settingMode(entry) === 'frame';
/** --real-time: untimed frames before the timed ones last at least this long (the GPU's clocks rise). */
const FRAME_WARMUP_SECONDS = 1;

export function registerBench(program: Command, context: CliContext): void {
  const command = program
    .command('bench')
    .description('measure BVH build time, ray throughput (primary and diffuse rays) and path-tracing speed')
    .argument('[scene]', `${sceneHelp()} (with --protocol: default '${DRAGON_ALIAS}', the Stanford Dragon of the npm package)`);
  withKernelOption(
    withLensOptions(withSettingOptions(withEnvironmentOptions(withSceneOptions(withCameraOptions(withImageOptions(command, { width: 1920, height: 1080 })))), benchSetting)),
    'generic',
    'which path-tracing kernels to time; specialised reports their compile time too (the ray figures always use the BVH)',
  )
    .option('--unroll-limit <n>', `with --kernel specialised: trace scenes of at most n primitives without a BVH (default ${UNROLL_PRIMITIVE_LIMIT}; 0: never)`, integerOption('--unroll-limit', 0, 1_000_000))
    .option('--specialise <parts>', `with --kernel specialised: the parts applied, comma-separated (${SPECIALISATION_PARTS.join(', ')}; default all)`)
    .option('--levels <which>', `the acceleration structure: ${LEVELS.join(', ')} (scene: moving instances in a top level over the static world; single: one BVH, nothing moves; two: every instance in the top level, each mesh its own bottom level)`, (v: string) => {
      if (!(LEVELS as readonly string[]).includes(v)) throw new LanternError(`--levels must be one of ${LEVELS.join(', ')}, not '${v}'`);
      return v;
    }, 'scene')
    .option('--no-billboards', "leave out the scene's billboards (Doom's things): what a map cost before it had them")
    .option('--tlas-instances <n>', 'instances of the timed top-level rebuild (CPU)', integerOption('--tlas-instances', 1, 10_000_000), 10_000)
    .option('-r, --repeats <n>', 'timed launches of each measurement (the median is reported)', integerOption('--repeats', 1, 1000), 20)
    .option('--warmups <n>', 'untimed launches before them', integerOption('--warmups', 0, 1000), 5)
    .option('--ray-order <order>', `how primary rays are laid out over a workgroup's 64 threads: ${RAY_ORDERS.join(', ')} (tiles: one 8 × 8-pixel tile per workgroup, as tinybvh's speed test; scanline: 64 pixels of a row)`, choiceOption('--ray-order', RAY_ORDERS), 'tiles')
    .option('--protocol <name>', `reproduce a published workload exactly: ${BENCH_PROTOCOLS.join(', ')} (tinybvh v1.6.7's speed test on the bare Stanford Dragon: its camera, 45° at 16:9, tiles, rays only)`, choiceOption('--protocol', BENCH_PROTOCOLS))
    .option('--reorder', 'sort the diffuse rays by direction octant and origin (Morton order) before tracing them, as a sorting stage would (the sort is not timed)', false)
    .option('--no-path-tracing', 'time traversal only (the default with --protocol)')
    .option('--real-time', "time the real-time frame instead: --repeats frames of --spp samples at the camera, rendered back to back (after --warmups frames and at least a second of them) with nothing read back, as the viewer renders them; add --temporal and --denoise for the denoising chain (the median GPU time of each pass, of the chain and of the frame)", false)
    .option('--spp <samples>', 'with --real-time: samples per pixel in each frame (default 1)', integerOption('--spp', 1, 4096))
    .option('--json', 'print the figures as JSON')
    .action((sceneArg: string | undefined, options: BenchOptions) => context.run(() => bench(sceneArg, options, context)));
}

/** The diagonal of the box around everything traced: the static world's root and every moving instance's box. */
function sceneDiagonal(prepared: PreparedScene): number {
  const boxes = prepared.levels?.boxes ?? prepared.bvh.bounds.subarray(0, 6);
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let o = 0; o < boxes.length; o += 6) {
    if (!(boxes[o]! <= boxes[o + 3]!)) continue; // an empty box
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k]!, boxes[o + k]!);
      hi[k] = Math.max(hi[k]!, boxes[o + 3 + k]!);
    }
  }
  return lo[0]! <= hi[0]! ? Math.hypot(hi[0]! - lo[0]!, hi[1]! - lo[1]!, hi[2]! - lo[2]!) : 0;
}

/** The scene as --protocol asks: the bare mesh (no studio floor or lights). */
function protocolScene(scene: Scene): Scene {
  const bare = withoutStudio(scene);
  if (!bare) throw new LanternError(`--protocol traces a bare mesh: '${scene.name}' is not a PLY mesh (or molecule) in the studio`, `Drop the scene argument to use the Stanford Dragon ('${DRAGON_ALIAS}')`);
  return bare;
}

async function bench(sceneArgument: string | undefined, o: BenchOptions, context: CliContext): Promise<void> {
  checkLensOptions(o);
  const protocol = o.protocol;
  if (sceneArgument === undefined && !protocol) throw new LanternError('bench needs a scene', 'Name one (for example cornell), or give --protocol');
  const sceneArg = sceneArgument ?? DRAGON_ALIAS;
  if (protocol) {
    if (o.camera || o.fov !== undefined) throw new LanternError('--protocol sets the camera: drop --camera and --fov');
  }
  checkRealTimeOptions(o, protocol);
  if (o.unrollLimit !== undefined && o.kernel !== 'specialised') throw new LanternError('--unroll-limit applies to the specialised kernel only', 'Add --kernel specialised');
  // The ray figures alone (--no-path-tracing, --protocol) accumulate nothing, unless the specialised
  // kernels are timed (they are the path tracer's); --real-time times frames.
  const accumulates = !o.realTime && ((o.pathTracing && !protocol) || o.kernel === 'specialised');
  const { renderer, prepared, loadMs } = await openSession(sceneArg, context, o, environmentFromOptions(o), { adjust: protocol ? protocolScene : adjustScene(o.levels, o.billboards), progressive: accumulates });
  await renderer.resize(o.width, o.height);
  renderer.updateSettings(mergeSettings(renderer.settings, settingsFromOptions(o, benchSetting)));
  await renderer.accelSettled();
  // What the timed recipe runs (renderer/recipes/recipe.ts): --real-time asks for frames, its switches say which.
  await renderer.compile({}, { frames: o.realTime, accumulate: accumulates });
  if (renderer.settings.spectral && o.kernel === 'specialised') throw new LanternError('--kernel specialised compiles RGB kernels: spectral mode runs the generic ones', 'Drop --spectral or --kernel specialised');
  // A lens makes primary rays start all over the aperture: less coherent, and that is what is measured.
  const protocolView = protocol ? tinybvhView(protocol, prepared.triangles.positions) : undefined;
  if (protocolView && Math.abs(o.width / o.height - protocolView.aspect) > 0.01 * protocolView.aspect) {
    throw new LanternError(`--protocol ${protocol} is defined at 16:9: ${o.width}×${o.height} is not`, 'Give -W and -H in 16:9 (the default 1920×1080 is)');
  }
  const base = protocolView?.camera ?? cameraFromOptions(prepared.scene.camera, o.camera, o.fov);
  const camera = cameraWithLens(base, o, { scene: prepared.scene, ...(o.camera ? { target: [o.camera[3]!, o.camera[4]!, o.camera[5]!] as const } : {}), centreDistance: (c) => centreFocusDistance(prepared, c) });
  renderer.setCamera(camera);
  const parts = o.specialise?.split(',').map((p) => p.trim()).filter((p) => p !== '');
  for (const p of parts ?? []) if (!(SPECIALISATION_PARTS as readonly string[]).includes(p)) throw new LanternError(`--specialise: unknown part '${p}'`, `Parts are: ${SPECIALISATION_PARTS.join(', ')}`);
  const specialisation = o.kernel === 'specialised' ? await renderer.requestSpecialisation({ ...(o.unrollLimit !== undefined ? { unrollLimit: o.unrollLimit } : {}), ...(parts ? { parts: parts as SpecialisationPart[] } : {}) }) : undefined;
  if (o.kernel === 'specialised' && renderer.kernel !== 'specialised') throw new Error('bench: the specialised kernels were compiled but are not in use');
  if (o.realTime) {
    await benchRealTime(renderer, prepared, loadMs, o, context);
    return;
  }
  const diagonal = sceneDiagonal(prepared);
  const result = await runBenchmark(renderer, { triangles: prepared.triangles, diagonal, repeats: o.repeats, warmups: o.warmups, rayOrder: o.rayOrder, reorder: o.reorder, pathTracing: o.pathTracing && !protocol });
  const levels = benchmarkLevels(prepared, o.tlasInstances, o.repeats);
  const culling = renderer.tileCullingStats;
  const s = prepared.bvh.stats;
  const report = {
    scene: prepared.scene.name,
    triangles: prepared.triangles.count,
    lights: prepared.packed.counts.lights,
    loadMs,
    ...(camera.lens ? { lens: camera.lens } : {}),
    ...(protocol && protocolView ? { protocol: { name: protocol, eye: camera.position, target: protocolView.target, framingDistance: protocolView.framingDistance, vfovDegrees: camera.vfovDegrees } } : {}),
    camera: { position: camera.position, forward: camera.forward, vfovDegrees: camera.vfovDegrees },
    spectral: renderer.settings.spectral,
    bvh: { buildMs: s.buildMs, nodes: s.nodeCount, leaves: s.leafCount, maxDepth: s.maxDepth, sahCost: s.sahCost },
    accel: renderer.settings.accel,
    ...(renderer.scene?.wide ? { wide: renderer.scene.wide.stats } : {}),
    levels: { mode: o.levels, instances: prepared.packed.counts.instances, ...levels },
    ...(culling ? { tileCulling: culling } : {}),
    kernel: { kind: o.kernel, ...(specialisation ? { compileMs: specialisation.compileMs, specialisation: specialisation.description, unrolled: specialisation.unrolled } : {}) },
    ...result,
    adapterInfo: adapterInfo(renderer),
  };
  renderer.destroy();
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
    return;
  }
  const f = (x: number, digits = 1) => x.toFixed(digits);
  const p = result.pathTracing;
  context.print(
    [
      `Lantern bench: ${report.scene} at ${o.width}×${o.height} on ${result.adapter} (${result.timing === 'gpu-timestamps' ? 'GPU timestamps' : 'wall clock'}, median of ${o.repeats} after ${o.warmups} warm-ups)`,
      ...(protocol && protocolView ? [`  protocol        ${protocol}: bare mesh, eye (${camera.position.map((v) => v.toFixed(7)).join(', ')}), target (${protocolView.target.map((v) => v.toFixed(7)).join(', ')}), ${camera.vfovDegrees}° vertical`] : []),
      ...(camera.lens ? [`  lens            aperture radius ${camera.lens.apertureRadius.toPrecision(3)}, focus distance ${camera.lens.focusDistance.toPrecision(4)} (scene units)`] : []),
      `  triangles       ${report.triangles.toLocaleString('en-US')} (${report.lights} emissive)`,
      `  BVH build       ${f(s.buildMs)} ms: ${s.nodeCount.toLocaleString('en-US')} nodes, depth ${s.maxDepth}, SAH cost ${f(s.sahCost, 2)}`,
      ...(report.wide ? [`  traversed as    ${report.accel}: ${report.wide.nodeCount.toLocaleString('en-US')} wide nodes, depth ${report.wide.maxDepth}, ${f(report.wide.meanChildren, 2)} children a node, SAH cost ${f(report.wide.sahCost, 2)}`] : report.accel !== 'bvh' ? [`  traversed as    ${report.accel}`] : []),
      `  levels          ${o.levels}: ${prepared.packed.counts.instances} instance record(s), ${levels.blas.meshes} moving mesh(es) of ${levels.blas.triangles.toLocaleString('en-US')} primitives`,
      `  top level       rebuilt over ${levels.tlas.instances.toLocaleString('en-US')} instances in ${f(levels.tlas.ms, 3)} ms (CPU)`,
      ...(levels.blas.meshes > 0 ? [`  moving meshes   refit ${f(levels.blas.refitMs, 3)} ms vs rebuild ${f(levels.blas.rebuildMs, 3)} ms; a frame moving all of them: ${f(levels.updateMs, 3)} ms (CPU)`] : []),
      ...(culling ? [`  tile culling    ${culling.tiles} tiles of ${f(culling.meanTriangles, 0)} triangles on average (max ${culling.maxTriangles}, full ${culling.fullTriangles}); geometry ${f(culling.tilesGeometryBytes / 2 ** 20)} MiB for all tiles vs ${f(culling.fullGeometryBytes / 2 ** 20, 2)} MiB; precomputed in ${f(culling.precomputeMs, 0)} ms (CPU)`] : []),
      `  primary rays    ${f(result.primary.mraysPerSecond)} Mrays/s (${f(result.primary.ms, 3)} ms for ${result.primary.rays.toLocaleString('en-US')} rays by ${result.rayOrder}; ${f(100 * result.primary.hitFraction)} % hit)`,
      `  diffuse rays    ${f(result.diffuse.mraysPerSecond)} Mrays/s (${f(result.diffuse.ms, 3)} ms for ${result.diffuse.rays.toLocaleString('en-US')} rays, one per primary hit${result.reordered ? ', reordered' : ''}; ${f(100 * result.diffuse.hitFraction)} % hit)`,
      `  kernel          ${specialisation ? `specialised (${specialisation.description}), compiled in ${f(specialisation.compileMs, 0)} ms` : 'generic'}`,
      ...(p ? [`  path tracing    ${report.spectral ? '(spectral) ' : ''}${f(p.samplesPerSecond / 1e6, 2)} M samples/s (${f(p.msPerSample, 3)} ms per spp), ${f(p.mraysPerSecond)} Mrays/s at ${p.maxBounces} bounces (${f(p.raysPerPath, 2)} rays per path)`] : []),
    ].join('\n'),
  );
}

/** The adapter's own words (vendor, architecture, device, driver description), for records such as bench-matrix's. */
function adapterInfo(renderer: Renderer): { vendor: string; architecture: string; device: string; description: string } {
  const { vendor, architecture, device, description } = renderer.gpu.adapter.info;
  return { vendor, architecture, device, description };
}

/** Frame-mode settings apply to --real-time only, as --spp does; --protocol times rays alone. */
function checkRealTimeOptions(o: BenchOptions, protocol: BenchProtocol | undefined): void {
  if (o.realTime) {
    if (protocol) throw new LanternError('--protocol times traversal only: it does not apply with --real-time', 'Leave one out');
    return;
  }
  if (o.spp !== undefined) throw new LanternError('--spp applies to --real-time only', 'Add --real-time, or leave it out');
  for (const entry of CLI_SETTINGS) {
    if (entry.spec.restarts || settingMode(entry) !== 'frame' || o[settingOption(entry).attributeName()] === undefined) continue;
    throw new LanternError(`${entry.spec.cli!.flag} applies to --real-time only`, 'Add --real-time, or leave it out');
  }
}

/** `bench --real-time`: frames of the real-time recipe back to back (renderer/frame-benchmark.ts). */
async function benchRealTime(renderer: Renderer, prepared: PreparedScene, loadMs: number, o: BenchOptions, context: CliContext): Promise<void> {
  const s = renderer.settings;
  const spp = o.spp ?? 1;
  const frames = await benchmarkFrames(renderer, { spp, frames: o.repeats, warmups: o.warmups, warmupSeconds: FRAME_WARMUP_SECONDS });
  const memory = renderer.denoiserMemory;
  // ReSTIR runs only in the megakernel's RGB paths (renderer/recipes/real-time.ts usesRestir): say so where it was asked for and no ReSTIR pass was timed.
  const restirRan = frames.frameMs === undefined ? s.restir : Object.keys(frames.passMs).some((name) => name.startsWith('restir'));
  const timing = renderer.gpu.hasTimestamps ? 'gpu-timestamps' : 'wall-clock';
  const report = {
    scene: prepared.scene.name,
    triangles: prepared.triangles.count,
    lights: prepared.packed.counts.lights,
    loadMs,
    adapter: renderer.gpu.adapterName,
    adapterInfo: adapterInfo(renderer),
    timing,
    width: o.width,
    height: o.height,
    recipe: s.recipe,
    ...(s.recipe === 'path' ? { integrator: renderer.frameIntegrator, temporal: s.temporal, denoise: s.denoise, restir: restirRan } : {}),
    warmups: o.warmups,
    ...(memory.bytesPerPixel > 0 ? { denoiserBytesPerPixel: memory.bytesPerPixel } : {}),
    ...frames,
  };
  const restir = s.restir ? [restirRan ? 'ReSTIR' : 'ReSTIR asked for but not run: the wavefront and spectral paths keep one light sample a bounce'] : [];
  const features = s.recipe === 'hybrid' ? ['hybrid recipe'] : [renderer.frameIntegrator, ...restir, ...(s.temporal ? ['temporal'] : []), ...(s.denoise ? ['à-trous'] : [])];
  renderer.destroy();
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
    return;
  }
  const ms = (x: number) => `${x.toFixed(3)} ms`;
  context.print(
    [
      `Lantern bench --real-time: ${report.scene} at ${o.width}×${o.height} on ${report.adapter} (${timing === 'gpu-timestamps' ? 'GPU timestamps' : 'no timestamp queries: wall clock only'}, medians of ${o.repeats} frames after ${o.warmups} and at least ${FRAME_WARMUP_SECONDS} s of warm-up frames)`,
      `  frame           ${frames.frameMs !== undefined ? `${ms(frames.frameMs)} of GPU time, ` : ''}${frames.framesPerSecond.toFixed(1)} frames/s by the wall clock (${spp} spp; ${features.join(', ')})`,
      ...(frames.chainMs !== undefined ? [`  denoising chain ${ms(frames.chainMs)}${memory.bytesPerPixel > 0 ? `, ${memory.bytesPerPixel} bytes a pixel` : ''}`] : []),
      ...Object.entries(frames.passMs).map(([name, t]) => `    ${name.padEnd(24)}${ms(t)}`),
    ].join('\n'),
  );
}
