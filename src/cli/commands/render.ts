/** `lantern render <scene>`: a progressive render to PNG and/or EXR, with a progress bar. */
import { SingleBar } from 'cli-progress';
import type { Command } from 'commander';
import { renderProgressive } from '../../renderer/progressive.ts';
import { DEFAULT_SETTINGS, LIGHT_SAMPLING, TONE_MAPPERS, type LightSampling, type ToneMapper } from '../../renderer/settings.ts';
import { cameraFromOptions } from '../camera-option.ts';
import { choiceOption, integerOption, numberListOption, numberOption, withImageOptions, withSceneOptions } from '../options.ts';
import { writeExr, writePng } from '../output-files.ts';
import { sceneHelp } from '../scene-source.ts';
import { openSession } from '../session.ts';
import type { CliContext } from '../context.ts';

interface RenderOptions {
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
    .option('--json', 'print what was done as JSON')
    .action((sceneArg: string, options: RenderOptions) => context.run(() => render(sceneArg, options, context)));
}

async function render(sceneArg: string, o: RenderOptions, context: CliContext): Promise<void> {
  const png = o.out ?? (o.exr ? undefined : `${sceneArg.replace(/[^A-Za-z0-9_-]+/g, '_')}.png`);
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
  });

  const bar = !o.json && process.stderr.isTTY ? new SingleBar({ format: 'rendering [{bar}] {value}/{total} spp | {eta_formatted} left', hideCursor: true, stream: process.stderr }) : undefined;
  bar?.start(o.spp, 0);
  const { seconds } = await renderProgressive(renderer, { spp: o.spp, onProgress: (done) => bar?.update(done) });
  bar?.stop();

  const rays = await renderer.readRayCounts();
  if (png) await writePng(renderer, png);
  if (o.exr) await writeExr(renderer, o.exr);
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
    raysPerSecond: total / seconds,
    outputs: { ...(png ? { png } : {}), ...(o.exr ? { exr: o.exr } : {}) },
  };
  if (o.json) {
    context.print(JSON.stringify(report, null, 2));
  } else {
    const files = [png, o.exr].filter(Boolean).join(' and ');
    context.print(
      `${report.scene}: ${o.width}×${o.height}, ${report.spp} spp, ${o.bounces} bounces in ${seconds.toFixed(2)} s on ${report.adapter} ` +
        `(${(report.raysPerSecond / 1e6).toFixed(1)} Mrays/s) -> ${files}`,
    );
  }
  renderer.destroy();
}
