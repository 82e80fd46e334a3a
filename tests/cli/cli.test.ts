/**
 * The built `lantern` command, as a user runs it: real renders produce valid files and honest JSON;
 * bad input gives one line that says what is wrong and what to do, a non-zero exit code, and no
 * stack trace unless --verbose.
 */
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { decodeExr, encodeExr } from '../../src/image/exr.ts';
import { decodePng } from '../../src/image/png.ts';
import { squareRoomWad } from '../../src/loaders/doom/test-wad.ts';
import { randomSoup } from '../../src/bvh/test-scenes.ts';

let dir: string;
let cli: string;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-cli-'));
  // Built once for the e2e project (tests/e2e/global-setup.ts).
  cli = inject('lanternCli');
});

afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
});

function lantern(args: string[], env: Record<string, string> = {}) {
  // SwiftShader everywhere, so the outcome does not depend on the machine's GPU.
  const r = spawnSync(process.execPath, [cli, ...args], {
    encoding: 'utf8',
    env: { ...process.env, VK_ICD_FILENAMES: '/usr/lib/chromium/vk_swiftshader_icd.json', ...env },
    timeout: 120_000,
  });
  // Dawn's own warnings (Vulkan loader chatter) are not Lantern's output; Lantern's lines start with
  // "lantern:" and commander's usage errors with "error:".
  const stderr = r.stderr.split('\n').filter((l) => l.startsWith('lantern') || l.startsWith('error:')).join('\n');
  return { code: r.status, stdout: r.stdout, stderr, rawStderr: r.stderr };
}

