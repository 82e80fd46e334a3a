/**
 * A damaged .glb given to the built CLI: one line saying what is wrong in the file's terms, before
 * the GPU starts (so without a word from Dawn, and whatever the driver).
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { byteSizes } from '../../src/loaders/gltf/glb.ts';
import { dracoModel } from '../fixtures/draco-model.ts';
import { runLantern } from './run-lantern.ts';

let dir: string;
let glb: Uint8Array;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-damaged-glb-'));
  // The fixture's uncompressed torus: 2,304 triangles, about 44 kB.
  glb = (await dracoModel()).plain;
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('a damaged .glb', () => {
  // Without a driver, an error found after the GPU started would be "no WebGPU adapter found".
  const noDriver = () => ({ VK_ICD_FILENAMES: join(dir, 'no-such-driver.json') });

  it('truncated: one line with what its header claims and what the file has, before the GPU starts', () => {
    const path = join(dir, 'cut.glb');
    const cut = glb.subarray(0, Math.floor(glb.length * 0.6));
    writeFileSync(path, cut);
    const [claimed, has] = byteSizes(glb.length, cut.length);
    const expected = `lantern: error: cut.glb is truncated: its GLB header gives its length as ${claimed}, the file has ${has}. The file was cut short (an interrupted download or copy): get it again\n`;
    for (const [args, env] of [
      [['render', path, '-W', '8', '-H', '8'], noDriver()],
      [['bench', path, '-W', '8', '-H', '8'], noDriver()],
      [['render', path, '-W', '8', '-H', '8'], { VK_ICD_FILENAMES: undefined, VK_DRIVER_FILES: undefined }],
      [['info', path], {}],
    ] as const) {
      const r = runLantern(args, env);
      expect(r.code, args.join(' ')).toBe(1);
      expect(r.stderr, args.join(' ')).toBe(expected);
    }
  });

  it('a chunk past the end, a JSON chunk that is not JSON: the same, before the GPU starts', () => {
    const u32 = (b: Uint8Array, at: number) => new DataView(b.buffer, b.byteOffset).getUint32(at, true);
    const binAt = 20 + u32(glb, 12);
    const longBin = glb.slice();
    new DataView(longBin.buffer).setUint32(binAt, u32(glb, binAt) + 1000, true);
    const notJson = glb.slice();
    notJson[20] = 0x23; // '#' for the JSON's opening brace
    for (const [name, bytes, message] of [
      ['long-bin.glb', longBin, /^lantern: error: long-bin\.glb is damaged: its BIN chunk at byte [\d,]+ claims [\d.]+ kB, the file has [\d.]+ kB after it\. /],
      ['not-json.glb', notJson, /^lantern: error: not-json\.glb is damaged: its JSON chunk is not JSON \(/],
    ] as const) {
      writeFileSync(join(dir, name), bytes);
      const r = runLantern(['render', join(dir, name), '-W', '8', '-H', '8'], noDriver());
      expect(r.code, name).toBe(1);
      expect(r.stderr, name).toMatch(message);
      expect(r.stderr.split('\n'), name).toHaveLength(2);
    }
  });
});
