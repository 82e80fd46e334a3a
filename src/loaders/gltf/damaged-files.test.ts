/**
 * Truncated and damaged glTF files, made from a sound one: each error says what is wrong in the
 * file's terms (what the header or a chunk claims, what the file has), and the early check the CLI
 * runs before the GPU starts (checkGltfFile) says the same from the GLB's head alone.
 */
import { Document, WebIO } from '@gltf-transform/core';
import { EXTMeshoptCompression } from '@gltf-transform/extensions';
import { MeshoptEncoder } from 'meshoptimizer/encoder';
import { describe, expect, it } from 'vitest';
import { glbOf } from './test-glb.ts';
import { LanternError } from '../../errors.ts';
import { checkGltfFile } from './document.ts';
import { byteSizes } from './glb.ts';
import { loadGltf } from './index.ts';

/** A quad mesh and 200 kB of vertex data (so that the BIN chunk dwarfs the JSON). */
async function sound(): Promise<{ glb: Uint8Array; json: Record<string, unknown>; bin: Uint8Array }> {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const positions = new Float32Array(3 * 16_384).map((_, i) => (i * 0.37) % 1);
  const prim = doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(positions).setBuffer(buffer));
  doc.createScene().addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(prim)));
  const io = new WebIO();
  const glb = await io.writeBinary(doc);
  const { json, resources } = await io.writeJSON(doc, { format: 1 as never });
  return { glb, json: json as unknown as Record<string, unknown>, bin: Object.values(resources)[0]! };
}

/** A GLB assembled by hand (test-glb.ts): its buffer is the BIN chunk, so no uri. */
function assemble(json: Record<string, unknown>, bin: Uint8Array): Uint8Array {
  const buffers = (json.buffers as { uri?: string }[]).map(({ uri: _, ...rest }) => rest);
  return glbOf({ ...json, buffers }, bin);
}

async function loadError(bytes: Uint8Array, resources: Record<string, Uint8Array> = {}, name = 'model.glb'): Promise<string> {
  try {
    await loadGltf({ name, bytes }, async (uri) => resources[uri]);
  } catch (e) {
    expect(e).toBeInstanceOf(LanternError);
    return (e as LanternError).userMessage;
  }
  throw new Error('the damaged file loaded');
}

/** checkGltfFile's error, and how many bytes it read. */
function earlyCheck(bytes: Uint8Array): { message: string | undefined; bytesRead: number } {
  let bytesRead = 0;
  try {
    checkGltfFile('model.glb', bytes.length, (offset, length) => {
      const range = bytes.subarray(offset, offset + length);
      bytesRead += range.length;
      return range;
    });
  } catch (e) {
    expect(e).toBeInstanceOf(LanternError);
    return { message: (e as LanternError).userMessage, bytesRead };
  }
  return { message: undefined, bytesRead };
}

const u32 = (bytes: Uint8Array, at: number) => new DataView(bytes.buffer, bytes.byteOffset).getUint32(at, true);
function patched(bytes: Uint8Array, at: number, value: number): Uint8Array {
  const copy = bytes.slice();
  new DataView(copy.buffer).setUint32(at, value, true);
  return copy;
}