describe('lantern render', () => {
  it('renders PNG and EXR and reports what it did', () => {
    const png = join(dir, 'c.png'), exr = join(dir, 'c.exr');
    const r = lantern(['render', 'cornell', '-W', '24', '-H', '16', '-s', '3', '--out', png, '--exr', exr, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const report = JSON.parse(r.stdout);
    expect(report).toMatchObject({ scene: 'cornell', width: 24, height: 16, spp: 3, bounces: 8, seed: 1, triangles: 32 });
    expect(report.rays.extension).toBeGreaterThanOrEqual(24 * 16 * 3);
    expect(report.rays.total).toBe(report.rays.extension + report.rays.shadow);
    expect(report.raysPerSecond).toBeGreaterThan(0);
    const image = decodePng(readFileSync(png));
    expect([image.width, image.height]).toEqual([24, 16]);
    const radiance = decodeExr(readFileSync(exr));
    expect([radiance.width, radiance.height]).toEqual([24, 16]);
    expect(Object.keys(radiance.channels).sort()).toEqual(['B', 'G', 'R']);
  });

  it('renders with depth of field: an f-number becomes an aperture in the scene\'s millimetres, focused at the --camera target', () => {
    const png = join(dir, 'dof.png');
    const r = lantern(['render', 'cornell', '-W', '16', '-H', '16', '-s', '2', '--f-number', '2', '--focal-length', '50', '--camera', '278,273,-800,278,273,0', '--out', png, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    // 50 mm at f/2: a 25 mm pupil, radius 12.5 mm (the Cornell box's unit); the target is 800 mm ahead.
    expect(JSON.parse(r.stdout).lens).toEqual({ apertureRadius: 12.5, focusDistance: 800 });
    expect(existsSync(png)).toBe(true);
  });

  it('is deterministic for a fixed seed', () => {
    const a = join(dir, 'a.exr'), b = join(dir, 'b.exr');
    expect(lantern(['render', 'furnace', '-W', '8', '-H', '8', '-s', '2', '--seed', '5', '--exr', a]).code).toBe(0);
    expect(lantern(['render', 'furnace', '-W', '8', '-H', '8', '-s', '2', '--seed', '5', '--exr', b]).code).toBe(0);
    expect(Buffer.compare(readFileSync(a), readFileSync(b))).toBe(0);
  });
});

describe('lantern render --debug', () => {
  it('writes the heat map as PNG and its raw counts as EXR, and reports the legend', () => {
    const png = join(dir, 'heat.png'), exr = join(dir, 'heat.exr');
    const r = lantern(['render', 'bvh-teaching', '-W', '32', '-H', '24', '--debug', 'heat-nodes', '--out', png, '--exr', exr, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const report = JSON.parse(r.stdout);
    // Replacing the image needs no path tracing.
    expect(report).toMatchObject({ spp: 0, debug: { view: 'heat-nodes', layout: 'replace', label: 'BVH nodes visited per primary ray', scale: { min: 0, auto: true } } });
    const counts = decodeExr(readFileSync(exr)).channels.R!;
    expect(counts.every((c) => Number.isInteger(c) && c >= 1)).toBe(true);
    expect(report.debug.scale.max).toBe(Math.max(...counts));
    const image = decodePng(readFileSync(png));
    expect([image.width, image.height]).toEqual([32, 24]);
  });

  it('draws the wireframe over the rendered image with a fixed depth', () => {
    const png = join(dir, 'wire.png');
    const r = lantern(['render', 'cornell', '-W', '16', '-H', '16', '-s', '1', '--debug', 'wireframe', '--debug-layout', 'overlay', '--wireframe-depth', '2', '--out', png]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(r.stdout).toMatch(/debug view wireframe, overlay: BVH boxes at depth 2 of \d+/);
    expect(decodePng(readFileSync(png)).width).toBe(16);
  });
});

describe('lantern bvh-stats', () => {
  it('reports every BVH layout with its statistics', () => {
    const r = lantern(['bvh-stats', 'cornell', '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const stats = JSON.parse(r.stdout);
    expect(stats).toMatchObject({ scene: 'cornell', triangles: 32 });
    const [layout] = stats.layouts;
    expect(layout).toMatchObject({ name: 'binary-sah', triangleCount: 32, nodeCount: 2 * layout.leafCount - 1 });
    expect(layout.leafSizeHistogram.reduce((a: number, n: number, size: number) => a + n * size, 0)).toBe(32);
    expect(layout.maxDepth).toBeGreaterThanOrEqual(Math.ceil(Math.log2(layout.leafCount)));
    expect(layout.sahCost).toBeGreaterThan(0);
    expect(layout.nodeBytesPerTriangle).toBeCloseTo(((layout.nodeCount + 1) * 32) / 32, 9);
    expect(layout.buildMs).toBeGreaterThan(0);
    // The wide trees (bvh/wide.ts) over the same leaves: fewer nodes, a lower SAH cost.
    expect(stats.layouts.map((l: { name: string }) => l.name)).toEqual(['binary-sah', 'bvh4', 'cwbvh', 'bvh4-greedy', 'cwbvh-greedy']);
    for (const wide of stats.layouts.slice(1)) {
      expect(wide).toMatchObject({ triangleCount: 32, leafCount: layout.leafCount });
      expect(wide.nodeCount).toBeLessThan(layout.nodeCount / 2);
      expect(wide.sahCost).toBeLessThan(layout.sahCost);
    }
    const text = lantern(['bvh-stats', 'bvh-teaching']);
    expect(text.stdout).toMatch(/^bvh-teaching: 2,508 triangles/);
    expect(text.stdout).toMatch(/binary-sah: binary BVH.*\n.*SAH cost [\d.]+\n.*leaf sizes: .*\n.*bytes\/triangle.*built in/);
  });

  it('--threads builds the same tree on worker threads (bvh/build-parallel.ts) and times both builds', () => {
    // 6,000 random triangles: halves split again by the workers into subtrees of at most 2,048.
    const soup = randomSoup(6_000, 4);
    const lines = ['ply', 'format ascii 1.0', `element vertex ${soup.length / 3}`, 'property float x', 'property float y', 'property float z', `element face ${soup.length / 9}`, 'property list uchar int vertex_indices', 'end_header'];
    for (let v = 0; v < soup.length; v += 3) lines.push(`${soup[v]} ${soup[v + 1]} ${soup[v + 2]}`);
    for (let t = 0; t < soup.length / 9; t++) lines.push(`3 ${3 * t} ${3 * t + 1} ${3 * t + 2}`);
    const file = join(dir, 'soup.ply');
    writeFileSync(file, lines.join('\n'));
    const r = lantern(['bvh-stats', file, '--threads', '2', '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const { build, layouts } = JSON.parse(r.stdout);
    expect(build).toMatchObject({ threads: 2, identical: true, sahCost: layouts[0].sahCost });
    for (const ms of [build.singleMs, build.parallelMs, build.parallelFirstMs]) expect(ms).toBeGreaterThan(0);
    const one = lantern(['bvh-stats', file, '--threads', '1']);
    expect(one.stdout).toMatch(/binary-SAH build: [\d.]+ ms on one thread; no parallel build/);
  });
});

describe('lantern render in frame mode, and lantern diff', () => {
  it('renders a camera path frame by frame and compares images', () => {
    const path = join(dir, 'path.json'), frames = join(dir, 'frames');
    writeFileSync(path, JSON.stringify({ keyframes: [{ time: 0, position: [300, 273, -800], target: [278, 273, 0] }, { time: 1, position: [278, 273, -800], target: [278, 273, 0], fov: 35 }] }));
    const r = lantern(['render', 'cornell', '-W', '16', '-H', '12', '-s', '1', '-b', '2', '--frames', '3', '--temporal', '--denoise', '--path', path, '--out', frames, '--exr', frames, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const report = JSON.parse(r.stdout);
    expect(report).toMatchObject({ scene: 'cornell', frames: 3, sppPerFrame: 1, temporal: true, denoise: true });
    expect(report.frameChangeRmse).toBeGreaterThan(0);
    expect(readdirSync(frames).sort()).toEqual(['frame-0000.exr', 'frame-0000.png', 'frame-0001.exr', 'frame-0001.png', 'frame-0002.exr', 'frame-0002.png']);

    const [a, b] = [join(frames, 'frame-0001.exr'), join(frames, 'frame-0002.exr')];
    const same = JSON.parse(lantern(['diff', a, a, '--json']).stdout);
    expect(same).toMatchObject({ rmse: 0, relMse: 0, ssim: 1, width: 16, height: 12 });
    const heat = join(dir, 'heat.png');
    const d = lantern(['diff', a, b, '--heatmap', heat]);
    expect(d.code, d.rawStderr).toBe(0);
    expect(d.stdout).toMatch(/^RMSE [0-9.e-]+ {2}relMSE [0-9.e-]+ {2}SSIM 0\.\d+ {2}\(16×12\)/);
    expect(decodePng(readFileSync(heat)).width).toBe(16);

    // Another size, written here (diff compares files; rendering one costs a compile).
    const small = join(dir, 'small.exr');
    writeFileSync(small, encodeExr(8, 8, new Float32Array(8 * 8 * 3).fill(0.5)));
    const mismatch = lantern(['diff', a, small]);
    expect(mismatch.code).toBe(1);
    expect(mismatch.stderr).toMatch(/is 16×12 but .* is 8×8/);
    const badPath = join(dir, 'bad-path.json');
    writeFileSync(badPath, JSON.stringify({ keyframes: [{ time: 0, position: [0, 0, 0] }] }));
    const bad = lantern(['render', 'cornell', '-W', '8', '-H', '8', '--path', badPath]);
    expect(bad.code).toBe(1);
    expect(bad.stderr).toMatch(/keyframe 0: "target" must be three numbers/);
  });
});

describe('bad input', () => {
  const oneLine = (s: string) => s.trim().split('\n').length === 1;

  it.each([
    [['render', 'nope'], /unknown scene 'nope'.*cornell/],
    [['render', 'missing.ply'], /cannot read 'missing\.ply': no such file/],
    [['render', 'cornell', '--width', '0'], /--width must be from 1 to 16384/],
    [['render', 'cornell', '--height', 'tall'], /--height must be a whole number/],
    [['render', 'cornell', '--spp', '-3'], /--spp must be from 1/],
    [['render', 'cornell', '--tonemap', 'filmic'], /--tonemap must be one of linear, reinhard, aces/],
    [['render', 'cornell', '-W', '16384', '-H', '16384'], /image 16384×16384 is too large/],
    [['info', 'nope.obj'], /unknown scene 'nope\.obj'/],
    [['render', 'cornell', '--debug', 'heat'], /--debug must be one of heat-nodes, heat-triangles, wireframe/],
    [['render', 'cornell', '--debug', 'wireframe', '--wireframe-depth', '99'], /--wireframe-depth must be a whole number from 0 to 64/],
    [['render', 'cornell', '--debug', 'heat-nodes', '--heat-max', '0'], /--heat-max must be a positive number or 'auto'/],
    [['bvh-stats', 'nope'], /unknown scene 'nope'/],
    [['bvh-stats', 'cornell', '--builder', 'cpu,fast'], /--builder takes a comma-separated list of cpu, gpu; got 'cpu,fast'/],
    [['bvh-stats', 'cornell', '--bare'], /--bare takes the mesh out of its studio: 'cornell' is not a PLY mesh/],
    [['render', 'cornell', '--sky', '100,0'], /--sky: the sun's elevation must be from -90 to 90 degrees, not 100/],
    [['render', 'cornell', '--sky', '30'], /--sky/],
    [['render', 'cornell', '--env', 'nowhere.hdr'], /--env: cannot read 'nowhere\.hdr'/],
    [['render', 'cornell', '--sky', '30,0', '--env', 'x.hdr'], /--sky and --env both give the environment/],
    [['render', 'cornell', '--env', 'none', '--env-intensity', '2'], /--env-intensity and --env-rotation have nothing to act on with --env none/],
    [['render', 'cornell', '--aperture', '-1'], /--aperture must be a number ≥ 0/],
    [['render', 'cornell', '--focus-distance', '0', '--aperture', '1'], /--focus-distance must be a number > 0/],
    [['render', 'cornell', '--aperture', '1', '--f-number', '2'], /--aperture and --f-number both give the aperture/],
    [['render', 'cornell', '--focus-distance', '500'], /--focus-distance needs a lens, and the camera of 'cornell' is a pinhole/],
    [['bench', 'cornell', '--kernel', 'fast'], /--kernel must be one of generic, specialised, not 'fast'/],
    [['bench', 'cornell', '--unroll-limit', '8'], /--unroll-limit applies to the specialised kernel only/],
    [['bench', 'cornell', '--ray-order', 'hilbert'], /--ray-order must be one of tiles, scanline, not 'hilbert'/],
    [['bench', 'cornell', '--protocol', 'tinybvh-closeup'], /--protocol traces a bare mesh: 'cornell' is not a PLY mesh/],
    [['bench'], /bench needs a scene/],
    [['bench', 'cornell', '--temporal'], /--temporal applies to --real-time only/],
    [['bench', 'cornell', '--clamp-k', '2'], /--clamp-k applies to --real-time only/],
    [['bench', 'cornell', '--spp', '4'], /--spp applies to --real-time only/],
    [['bench', '--protocol', 'tinybvh-closeup', '--real-time'], /--protocol times traversal only/],
    [['render', 'cornell', '--camera', '1e308,0,0,0,0,0'], /--camera takes numbers from -10000000 to 10000000, not 1e\+308/],
    [['render', 'cornell', '--history-cap', '8'], /--history-cap applies to frame mode only/],
    [['render', 'cornell', '--frames', '2', '--light-samples', '2'], /--light-samples applies to the hybrid recipe only/],
    [['render', 'cornell', '--fps', '10'], /--fps applies to frame mode only/],
    [['render', 'cornell', '--light-table', 'lights.json'], /--light-table applies to Doom maps only, not to a built-in scene/],
    [['info', 'cornell', '--skill', '2'], /--skill applies to Doom and Wolfenstein 3D maps only/],
    [['render', 'cornell', '--out', ''], /--out needs a file name, not an empty one/],
    [['render', 'cornell', '--exr', '/proc/lantern/x.exr'], /--exr: cannot write '\/proc\/lantern\/x\.exr': \/proc is a system folder/],
    // Once spun for ever in a recursive mkdir.
    [['textures', 'missing.wad', '-o', '/proc/lantern-textures'], /--out: cannot write '\/proc\/lantern-textures': \/proc is a system folder/],
  ])('%j: one line, non-zero exit', (args, message) => {
    const r = lantern(args as string[]);
    expect(r.code).not.toBe(0);
    expect(r.stderr).toMatch(message);
    expect(oneLine(r.stderr), r.stderr).toBe(true);
    expect(r.rawStderr).not.toMatch(/^\s+at /m);
  });

  it('a corrupt PLY names the file and the problem', () => {
    const path = join(dir, 'broken.ply');
    writeFileSync(path, 'ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\nelement face 10\nproperty list uchar int vertex_indices\nend_header\n\x00\x01');
    const r = lantern(['info', path]);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/broken\.ply/);
    expect(oneLine(r.stderr)).toBe(true);
  });

  it('no WebGPU adapter: says so and what to do', () => {
    const r = lantern(['render', 'cornell', '-W', '8', '-H', '8'], { VK_ICD_FILENAMES: join(dir, 'no-such-driver.json') });
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/no WebGPU adapter found.*driver/);
    expect(oneLine(r.stderr)).toBe(true);
  });

  it('checks inputs and outputs before the GPU starts (without a driver, their error is the one shown)', () => {
    const noDriver = { VK_ICD_FILENAMES: join(dir, 'no-such-driver.json') };
    const path = join(dir, 'straight-through.json');
    writeFileSync(path, JSON.stringify({ keyframes: [{ time: 0, position: [0, 0, 0], target: [0, 0, 1] }, { time: 1, position: [0, 0, 0], target: [0, 0, -1] }] }));
    for (const [args, message] of [
      [['render', 'missing.ply'], /cannot read 'missing\.ply': no such file/],
      [['render', 'cornell', '--path', join(dir, 'no-path.json')], /cannot read '.*no-path\.json': no such file/],
      [['render', 'cornell', '--path', path], /between keyframes 0 and 1 the camera passes through its target/],
      [['render', 'cornell', '--out', dir], /--out: cannot write '.*': it is a folder/],
      [['render', 'cornell', '--frames', '2', '--out', path], /--out: cannot write '.*straight-through\.json': it is a file, not a folder/],
    ] as const) {
      const r = lantern([...args], noDriver);
      expect(r.code, r.rawStderr).toBe(1);
      expect(r.stderr).toMatch(message);
    }
  });

  it('--verbose adds the stack trace', () => {
    const r = lantern(['--verbose', 'render', 'nope']);
    expect(r.code).toBe(1);
    expect(r.rawStderr).toMatch(/^\s+at /m);
  });
});

// Beside the checkout; a worktree finds them in the shared folder.
const GLTF = existsSync('../shared/assets/gltf') ? '../shared/assets/gltf' : '/work/shared/assets/gltf';
const haveGltf = existsSync(GLTF);

/** Mean of a PNG's colour channels, 0–255. */
function meanPixel(path: string): number {
  const image = decodePng(readFileSync(path));
  const channels = image.data.length / (image.width * image.height);
  let sum = 0;
  for (let i = 0; i < image.data.length; i += channels) sum += image.data[i]! + image.data[i + 1]! + image.data[i + 2]!;
  return sum / (3 * image.width * image.height);
}

describe.skipIf(!haveGltf)('glTF from the command line (needs ../shared/assets/gltf)', () => {
  it('info names a missing texture once as a warning, and how the model is lit apart, as information', () => {
    const r = lantern(['info', `${GLTF}/Lantern/glTF/Lantern.gltf`, '--json']);
    expect(r.code).toBe(0);
    expect(r.stderr.match(/Lantern_baseColor\.png/g)).toHaveLength(1);
    expect(r.stderr).toMatch(/^lantern: warning: Lantern_baseColor\.png is missing/m);
    const info = JSON.parse(r.stdout);
    // Its glowing glass gives a few per cent of a sky's light: the default sky lights it.
    expect(info).toMatchObject({ scene: 'Lantern', materialKinds: { 'metallic-roughness': 1 }, environment: 'sky' });
    expect(info.emissiveTriangles).toBeGreaterThan(0);
    expect(info.notes).toEqual([expect.stringMatching(/^its emitters give [\d.]+ % of the light of a default sky; a default sky lights it$/)]);
    expect(info.warnings.some((w: string) => /sky/.test(w))).toBe(false);
  });

  it('renders a .glb under the sky given on the command line, and says nothing of a default sky', () => {
    const out = join(dir, 'duck.png');
    const r = lantern(['render', `${GLTF}/Duck/glTF-Binary/Duck.glb`, '--width', '16', '--height', '16', '--spp', '2', '--sky', '30,45,3', '--out', out, '--json']);
    expect(r.code, r.stderr).toBe(0);
    expect(existsSync(out)).toBe(true);
    expect(r.stderr).not.toMatch(/sky|light of its own/);
    expect(JSON.parse(r.stdout).notes).toBeUndefined();
  });

  it('--env none leaves a model without light in the dark, with no default sky and no word of one', () => {
    const out = join(dir, 'duck-dark.png');
    const r = lantern(['render', `${GLTF}/Duck/glTF-Binary/Duck.glb`, '--width', '8', '--height', '8', '--spp', '1', '--env', 'none', '--out', out]);
    expect(r.code, r.stderr).toBe(0);
    expect(meanPixel(out)).toBe(0);
    expect(r.stderr).not.toMatch(/sky|light of its own/);
  });

  const HELMET = `${GLTF}/DamagedHelmet/glTF-Binary/DamagedHelmet.glb`;
  it('DamagedHelmet: its glowing details cannot light it, so the default sky does, and the render is not black', (context) => {
    if (!existsSync(HELMET)) {
      console.warn(`skipped: ${HELMET} is absent`);
      context.skip();
    }
    const out = join(dir, 'helmet.png');
    const r = lantern(['render', HELMET, '--width', '16', '--height', '16', '--spp', '4', '--out', out, '--json']);
    expect(r.code, r.stderr).toBe(0);
    // Said once, as information (no "warning"), on stderr and apart in the JSON.
    expect(r.stderr).toMatch(/^lantern: DamagedHelmet: its emitters give 0\.\d+ % of the light of a default sky; a default sky lights it$/m);
    expect(r.stderr).not.toMatch(/warning/);
    expect(JSON.parse(r.stdout).notes).toEqual([expect.stringMatching(/a default sky lights it$/)]);
    // Black but for a few glowing pixels before (no environment at all): now lit by daylight.
    expect(meanPixel(out)).toBeGreaterThan(30);
  });
});

describe('lantern info and bench', () => {
  it('info reports the scene and its BVH', () => {
    const r = lantern(['info', 'cornell', '--json']);
    expect(r.code).toBe(0);
    const info = JSON.parse(r.stdout);
    expect(info).toMatchObject({ scene: 'cornell', triangles: 32, emissiveTriangles: 2, punctualLights: 0, environment: 'none', materialKinds: { diffuse: 4 } });
    expect(info.bvh.nodeCount).toBeGreaterThan(0);
  });

  it('bench reports GPU-timed throughput figures', () => {
    const r = lantern(['bench', 'cornell', '-W', '32', '-H', '32', '-r', '1', '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const b = JSON.parse(r.stdout);
    expect(b.timing).toBe('gpu-timestamps');
    for (const figure of [b.primary.mraysPerSecond, b.diffuse.mraysPerSecond, b.pathTracing.samplesPerSecond, b.pathTracing.mraysPerSecond]) {
      expect(figure).toBeGreaterThan(0);
      expect(Number.isFinite(figure)).toBe(true);
    }
    expect(b.pathTracing.raysPerPath).toBeGreaterThan(1);
    expect(b.bvh.nodes).toBe(33);
    expect(b.kernel).toEqual({ kind: 'generic' });
    // tinybvh's diffuse rays: one per primary hit. Rows instead of tiles trace the same rays in
    // another order (so the same hits), and --camera moves the view.
    expect(b).toMatchObject({ rayOrder: 'tiles', warmups: 5, repeats: 1 });
    expect(b.primary.rays).toBe(32 * 32);
    expect(b.diffuse.rays).toBe(Math.round(b.primary.hitFraction * 32 * 32));
    expect(b.primary.hitFraction).toBeGreaterThan(0.8);
    const rows = JSON.parse(lantern(['bench', 'cornell', '-W', '32', '-H', '32', '-r', '1', '--warmups', '0', '--ray-order', 'scanline', '--no-path-tracing', '--json']).stdout);
    expect(rows).toMatchObject({ rayOrder: 'scanline', primary: { rays: 1024, hitFraction: b.primary.hitFraction }, diffuse: { rays: b.diffuse.rays } });
    expect(rows.pathTracing).toBeUndefined();
    const away = JSON.parse(lantern(['bench', 'cornell', '-W', '32', '-H', '32', '-r', '1', '--warmups', '0', '--no-path-tracing', '--camera', '278,273,-800,278,273,-1800', '--json']).stdout);
    expect(away.primary.hitFraction).toBe(0);
    expect(away.diffuse.rays).toBe(0);
  });

  it('bench --real-time times the real-time frames pass by pass, the denoising chain apart', () => {
    const r = lantern(['bench', 'cornell', '-W', '32', '-H', '24', '-r', '3', '--warmups', '1', '--real-time', '--temporal', '--denoise', '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const b = JSON.parse(r.stdout);
    expect(b).toMatchObject({ timing: 'gpu-timestamps', recipe: 'path', integrator: 'megakernel', temporal: true, denoise: true, restir: false, frames: 3, sppPerFrame: 1, denoiserBytesPerPixel: 72 });
    // Only the frame's passes: no ray or path-tracing throughput figures.
    expect(b.primary).toBeUndefined();
    const passes = Object.keys(b.passMs);
    expect(passes).toEqual(expect.arrayContaining(['path trace (frame)', 'temporal', 'a-trous 1', 'a-trous 2', 'a-trous 3', 'a-trous 4', 'a-trous 5']));
    const chain = passes.filter((p) => p === 'temporal' || p.startsWith('a-trous')).reduce((sum, p) => sum + b.passMs[p], 0);
    // Medians of per-frame sums against sums of per-pass medians: close, not equal.
    expect(b.chainMs).toBeGreaterThan(0.5 * chain);
    expect(b.chainMs).toBeLessThan(2 * chain);
    expect(b.chainMs).toBeLessThan(b.frameMs);
    expect(b.framesPerSecond).toBeGreaterThan(0);
  });

  it('bench --kernel specialised times the kernels specialised to the scene and reports their compile time', () => {
    const r = lantern(['bench', 'furnace', '-W', '16', '-H', '16', '-r', '1', '--bounces', '1', '--kernel', 'specialised', '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const b = JSON.parse(r.stdout);
    expect(b.kernel).toMatchObject({ kind: 'specialised', unrolled: true, specialisation: expect.stringMatching(/^12 primitives unrolled, no BVH; .* 1 bounces inlined$/) });
    expect(b.kernel.compileMs).toBeGreaterThan(0);
    expect(b.pathTracing.samplesPerSecond).toBeGreaterThan(0);
  });
});

const FREEDOOM1 = '/usr/share/games/doom/freedoom1.wad';

describe.skipIf(!existsSync(FREEDOOM1))('Doom maps from the command line', () => {
  it('info lists every map with its counts', () => {
    const r = lantern(['info', FREEDOOM1, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    const { maps } = JSON.parse(r.stdout);
    expect(maps).toHaveLength(36);
    expect(maps[0]).toMatchObject({ name: 'E1M1', format: 'doom', failures: [] });
    expect(maps[0].triangles).toBeGreaterThan(1000);
    // Things drawn as sprites at the default skill (3), and the floor lamps among them that emit.
    expect(maps[0]).toMatchObject({ sprites: 169, emittingSprites: 7 });
  });

  it('info counts the things of the skill asked for, in the listing and for one map', () => {
    const listing = lantern(['info', FREEDOOM1, '--skill', '5']);
    expect(listing.code, listing.rawStderr).toBe(0);
    expect(listing.stdout).toContain('at skill 5');
    expect(listing.stdout).toMatch(/^ {2}E1M1 .* 185 +7$/m);
    const one = lantern(['info', `${FREEDOOM1}#E1M1`, '--skill', '1', '--json']);
    expect(one.code, one.rawStderr).toBe(0);
    expect(JSON.parse(one.stdout)).toMatchObject({ scene: 'E1M1', sprites: 171, emittingSprites: 7 });
  });

  it('refuses a skill outside 1 to 5', () => {
    const r = lantern(['info', `${FREEDOOM1}#E1M1`, '--skill', '6']);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/--skill must be from 1 to 5, not 6/);
  });

  it('renders a map from the player start, with the start-up timeline from process start to the PNG', () => {
    const png = join(dir, 'e1m1.png');
    const r = lantern(['render', `${FREEDOOM1}#E1M1`, '-W', '32', '-H', '20', '-s', '1', '-b', '2', '--out', png, '--json', '--timings']);
    expect(r.code, r.rawStderr).toBe(0);
    const report = JSON.parse(r.stdout);
    expect(report).toMatchObject({ scene: 'E1M1', width: 32, height: 20 });
    expect(decodePng(readFileSync(png)).width).toBe(32);

    const { totalMs, spans } = report.timeline as { totalMs: number; spans: { stage: string; startMs: number; endMs: number; detail?: string }[] };
    const at = (stage: string) => {
      const span = spans.find((s) => s.stage.startsWith(stage));
      expect(span, `the timeline has no '${stage}'`).toBeDefined();
      return span!;
    };
    for (const s of spans) {
      expect(s.startMs).toBeGreaterThanOrEqual(0);
      expect(s.endMs).toBeGreaterThanOrEqual(s.startMs);
      expect(s.endMs).toBeLessThanOrEqual(totalMs);
    }
    // Each step starts after the one it waits for ends: Node and the bundle, the device, the scene
    // (its features choose the path tracer's variant), the compile, the upload, the frame, the PNG.
    const chain = [
      ['node start + bundle parse', 'bundle evaluated'], ['bundle evaluated', 'device'], ['device', 'pipeline passes/path-trace:path_trace'],
      ['prepare: pack', 'pipeline passes/path-trace:path_trace'], ['pipeline passes/path-trace:path_trace', 'first dispatch'], ['upload scene', 'first dispatch'],
      ['first dispatch', 'tone map + read back'], ['tone map + read back', 'PNG encode'], ['PNG encode', 'PNG write'],
    ];
    for (const [before, after] of chain) expect(at(before!).endMs, `${before} ends before ${after} starts`).toBeLessThanOrEqual(at(after!).startMs);
    expect(at('PNG write').endMs).toBe(totalMs);
    expect(at('scene: build').startMs).toBeGreaterThan(0);
    // The scene loaded on a thread of its own; only the kernels this render runs were compiled, the
    // path tracer once (for this map's features, not a plain scene's first), and the automatic
    // exposure's two (a Doom map is exposed automatically by default).
    expect(spans.some((s) => s.stage === 'scene thread: result received')).toBe(true);
    // The bundle carries the WGSL's reflection (scripts/shader-reflection.ts): read, never parsed.
    const reflected = spans.filter((s) => s.stage.startsWith('reflect '));
    expect(reflected.map((s) => s.stage)).toContain('reflect passes/path-trace');
    expect(reflected.map((s) => `${s.stage}: ${s.detail}`)).toEqual(reflected.map((s) => `${s.stage}: precomputed`));
    expect(spans.filter((s) => s.stage.startsWith('bindings ')).map((s) => s.stage)).toEqual([]);
    expect(spans.filter((s) => s.stage.startsWith('pipeline ')).map((s) => s.stage).sort()).toEqual([
      'pipeline passes/exposure:exposure_adapt', 'pipeline passes/exposure:exposure_reduce', 'pipeline passes/path-trace:path_trace', 'pipeline passes/tonemap:tonemap_image',
    ]);
  });

  it('converts a map to a .glb', () => {
    const glb = join(dir, 'e1m1.glb');
    const r = lantern(['convert', `${FREEDOOM1}#E1M1`, '-o', glb]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(new TextDecoder().decode(readFileSync(glb).subarray(0, 4))).toBe('glTF');
  });

  it('converts analytic spheres to glTF triangles and says so', () => {
    const glb = join(dir, 'spheres.glb');
    const r = lantern(['convert', 'spheres', '-o', glb]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(r.stdout).toContain('0 triangles + 5 spheres and capsules (tessellated)');
    expect(new TextDecoder().decode(readFileSync(glb).subarray(0, 4))).toBe('glTF');
  });

  it('writes every texture and flat as PNG', () => {
    const out = join(dir, 'textures');
    const r = lantern(['textures', FREEDOOM1, '-o', out]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(readdirSync(join(out, 'textures')).length).toBeGreaterThan(800);
    expect(readdirSync(join(out, 'flats')).length).toBeGreaterThan(200);
    const startan = decodePng(readFileSync(join(out, 'textures', 'STARTAN3.png')));
    expect([startan.width, startan.height]).toEqual([128, 128]);
  });

  it('an unknown map lists the maps there are', () => {
    const r = lantern(['render', `${FREEDOOM1}#E9M9`]);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/has no map 'E9M9'.*E1M1, E1M2/);
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
  });

  it('a truncated WAD says what is wrong in one line', () => {
    const cut = join(dir, 'cut.wad');
    writeFileSync(cut, readFileSync(FREEDOOM1).subarray(0, 100_000));
    const r = lantern(['info', `${cut}#E1M1`]);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/cut\.wad/);
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
  });
});

describe('molecules from the command line', () => {
  const CAFFEINE = 'tests/fixtures/caffeine.mol';

  it('info lists the molecule: formula, atoms, bonds', () => {
    const r = lantern(['info', CAFFEINE]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(r.stdout).toMatch(/caffeine\s+C8H10N4O2\s+24 atoms\s+25 bonds \(21 single, 4 double\)/);
    const json = JSON.parse(lantern(['info', CAFFEINE, '--json']).stdout);
    expect(json.molecules[0]).toMatchObject({ name: 'caffeine', formula: 'C8H10N4O2', atoms: 24, bonds: 25 });
  });

  it("'#' picks a style; an SD file's record by number, reported by its name", () => {
    const info = JSON.parse(lantern(['info', `${CAFFEINE}#space-filling`, '--json']).stdout);
    expect(info.scene).toBe('caffeine.mol#space-filling');
    const sdf = join(dir, 'two.sdf');
    writeFileSync(sdf, `${readFileSync(CAFFEINE, 'utf8')}$$$$\nwater\n\n\n  1  0  0     0  0  0  0  0  0999 V2000\n    0.0000    0.0000    0.0000 O   0  0\nM  END\n$$$$\n`);
    const r = lantern(['info', `${sdf}#2:space-filling`, '--json']);
    expect(r.code, r.rawStderr).toBe(0);
    expect(JSON.parse(r.stdout).scene).toBe('two.sdf#water:space-filling');
  });

  it('a bad molfile: one line naming the file and the line', () => {
    const bad = join(dir, 'bad.mol');
    writeFileSync(bad, readFileSync(CAFFEINE, 'utf8').replace('O   0  0  0  0  0  0  0  0  0  0  0  0', 'Zz  0  0  0  0  0  0  0  0  0  0  0  0'));
    const r = lantern(['info', bad]);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/bad\.mol line 5: unknown element 'Zz'/);
    expect(r.stderr.trim().split('\n')).toHaveLength(1);
    const unknown = lantern(['info', `${CAFFEINE}#sticks`]);
    expect(unknown.stderr).toMatch(/has no model 'sticks'.*ball-and-stick, space-filling/);
  });
});

describe('lantern view', () => {
  /** Starts `lantern view`, waits for the address it prints, and returns it with a stop function. */
  async function startView(args: string[]): Promise<{ link: string; stop: () => void }> {
    const child = spawn(process.execPath, [cli, 'view', '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    child.stderr.on('data', (d) => (err += d));
    const link = await new Promise<string>((resolve, reject) => {
      child.stdout.on('data', (d) => {
        out += d;
        const m = /Lantern viewer: (\S+)/.exec(out);
        if (m) resolve(m[1]!);
      });
      child.on('exit', (code) => reject(new Error(`lantern view exited (${code}): ${err}`)));
    });
    return { link, stop: () => child.kill('SIGINT') };
  }

  it('serves the page and the WAD named on the command line, and a link that opens its map', async () => {
    const app = join(dir, 'app');
    mkdirSync(join(app, 'assets'), { recursive: true });
    writeFileSync(join(app, 'index.html'), '<!doctype html><title>page</title>');
    writeFileSync(join(app, 'assets', 'a.js'), 'export {};');
    const wad = join(dir, 'room.wad');
    writeFileSync(wad, squareRoomWad('MAP01'));
    const { link, stop } = await startView([`${wad}#MAP01`, '--app', app]);
    try {
      const url = new URL(link);
      expect(url.hostname).toBe('127.0.0.1');
      expect(url.searchParams.get('map')).toBe('MAP01');
      const fileUrl = url.searchParams.get('wad')!;
      expect(fileUrl).toBe('files/0/room.wad');
      expect(await (await fetch(link)).text()).toContain('<title>page</title>');
      expect((await fetch(new URL('assets/a.js', link))).headers.get('content-type')).toMatch(/javascript/);
      const served = new Uint8Array(await (await fetch(new URL(fileUrl, link))).arrayBuffer());
      expect(served).toEqual(new Uint8Array(readFileSync(wad)));
      // Nothing outside the page and the named files.
      for (const path of ['files/1/x.wad', '../cli.test.ts', '%2e%2e/room.wad', 'assets/../../room.wad']) {
        expect((await fetch(`${url.origin}/${path}`)).status, path).toBe(404);
      }
    } finally {
      stop();
    }
    const builtin = await startView(['furnace', '--app', app]);
    builtin.stop();
    expect(new URL(builtin.link).searchParams.get('scene')).toBe('furnace');
    // A lens on the command line is a lens in the link, as the page reads it (aperture=, focus=).
    const lensed = await startView(['cornell', '--app', app, '--aperture', '12.5', '--focus-distance', '800']);
    lensed.stop();
    const params = new URL(lensed.link).searchParams;
    expect([params.get('scene'), params.get('aperture'), params.get('focus')]).toEqual(['cornell', '12.5', '800']);
    // Doom's skill level goes into the link with the files (skill=), as the page reads it.
    const skilled = await startView([`${wad}#MAP01`, '--app', app, '--skill', '4']);
    skilled.stop();
    expect([new URL(skilled.link).searchParams.get('map'), new URL(skilled.link).searchParams.get('skill')]).toEqual(['MAP01', '4']);
  });

  it('refuses unknown scenes, missing maps and a page that was not built, before serving', () => {
    const noApp = join(dir, 'no-app');
    mkdirSync(noApp, { recursive: true });
    const wad = join(dir, 'room2.wad');
    writeFileSync(wad, squareRoomWad('MAP01'));
    const cases: [string[], RegExp][] = [
      [['view', 'nope', '--port', '0'], /unknown scene 'nope'/],
      [['view', `${wad}#MAP07`, '--port', '0'], /has no map 'MAP07'.*MAP01/],
      [['view', join(dir, 'absent.wad'), '--port', '0'], /cannot read .*absent\.wad.*no such file/],
      [['view', 'cornell', '--port', '0', '--app', noApp], /the page is not built.*npm run build:app/],
    ];
    for (const [args, message] of cases) {
      const r = lantern(args);
      expect(r.code, args.join(' ')).toBe(1);
      expect(r.stderr).toMatch(message);
    }
  });
});
