/**
 * The hostile glTF inputs of issue 27 §6 through the built `lantern` command, as a user meets them:
 * each ends with exit 0 (a warning for what is left out) or one line naming the problem, and the
 * process's peak memory stays under 2 GB (read from the child itself at exit: its maxRSS counts
 * every thread). Before: 1.5·10⁸ vertices aborted V8 at 2.8 GB, 10⁷ instances and a sparse count of
 * 10⁹ ran past a minute, 100 images sharing one 5792² PNG past 90 s, a progressive JPEG of 30,000
 * scans past 120 s, a zero-scaled camera or light was an internal error, a buffer at
 * ../../../../../../etc/hostname was read.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { encodePng } from '../../src/image/png.ts';
import { countBombGltf, externalBufferGltf, pngStreamBomb, progressiveJpeg, sharedImageGlb, zeroScaleGltf } from '../fuzz/crafted.ts';

let dir: string;
let cli: string;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-hostile-'));
  cli = inject('lanternCli');
  // Loaded before the command: writes the process's peak resident memory (kB) when it exits.
  writeFileSync(join(dir, 'peak.cjs'), "process.on('exit', () => require('fs').writeFileSync(process.env.LANTERN_PEAK_FILE, String(process.resourceUsage().maxRSS)));\n");
});

afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
});

const MAX_PEAK_MB = 2048;

/** Runs the command without a Vulkan driver: every case here ends before the GPU would start. */
function lantern(args: string[]): { code: number | null; stdout: string; stderr: string; peakMb: number } {
  const peakFile = join(dir, 'peak.txt');
  writeFileSync(peakFile, '');
  const r = spawnSync(process.execPath, ['--require', join(dir, 'peak.cjs'), cli, ...args], {
    encoding: 'utf8',
    env: { ...process.env, LANTERN_PEAK_FILE: peakFile, VK_ICD_FILENAMES: join(dir, 'no-such-driver.json') },
    timeout: 120_000,
  });
  const stderr = r.stderr.split('\n').filter((l) => l.startsWith('lantern')).join('\n');
  return { code: r.status, stdout: r.stdout, stderr, peakMb: Number(readFileSync(peakFile, 'utf8')) / 1024 };
}

function write(name: string, bytes: Uint8Array): string {
  const path = join(dir, name);
  mkdirSync(join(path, '..'), { recursive: true });
  writeFileSync(path, bytes);
  return path;
}

describe('hostile glTF files through lantern info (issue 27)', () => {
  it.each([
    ['1.5e8 vertices without a buffer view', () => countBombGltf('positions', 1.5e8), /bomb\.gltf: vertices of the meshes it places: 150,000,000 is over the limit vertices=/],
    ['a sparse count of 1e9', () => countBombGltf('sparse', 1e9), /its sparse count 1,000,000,000 is not from 1 to its count 3/],
    ['1e7 EXT_mesh_gpu_instancing rows', () => countBombGltf('instances', 1e7), /10,000,000 is over the limit instances=/],
  ])('%s: one line, exit 1, no allocation', (_what, make, message) => {
    const r = lantern(['info', write('bomb.gltf', make())]);
    expect(r.code, r.stderr).toBe(1);
    expect(r.stderr).toMatch(message);
    expect(r.stderr.split('\n')).toHaveLength(1);
    expect(r.peakMb).toBeGreaterThan(0);
    expect(r.peakMb).toBeLessThan(MAX_PEAK_MB);
  });

  it('100 images sharing one 5792² PNG: one texture, decoded once', () => {
    const side = 5792;
    const r = lantern(['info', '--json', write('shared.glb', sharedImageGlb(100, encodePng(side, side, new Uint8Array(side * side * 4))))]);
    expect(r.code, r.stderr).toBe(0);
    expect(r.stderr).not.toMatch(/replaced by a neutral one/);
    expect(JSON.parse(r.stdout)).toMatchObject({ materials: 100, textures: 1 });
    expect(r.peakMb).toBeLessThan(MAX_PEAK_MB);
  });

  it('a progressive JPEG of 30,000 scans and a PNG whose stream inflates to 512 MB: each texture left out with a warning', () => {
    for (const [name, image, reason] of [
      ['scans.glb', progressiveJpeg(4096, 4096, 30_000), /it is a JPEG of more than 32 scans/],
      ['png-bomb.glb', pngStreamBomb(16, 512 * 2 ** 20), /its image data inflates past the 1,040 bytes its 16×16 pixels need/],
    ] as const) {
      const r = lantern(['info', write(name, sharedImageGlb(1, image))]);
      expect(r.code, r.stderr).toBe(0);
      expect(r.stderr).toMatch(reason);
      expect(r.peakMb).toBeLessThan(MAX_PEAK_MB);
    }
  });

  it('a camera and a spot light on zero-scaled nodes: left out with a warning each (they were internal errors)', () => {
    for (const what of ['camera', 'spot'] as const) {
      const r = lantern(['info', write(`${what}.gltf`, zeroScaleGltf(what))]);
      expect(r.code, r.stderr).toBe(0);
      expect(r.stderr).toMatch(/is left out: its node's transform/);
      expect(r.stderr).not.toMatch(/internal error/);
    }
  });

  it("a buffer at ../../../../../../etc/hostname or beside the model's folder is not read", () => {
    // A readable triangle one folder up: before, the model loaded it.
    write('secret.bin', new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer));
    for (const uri of ['../secret.bin', '../../../../../../etc/hostname', `file://${join(dir, 'secret.bin')}`, join(dir, 'secret.bin')]) {
      const r = lantern(['info', write('model/escape.gltf', externalBufferGltf(uri))]);
      expect(r.code, uri).toBe(1);
      expect(r.stderr).toMatch(/^lantern: error: escape: nothing to show, the geometry is in .*, which Lantern does not read \(/);
      expect(r.stderr.split('\n')).toHaveLength(1);
    }
    // Its own folder and below is what it may name.
    write('model/data/triangle.bin', readFileSync(join(dir, 'secret.bin')));
    expect(lantern(['info', write('model/inside.gltf', externalBufferGltf('data/../data/triangle.bin'))]).code).toBe(0);
  });
});

describe('a hostile camera path (issue 27)', () => {
  it('keyframes at ±1e308 seconds: one line naming the keyframe, before the GPU starts', () => {
    const path = write('path.json', new TextEncoder().encode(JSON.stringify({ keyframes: [{ time: -1e308, position: [0, 0, 5], target: [0, 0, 0] }, { time: 1e308, position: [0, 1, 5], target: [0, 0, 0] }] })));
    const r = lantern(['render', 'cornell', '--path', path, '-W', '8', '-H', '8', '--frames', '2', '--out', join(dir, 'frames')]);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/path\.json: keyframe 0: "time" must be a number of seconds from -1000000 to 1000000$/);
    expect(r.stderr.split('\n')).toHaveLength(1);
  });
});
