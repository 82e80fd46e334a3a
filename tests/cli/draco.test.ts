/**
 * A Draco-compressed glTF (KHR_draco_mesh_compression) in the built CLI: its decoder starts inside
 * the bundle, and the model decodes to the same geometry as its uncompressed twin.
 */
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { decodePng } from '../../src/image/png.ts';
import { dracoModel, type DracoModel } from '../fixtures/draco-model.ts';
import { runLantern } from './run-lantern.ts';

let dir: string;
let model: DracoModel;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-draco-'));
  model = await dracoModel();
  writeFileSync(join(dir, 'torus.glb'), model.plain);
  writeFileSync(join(dir, 'torus-draco.glb'), model.draco);
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

interface Info {
  triangles: number;
  bounds: { min: number[]; max: number[] };
  materialKinds: Record<string, number>;
}

function info(file: string): Info {
  const r = runLantern(['info', join(dir, file), '--json']);
  expect(r.code, r.stderr).toBe(0);
  return JSON.parse(r.stdout) as Info;
}

describe('a Draco-compressed glTF in the CLI', () => {
  it('info decodes it to the geometry of the uncompressed model', () => {
    const plain = info('torus.glb');
    const draco = info('torus-draco.glb');
    expect(plain.triangles).toBe(model.triangles);
    expect(draco.triangles).toBe(model.triangles);
    expect(draco.materialKinds).toEqual(plain.materialKinds);
    // Draco stores positions quantized to 14 bits over the model's box (2 units): steps of 1.2e-4.
    for (const k of ['min', 'max'] as const) draco.bounds[k].forEach((x, i) => expect(x).toBeCloseTo(plain.bounds[k][i]!, 3));
  });

  it('renders it: the orange torus in front of the sky', () => {
    const out = join(dir, 'torus-draco.png');
    // The scene loads on the CLI's worker thread here (info loads it on the main thread).
    const r = runLantern(['render', join(dir, 'torus-draco.glb'), '-W', '32', '-H', '32', '--spp', '2', '--out', out]);
    expect(r.code, r.stderr).toBe(0);
    const img = decodePng(readFileSync(out));
    let orange = 0, sky = 0;
    for (let i = 0; i < img.width * img.height; i++) {
      const [red, blue] = [img.data[i * 4]!, img.data[i * 4 + 2]!];
      if (red > 2 * blue + 20) orange++;
      else if (blue > red) sky++;
    }
    expect(orange).toBeGreaterThan(img.width * img.height * 0.1);
    expect(sky).toBeGreaterThan(img.width * img.height * 0.1);
  });
});