describe('a damaged glTF file', () => {
  it('is sound to begin with: it loads, and the early check passes reading only the head', async () => {
    const { glb } = await sound();
    await expect(loadGltf({ name: 'model.glb', bytes: glb }, async () => undefined)).resolves.toBeDefined();
    const check = earlyCheck(glb);
    expect(check.message).toBeUndefined();
    // The headers (file, JSON chunk, BIN chunk) and the JSON: not the 190 kB of the BIN chunk.
    expect(check.bytesRead).toBeLessThanOrEqual(u32(glb, 12) + 64);
    expect(glb.length).toBeGreaterThan(190_000);
  });

  it('a meshopt-compressed GLB is not damaged: its fallback buffer holds nothing to check views against', async () => {
    const doc = new Document();
    const buffer = doc.createBuffer();
    const positions = new Float32Array(3 * 4096).map((_, i) => (i * 0.37) % 1);
    const prim = doc.createPrimitive().setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(positions).setBuffer(buffer));
    doc.createScene().addChild(doc.createNode().setMesh(doc.createMesh().addPrimitive(prim)));
    doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.QUANTIZE });
    await MeshoptEncoder.ready;
    const glb = await new WebIO().registerExtensions([EXTMeshoptCompression]).registerDependencies({ 'meshopt.encoder': MeshoptEncoder }).writeBinary(doc);
    const scene = await loadGltf({ name: 'meshopt.glb', bytes: glb }, async () => undefined);
    expect(scene.meshes[0]!.positions.length).toBe(positions.length);
    expect(earlyCheck(glb).message).toBeUndefined();
  });

  it('truncated: the length its header gives and the length it has', async () => {
    const { glb } = await sound();
    const cut = glb.subarray(0, Math.floor(glb.length * 0.4));
    const [claimed, has] = byteSizes(glb.length, cut.length);
    const message = `model.glb is truncated: its GLB header gives its length as ${claimed}, the file has ${has}`;
    expect(claimed).toMatch(/^\d+(\.\d+)? kB$/);
    expect(await loadError(cut)).toMatch(new RegExp(`^${message}\\. `));
    expect(earlyCheck(cut).message).toBe(await loadError(cut));
    // Cut by a few bytes, the sizes are exact.
    expect(await loadError(glb.subarray(0, glb.length - 3))).toMatch(`gives its length as ${glb.length.toLocaleString('en-US')} bytes, the file has ${(glb.length - 3).toLocaleString('en-US')} bytes`);
  });

  it('a chunk claiming more than the file holds after it', async () => {
    const { glb } = await sound();
    const jsonLength = u32(glb, 12);
    const binAt = 20 + jsonLength;
    const longBin = patched(glb, binAt, u32(glb, binAt) + 4096);
    const [claimed, left] = byteSizes(u32(glb, binAt) + 4096, glb.length - binAt - 8);
    expect(await loadError(longBin)).toMatch(`model.glb is damaged: its BIN chunk at byte ${binAt.toLocaleString('en-US')} claims ${claimed}, the file has ${left} after it`);
    expect(earlyCheck(longBin).message).toBe(await loadError(longBin));
    const longJson = patched(glb, 12, 1 << 30);
    expect(await loadError(longJson)).toMatch(/^model\.glb is damaged: its JSON chunk at byte 12 claims 1\.07 GB, the file has [\d.]+ kB after it/);
  });

  it('a JSON chunk that is not JSON', async () => {
    const { glb } = await sound();
    const broken = glb.slice();
    // Its opening brace overwritten: the rest is no JSON value.
    broken.set(new TextEncoder().encode('#'), 20);
    expect(await loadError(broken)).toMatch(/^model\.glb is damaged: its JSON chunk is not JSON \(.*\)/);
    expect(earlyCheck(broken).message).toBe(await loadError(broken));
  });

  it('a BIN chunk shorter than its buffer', async () => {
    const { json, bin } = await sound();
    const short = assemble(json, bin.subarray(0, 100_000));
    const [has, declared] = byteSizes(100_000, bin.length);
    expect(await loadError(short)).toMatch(`model.glb is truncated: its BIN chunk holds ${has}, its buffer 0 declares ${declared}`);
    expect(earlyCheck(short).message).toBe(await loadError(short));
  });

  it('a .bin shorter than its buffer, and a buffer view past its buffer', async () => {
    const { json, bin } = await sound();
    const buffers = json.buffers as { uri: string; byteLength: number }[];
    const uri = buffers[0]!.uri;
    const gltf = (j: unknown) => new TextEncoder().encode(JSON.stringify(j));
    const [has, declared] = byteSizes(bin.length - 64, bin.length);
    expect(await loadError(gltf(json), { [uri]: bin.subarray(0, bin.length - 64) }, 'model.gltf')).toMatch(`model.gltf: buffer 0 ('${uri}') has ${has}, the model declares ${declared}`);
    const views = structuredClone(json.bufferViews) as { byteLength: number }[];
    views[0]!.byteLength += 8;
    expect(await loadError(gltf({ ...json, bufferViews: views }), { [uri]: bin }, 'model.gltf')).toMatch(/^model\.gltf: buffer view 0 \(0 \+ [\d,]+ bytes\) does not fit in buffer 0 \([\d,]+ bytes\)/);
    // A buffer must say how long it is (glTF requires byteLength): the views are held to it.
    const undeclared = (json.buffers as object[]).map((b) => ({ ...b, byteLength: undefined }));
    expect(await loadError(gltf({ ...json, buffers: undeclared, bufferViews: views }), { [uri]: bin }, 'model.gltf')).toMatch(/^model\.gltf: buffer 0 declares no byteLength\./);
  });
});
