/**
 * One fuzz target per loader: seed inputs built in code, a structure-aware mutator that knows where
 * the format keeps its counts, sizes, offsets and indices, and the code path `lantern info` (scenes)
 * or `lantern diff` (images) runs on the file. A case passes when it loads or is refused with a
 * LanternError; anything else thrown is a crash. Time and memory are judged by the callers.
 */
import { gzipSync } from 'node:zlib';
import { LanternError } from '../../src/errors.ts';
import { decodeExr, decodeExrRgb, encodeExr, exrToRgb } from '../../src/image/exr.ts';
import { decodeHdr } from '../../src/image/hdr.ts';
import { decodePng, encodePng } from '../../src/image/png.ts';
import { animatedRoomWad, encodeMap, encodePalette, squareRoomWad, twoRooms, WadBuilder } from '../../src/loaders/doom/test-wad.ts';
import { readWad } from '../../src/loaders/doom/wad.ts';
import { NO_SIBLINGS, type FileSet, type NamedBytes, type SceneFormat } from '../../src/loaders/format.ts';
import { formatOfSet } from '../../src/loaders/registry.ts';
import { testGameFiles } from '../../src/loaders/wolf3d/test-files.ts';
import { bigSectorMap, bigTexturesWad, danglingSegmentsMap, gridMap, gzipBomb, hugeExr, manyLumpsWad, missingPatchesWad, noPlayerStartMap, randomLinesMap, wadOf } from './crafted.ts';
import { countBombGltf, externalBufferGltf, glbOf, pngStreamBomb, progressiveJpeg, sharedImageGlb, zeroScaleGltf } from './crafted.ts';
import { DEFAULT_LIMITS } from '../../src/budgets.ts';
import { cameraBasis } from '../../src/gpu/view.ts';
import { cameraAt, frameTime, parseCameraPath } from '../../src/scene/camera-path.ts';
import type { Camera } from '../../src/scene/types.ts';
import { constantExr, constantHdr, hubMolfile, wolfWarningFloodFiles } from './crafted.ts';
import { compareImages, errorHeatmap } from '../../src/image/compare.ts';
import { loadEnvironmentImage } from '../../src/loaders/environment-image.ts';
import { packEnvironment } from '../../src/gpu/pack/environment-pack.ts';
import { concat, interesting, mutateBytes, mutateLines, putInt, Rng } from './mutate.ts';

export interface FuzzTarget {
  /** Short id: reproducers are saved under it. */
  readonly id: string;
  /** The input class, as the table names it. */
  readonly label: string;
  /**
   * The input of case `index` from its generator: mutated targets ignore `index`, crafted ones
   * (a fixed list) take input `index % count`.
   */
  input(rng: Rng, index: number): NamedBytes[];
  /** How many distinct inputs a crafted target has (undefined: unlimited). */
  readonly count?: number;
  /** The code path of the CLI command that reads this kind of file. */
  run(files: NamedBytes[]): Promise<void>;
}

/**
 * `lantern info`: the format from the bytes, the set opened, and its inventory (which builds every
 * map) or, for a format without one, its scene.
 */
async function infoOnly(files: NamedBytes[]): Promise<void> {
  const { format, files: ordered } = formatOfSet(files.map((f) => ({ ...f, head: f.bytes.subarray(0, 1024) })));
  const opened = await (format as SceneFormat).open({ files: ordered.map(({ name, bytes }) => ({ name, bytes })), resolve: NO_SIBLINGS });
  if (opened.inventory) opened.inventory();
  else await opened.scene(undefined, { onWarning: () => {} });
}

/** `lantern info`, then the scenes `render` would build: each part's (the first three), through the format's own scene path. */
async function infoPath(files: NamedBytes[]): Promise<void> {
  const { format, files: ordered } = formatOfSet(files.map((f) => ({ ...f, head: f.bytes.subarray(0, 1024) })));
  const set: FileSet = { files: ordered.map(({ name, bytes }) => ({ name, bytes })), resolve: NO_SIBLINGS };
  const opened = await (format as SceneFormat).open(set);
  opened.inventory?.();
  const parts = opened.parts.filter((p) => p.loadable).slice(0, 3);
  const warnings: string[] = [];
  const onWarning = (w: string) => void warnings.push(w);
  // Warnings are capped per kind (budgets.ts WarningCap); thousands of lines from one scene are a flood.
  const scene = async (part: string | undefined) => {
    warnings.length = 0;
    await opened.scene(part, { onWarning });
    if (warnings.length > WARNING_FLOOD) throw new Error(`warning flood: ${warnings.length} lines, the first "${warnings[0]}"`);
  };
  if (parts.length === 0) await scene(undefined);
  for (const p of parts) await scene(p.name);
}

/** Lines of warnings one scene may print before the fuzzer calls it a flood (a cap per kind keeps real loads far below). */
const WARNING_FLOOD = 1000;

/** `lantern diff`: both images decoded to RGB as diff does, and as planes converted to RGB. */
async function exrPath(files: NamedBytes[]): Promise<void> {
  for (const f of files) {
    decodeExrRgb(f.bytes, f.name);
    exrToRgb(decodeExr(f.bytes, f.name));
  }
}

/** All of `lantern diff --heatmap`: both images decoded to RGB, compared, the heat map encoded. */
async function diffPath(files: NamedBytes[]): Promise<void> {
  const [a, b] = files.map((f) => decodeExrRgb(f.bytes, f.name)) as [ReturnType<typeof decodeExrRgb>, ReturnType<typeof decodeExrRgb>];
  compareImages(a, b);
  encodePng(a.width, a.height, errorHeatmap(a, b));
}

/** `--env`: the map decoded and packed (its sampling tables built), as the scene thread does. */
async function environmentPath(files: NamedBytes[]): Promise<void> {
  const image = loadEnvironmentImage(files[0]!.bytes, files[0]!.name);
  packEnvironment({ kind: 'map', image, rotationDeg: 0, intensity: 1 });
}

/** The imagePixels limit's own shape, 8192×4096 (an 8K lat-long map). */
const LIMIT_SIDES = [8192, DEFAULT_LIMITS.imagePixels / 8192] as const;

// ---- WAD ----

const WAD_SEED_MAKERS: Array<() => Uint8Array> = [
  () => squareRoomWad(),
  () => animatedRoomWad(),
  () => new WadBuilder().lump('PLAYPAL', encodePalette()).lumps(encodeMap({ ...twoRooms({}, 'door'), name: 'MAP01' })).build('IWAD'),
];
let wadSeeds: Uint8Array[] | undefined;
const WAD_SEEDS = () => (wadSeeds ??= WAD_SEED_MAKERS.map((make) => make()));

/** Knows the directory, the map lumps' record layouts, TEXTURE1, PNAMES and pictures. */
export function mutateWad(rng: Rng, seed: Uint8Array): Uint8Array {
  let wad;
  try {
    wad = readWad(seed, 'seed.wad');
  } catch {
    return mutateBytes(rng, seed);
  }
  const bytes = seed.slice();
  const lumps = wad.lumps.filter((l) => l.size > 0);
  const dirOffset = new DataView(bytes.buffer).getInt32(8, true);
  const lump = (name: string) => lumps.find((l) => l.name === name);
  const record = (name: string, size: number, field: number, width: 1 | 2 | 4) => {
    const l = lump(name);
    if (!l || l.size < size) return;
    const n = Math.floor(l.size / size);
    putInt(bytes, l.offset + rng.int(n) * size + field, width, interesting(rng, n));
  };
  switch (rng.int(12)) {
    case 0: // a directory entry's offset or size
      putInt(bytes, dirOffset + 16 * rng.int(wad.lumps.length) + rng.pick([0, 4]), 4, interesting(rng));
      break;
    case 1: // the header's lump count or directory offset
      putInt(bytes, rng.pick([4, 8]), 4, interesting(rng, wad.lumps.length));
      break;
    case 2: // a lump renamed (a map lump lost, a marker moved)
      putInt(bytes, dirOffset + 16 * rng.int(wad.lumps.length) + 8 + rng.int(8), 1, rng.pick([0, 0x41, 0x5f, 0x31, rng.int(256)]));
      break;
    case 3: // linedef vertex or sidedef indices
      record('LINEDEFS', 14, rng.pick([0, 2, 10, 12]), 2);
      break;
    case 4: // vertex coordinates at the edges, or one vertex made another's
      record('VERTEXES', 4, rng.pick([0, 2]), 2);
      break;
    case 5: // sidedef sector, sector heights and light
      if (rng.chance(0.5)) record('SIDEDEFS', 30, 28, 2);
      else record('SECTORS', 26, rng.pick([0, 2, 20, 22, 24]), 2);
      break;
    case 6: // things: type, position, flags
      record('THINGS', 10, rng.pick([0, 2, 6, 8]), 2);
      break;
    case 7: { // TEXTURE1: count, an offset, or a texture's width, height or patch count
      const l = lump('TEXTURE1');
      if (!l || l.size < 8) return mutateBytes(rng, bytes);
      const view = new DataView(bytes.buffer, l.offset, l.size);
      const count = view.getInt32(0, true);
      if (rng.chance(0.3) || count <= 0) putInt(bytes, l.offset, 4, interesting(rng, count));
      else {
        const at = view.getInt32(4 + 4 * rng.int(Math.min(count, (l.size - 4) >> 2)), true);
        putInt(bytes, l.offset + at + rng.pick([12, 14, 20, 22, 24, 26]), 2, interesting(rng));
      }
      break;
    }
    case 8: { // PNAMES count or a name
      const l = lump('PNAMES');
      if (!l) return mutateBytes(rng, bytes);
      if (rng.chance(0.5)) putInt(bytes, l.offset, 4, interesting(rng));
      else putInt(bytes, l.offset + 4 + rng.int(Math.max(1, l.size - 4)), 1, rng.int(256));
      break;
    }
    case 9: { // a picture's size, offsets or a column offset
      const pictures = lumps.filter((l) => /PAT|WALL|SKY/.test(l.name));
      if (pictures.length === 0) return mutateBytes(rng, bytes);
      const l = rng.pick(pictures);
      putInt(bytes, l.offset + rng.pick([0, 2, 4, 6, 8, 12, 16]), rng.pick([2, 4] as const), interesting(rng));
      break;
    }
    case 10: { // bytes inside one lump (a mutated WAD may have none left with bytes)
      if (lumps.length === 0) return mutateBytes(rng, bytes);
      const l = rng.pick(lumps);
      return mutateBytes(rng, bytes, l.offset, l.offset + l.size);
    }
    default:
      return mutateBytes(rng, bytes);
  }
  return bytes;
}

// ---- PLY ----

/**
 * A PLY generated with lies: counts that disagree with the body, list counts, indices out of range,
 * NaN/Inf coordinates, n-gons, odd property types, either endianness or ascii, sometimes gzipped.
 */
function generatePly(rng: Rng): Uint8Array {
  const format = rng.pick(['ascii', 'binary_little_endian', 'binary_big_endian'] as const);
  const nv = 3 + rng.int(20);
  const nf = 1 + rng.int(20);
  const lie = (n: number) => (rng.chance(0.15) ? interesting(rng, n) : n);
  const posType = rng.pick(['float', 'double', 'float32', 'int', 'uchar']);
  const countType = rng.pick(['uchar', 'uchar', 'ushort', 'int', 'uint', 'char']);
  const indexType = rng.pick(['int', 'uint', 'int32', 'ushort', 'uchar']);
  const normals = rng.chance(0.3);
  const extra = rng.chance(0.2);
  const header = [
    'ply',
    `format ${format} 1.0`,
    ...(rng.chance(0.3) ? ['comment fuzz'] : []),
    ...(extra && rng.chance(0.5) ? [`element junk ${lie(2)}`, 'property list uchar int stuff'] : []),
    `element vertex ${lie(nv)}`,
    `property ${posType} x`, `property ${posType} y`, `property ${posType} z`,
    ...(normals ? ['property float nx', 'property float ny', 'property float nz'] : []),
    `element face ${lie(nf)}`,
    `property list ${countType} ${indexType} vertex_indices`,
    ...(extra ? [`element edge ${lie(1)}`, 'property int vertex1'] : []),
    'end_header',
  ];
  let head = header.join('\n') + '\n';
  if (rng.chance(0.2)) head = mutateLines(rng, head, 1);
  const values: Array<{ type: string; v: number }> = [];
  if (extra && header.some((l) => l.startsWith('element junk'))) values.push({ type: 'uchar', v: 1 }, { type: 'int', v: 5 }, { type: 'uchar', v: 0 });
  for (let i = 0; i < nv; i++) {
    for (let k = 0; k < 3; k++) values.push({ type: posType, v: rng.chance(0.03) ? rng.pick([NaN, Infinity, -Infinity, 1e308]) : rng.int(200) - 100 });
    if (normals) for (let k = 0; k < 3; k++) values.push({ type: 'float', v: rng.next() });
  }
  for (let f = 0; f < nf; f++) {
    const m = rng.chance(0.1) ? interesting(rng) & 0xffff : rng.pick([3, 3, 3, 4, 5, 8, 2, 0]);
    values.push({ type: countType, v: m });
    for (let j = 0; j < Math.min(m, 64); j++) values.push({ type: indexType, v: rng.chance(0.05) ? interesting(rng, nv) : rng.int(nv) });
  }
  if (extra) values.push({ type: 'int', v: 0 });
  let body: Uint8Array;
  if (format === 'ascii') body = new TextEncoder().encode(values.map((x) => String(x.v)).join(rng.chance(0.9) ? ' ' : '\n') + '\n');
  else {
    const little = format === 'binary_little_endian';
    const size: Record<string, number> = { float: 4, float32: 4, double: 8, int: 4, int32: 4, uint: 4, uchar: 1, char: 1, ushort: 2 };
    const view = new DataView(new ArrayBuffer(values.reduce((n, x) => n + size[x.type]!, 0)));
    let at = 0;
    for (const { type, v } of values) {
      if (type === 'float' || type === 'float32') view.setFloat32(at, v, little);
      else if (type === 'double') view.setFloat64(at, v, little);
      else if (size[type] === 4) view.setInt32(at, v | 0, little);
      else if (size[type] === 2) view.setUint16(at, v & 0xffff, little);
      else view.setUint8(at, v & 0xff);
      at += size[type]!;
    }
    body = new Uint8Array(view.buffer);
  }
  let bytes = concat(new TextEncoder().encode(head), body);
  if (rng.chance(0.25)) bytes = mutateBytes(rng, bytes);
  if (rng.chance(0.25)) {
    bytes = new Uint8Array(gzipSync(bytes));
    if (rng.chance(0.3)) bytes = mutateBytes(rng, bytes);
  }
  return bytes;
}

// ---- glTF / GLB ----

/** A textured triangle as GLB (or as .gltf with a data: URI): positions, uvs, indices, a PNG. */
export function gltfSeed(rng: Rng): { json: Record<string, unknown>; bin: Uint8Array } {
  const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]);
  const uvs = new Float32Array([0, 0, 1, 0, 0, 1]);
  const indices = new Uint16Array([0, 1, 2, 0]);
  const png = encodePng(2, 2, new Uint8Array(16).fill(200));
  const parts = [new Uint8Array(positions.buffer), new Uint8Array(uvs.buffer), new Uint8Array(indices.buffer), png];
  const views: Array<{ buffer: number; byteOffset: number; byteLength: number }> = [];
  let at = 0;
  for (const p of parts) {
    views.push({ buffer: 0, byteOffset: at, byteLength: p.length });
    at += (p.length + 3) & ~3;
  }
  const bin = new Uint8Array(at);
  parts.forEach((p, i) => bin.set(p, views[i]!.byteOffset));
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, ...(rng.chance(0.3) ? { scale: [2, 2, 2] } : {}) }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, material: 0 }] }],
    materials: [{ pbrMetallicRoughness: { baseColorTexture: { index: 0 }, baseColorFactor: [1, 1, 1, 1] } }],
    textures: [{ source: 0 }],
    images: [{ bufferView: 3, mimeType: 'image/png' }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] },
      { bufferView: 1, componentType: 5126, count: 3, type: 'VEC2' },
      { bufferView: 2, componentType: 5123, count: 3, type: 'SCALAR' },
    ],
    bufferViews: views,
    buffers: [{ byteLength: bin.length }],
  };
  return { json, bin };
}

/** Bends one number, deletes one key or retypes one value somewhere in the JSON tree. */
function mutateJson(rng: Rng, value: unknown, depth = 0): unknown {
  if (Array.isArray(value)) {
    if (value.length === 0 || rng.chance(0.1)) return rng.chance(0.5) ? [] : [...value, ...value];
    const copy = [...value];
    const i = rng.int(copy.length);
    copy[i] = mutateJson(rng, copy[i], depth + 1);
    return copy;
  }
  if (value && typeof value === 'object') {
    const entries = Object.entries(value as Record<string, unknown>);
    if (entries.length === 0) return value;
    const [k, v] = rng.pick(entries);
    const copy: Record<string, unknown> = { ...(value as Record<string, unknown>) };
    if (rng.chance(0.1) && depth > 0) delete copy[k];
    else copy[k] = mutateJson(rng, v, depth + 1);
    return copy;
  }
  if (typeof value === 'number') return rng.chance(0.85) ? interesting(rng, value) : rng.pick([0.5, -0.5, 1e308, null, 'x', [], {}]);
  if (typeof value === 'string') return rng.pick(['', 'VEC4', 'MAT4', 'SCALAR', 'image/jpeg', 'data:,', '../../etc/passwd', 'x'.repeat(300)]);
  return rng.pick([0, null, 'x', {}]);
}

/** A GLB of a JSON chunk and a binary chunk (crafted.ts builds it). */
export const glb = glbOf;

function generateGltf(rng: Rng): NamedBytes {
  const seed = gltfSeed(rng);
  const { json, bin } = rng.chance(0.4) ? mutateGltfStructure(rng, seed) : seed;
  let j: unknown = json;
  for (let r = rng.int(3); r > 0; r--) j = mutateJson(rng, j);
  let b = rng.chance(0.3) ? mutateBytes(rng, bin) : bin;
  if (rng.chance(0.3)) {
    // .gltf text with the buffer as a data: URI.
    const withUri = { ...(j as Record<string, unknown>), buffers: [{ byteLength: b.length, uri: `data:application/octet-stream;base64,${Buffer.from(b).toString('base64')}` }] };
    let text: Uint8Array = new TextEncoder().encode(JSON.stringify(withUri));
    if (rng.chance(0.2)) text = mutateBytes(rng, text);
    return { name: 'fuzz.gltf', bytes: text };
  }
  let out = glb(j, b);
  if (rng.chance(0.3)) {
    // A chunk or header length that lies.
    putInt(out, rng.pick([8, 12, 20 + ((out.length - 28 - b.length) & ~3)]), 4, interesting(rng, out.length));
  }
  if (rng.chance(0.1)) out = out.slice(0, rng.int(out.length));
  return { name: 'fuzz.glb', bytes: out };
}

/** Counts just past the default limits, and far past them (glTF-Transform once allocated them all). */
const HUGE_COUNTS = [DEFAULT_LIMITS.vertices + 1, DEFAULT_LIMITS.instances + 1, 1.5e8, 1e9, 2 ** 31 - 1, 2 ** 32, 2 ** 53];
/** URIs a model may not name (loaders/sibling-uri.ts), in the spellings that reach other files. */
const ESCAPING_URIS = ['../../../../../../etc/hostname', '/etc/hostname', 'file:///etc/hostname', 'http://127.0.0.1:1/x.bin', 'https://example.com/x.png', '%2e%2e/%2e%2e/etc/hostname', '..\\..\\etc\\hostname', 'C:\\Windows\\win.ini', '//server/share/x.bin', 'textures/../../x.bin', ''];

/** Images that cost more to decode than their bytes suggest, built once: a 2048² PNG of zeros (17 KB), a 30,000-scan progressive JPEG, a PNG whose stream inflates past its size. */
let costlyImages: Uint8Array[] | undefined;
const COSTLY_IMAGES = () => (costlyImages ??= [encodePng(2048, 2048, new Uint8Array(2048 * 2048 * 4)), progressiveJpeg(1024, 1024, 30_000), pngStreamBomb(16, 64 * 2 ** 20)]);

/**
 * Mutations that know glTF's structure: an accessor's count (or its sparse count, or
 * EXT_mesh_gpu_instancing's rows) past the limits, with or without its buffer view; a node scaled to
 * zero or past the float range carrying a camera, a light or the mesh; the image swapped for a costly
 * one, shared by up to a thousand images; a buffer or image URI out of the model's folder.
 */
export function mutateGltfStructure(rng: Rng, seed: { json: Record<string, unknown>; bin: Uint8Array }): { json: Record<string, unknown>; bin: Uint8Array } {
  const json = structuredClone(seed.json) as Record<string, any>;
  let bin = seed.bin;
  const accessors = json.accessors as Array<Record<string, unknown>>;
  switch (rng.int(6)) {
    case 0: { // a count past the limits; without a buffer view glTF-Transform zero-fills it
      const a = rng.pick(accessors);
      a.count = rng.pick(HUGE_COUNTS);
      if (rng.chance(0.6)) delete a.bufferView;
      break;
    }
    case 1: { // a sparse block: count huge, or past its accessor's
      const a = rng.pick(accessors);
      a.sparse = { count: rng.pick([...HUGE_COUNTS, (a.count as number) + 1, 0, 1]), indices: { bufferView: 2, componentType: 5123 }, values: { bufferView: 0 } };
      if (rng.chance(0.5)) delete a.bufferView;
      break;
    }
    case 2: { // EXT_mesh_gpu_instancing rows
      json.extensionsUsed = ['EXT_mesh_gpu_instancing'];
      accessors.push({ componentType: 5126, count: rng.pick([...HUGE_COUNTS, 4, 1000]), type: 'VEC3' });
      json.nodes[0].extensions = { EXT_mesh_gpu_instancing: { attributes: { [rng.pick(['TRANSLATION', 'SCALE'])]: accessors.length - 1 } } };
      break;
    }
    case 3: { // a degenerate node (zero scale, or 1e308 twice over: infinite) with a camera, a light or the mesh
      const scale = rng.pick([[0, 0, 0], [1, 0, 1], [1e308, 1e308, 1e308]]);
      const what = rng.pick(['camera', 'spot', 'directional', 'point', 'mesh']);
      const node: Record<string, unknown> = { scale };
      if (what === 'camera') {
        json.cameras = [{ type: rng.pick(['perspective', 'orthographic']), perspective: { yfov: rng.pick([0.8, 0, 1e308]), znear: 0.1 }, orthographic: { xmag: 1, ymag: rng.pick([1, 1e308]), znear: 0, zfar: 1 } }];
        node.camera = 0;
      } else if (what === 'mesh') node.mesh = 0;
      else {
        json.extensionsUsed = ['KHR_lights_punctual'];
        json.extensions = { KHR_lights_punctual: { lights: [{ type: what, intensity: 1, ...(what === 'spot' ? { spot: {} } : {}) }] } };
        node.extensions = { KHR_lights_punctual: { light: 0 } };
      }
      // Nested under a second 1e308 scale, the product is infinite.
      json.nodes.push(rng.chance(0.5) ? node : { scale: [1e308, 1e308, 1e308], children: [json.nodes.length + 1] }, node);
      json.scenes[0].nodes.push(json.nodes.length - 2);
      break;
    }
    case 4: { // a costly image, shared by many images (each its own texture, material and primitive)
      const image = rng.pick(COSTLY_IMAGES());
      const at = (bin.length + 3) & ~3;
      bin = concat(bin, new Uint8Array(at - bin.length), image);
      json.bufferViews.push({ buffer: 0, byteOffset: at, byteLength: image.length });
      json.buffers[0].byteLength = bin.length;
      const n = rng.pick([1, 2, 100, 1000]);
      json.images = Array.from({ length: n }, () => ({ bufferView: json.bufferViews.length - 1, mimeType: 'image/png' }));
      json.textures = json.images.map((_: unknown, i: number) => ({ source: i }));
      json.materials = json.images.map((_: unknown, i: number) => ({ pbrMetallicRoughness: { baseColorTexture: { index: i } } }));
      json.meshes[0].primitives = json.images.map((_: unknown, i: number) => ({ ...json.meshes[0].primitives[0], material: i }));
      break;
    }
    default: { // a URI out of the model's folder, for the buffer or the image
      const uri = rng.pick(ESCAPING_URIS);
      if (rng.chance(0.5)) json.images = [{ uri }];
      else {
        json.buffers.push({ byteLength: 36, uri });
        json.bufferViews[0].buffer = 1;
      }
    }
  }
  return { json, bin };
}

// ---- camera paths (`render --path`) ----

/** A camera path of a few keyframes, its times, positions or fields of view sometimes pushed to the edges (±1e308, past ±1e6 s, out of order). */
function generatePath(rng: Rng): NamedBytes {
  let t = rng.pick([0, -5, 1e5]);
  const keyframes: Array<Record<string, unknown>> = Array.from({ length: 1 + rng.int(4) }, (_, i) => ({
    time: (t += 0.5 + rng.int(3)),
    position: [i, 1, 5],
    target: [0, 0, 0],
    ...(rng.chance(0.3) ? { fov: 30 + rng.int(60) } : {}),
  }));
  const edge = () => rng.pick([1e308, -1e308, 1e6, 1e6 + 1, -1e6, 5e-324, 1e7, 1e7 + 1, 0, null, 'x']);
  for (let r = 1 + rng.int(2); r > 0; r--) {
    const k = rng.pick(keyframes);
    switch (rng.int(5)) {
      case 0: k.time = edge(); break;
      case 1: k.position = [edge(), 0, 5]; break;
      case 2: k.target = k.position; break;
      case 3: k.fov = edge(); break;
      default: keyframes.reverse();
    }
  }
  let text = JSON.stringify({ keyframes });
  if (rng.chance(0.1)) text = mutateLines(rng, text.replaceAll('},', '},\n'));
  return { name: 'path.json', bytes: new TextEncoder().encode(text) };
}

/** What `render --path` does with the file before and while it renders: parse and check it, and set up every frame's camera (30 frames, the default). */
async function pathPath(files: NamedBytes[]): Promise<void> {
  let json: unknown;
  try {
    json = JSON.parse(new TextDecoder().decode(files[0]!.bytes));
  } catch (e) {
    throw new LanternError(`path.json is not valid JSON: ${(e as Error).message}`);
  }
  const path = parseCameraPath(json, 'path.json');
  const base: Camera = { position: [0, 0, 5], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 };
  for (let f = 0; f < 30; f++) {
    const camera = cameraAt(path, frameTime(path, f, 30), base);
    const basis = cameraBasis(camera, 16 / 9);
    if (![...basis.position, ...basis.forward, ...basis.right, ...basis.up].every(Number.isFinite)) throw new Error(`frame ${f}: the camera is not finite`);
  }
}

/** The inputs of issue 27 §6 that once ran for minutes, took gigabytes or ended in an internal error, built on demand. */
const CRAFTED_GLTF: Array<[string, () => NamedBytes]> = [
  ['1.5e8 vertices without a buffer view.gltf', () => ({ name: 'positions.gltf', bytes: countBombGltf('positions', 1.5e8) })],
  ['5e7 vertices without a buffer view.gltf', () => ({ name: 'positions.gltf', bytes: countBombGltf('positions', 5e7) })],
  ['1e9 indices without a buffer view.gltf', () => ({ name: 'indices.gltf', bytes: countBombGltf('indices', 1e9) })],
  ['sparse count 1e9.gltf', () => ({ name: 'sparse.gltf', bytes: countBombGltf('sparse', 1e9) })],
  ['1e9 interleaved vertices over 36 bytes.gltf', () => ({ name: 'interleaved.gltf', bytes: countBombGltf('interleaved', 1e9) })],
  ['1e7 instances.gltf', () => ({ name: 'instances.gltf', bytes: countBombGltf('instances', 1e7) })],
  ['100 images sharing one 5792² PNG.glb', () => ({ name: 'shared.glb', bytes: sharedImageGlb(100, encodePng(5792, 5792, new Uint8Array(5792 * 5792 * 4))) })],
  ['a 4096² progressive JPEG of 30,000 scans.glb', () => ({ name: 'scans.glb', bytes: sharedImageGlb(1, progressiveJpeg(4096, 4096, 30_000)) })],
  ['a 16² PNG whose stream inflates to 512 MB.glb', () => ({ name: 'png-bomb.glb', bytes: sharedImageGlb(1, pngStreamBomb(16, 512 * 2 ** 20)) })],
  ['a camera on a zero-scaled node.gltf', () => ({ name: 'camera.gltf', bytes: zeroScaleGltf('camera') })],
  ['a spot light on a zero-scaled node.gltf', () => ({ name: 'spot.gltf', bytes: zeroScaleGltf('spot') })],
  ['a point light on a zero-scaled node.gltf', () => ({ name: 'point.gltf', bytes: zeroScaleGltf('point') })],
  ['a buffer at ../../../../../../etc/hostname.gltf', () => ({ name: 'escape.gltf', bytes: externalBufferGltf('../../../../../../etc/hostname') })],
  ['a buffer at file:///etc/hostname.gltf', () => ({ name: 'file-uri.gltf', bytes: externalBufferGltf('file:///etc/hostname') })],
];

// ---- EXR ----

function exrSeed(rng: Rng): Uint8Array {
  const [w, h] = [1 + rng.int(40), 1 + rng.int(40)];
  const rgb = new Float32Array(w * h * 3).map(() => rng.next() * 4);
  return encodeExr(w, h, rgb, { compression: rng.pick(['zip', 'zips', 'none'] as const), pixelType: rng.pick(['float', 'half'] as const) });
}

/** Knows the header's attributes (dataWindow, channels, compression) and the line offset table. */
function mutateExr(rng: Rng, seed: Uint8Array): Uint8Array {
  const bytes = seed.slice();
  const find = (text: string) => Buffer.from(bytes.buffer, bytes.byteOffset, bytes.length).indexOf(text);
  switch (rng.int(6)) {
    case 0: { // data window corners
      const at = find('dataWindow\0box2i\0');
      putInt(bytes, at + 21 + 4 * rng.int(4), 4, interesting(rng));
      return bytes;
    }
    case 1: { // a channel's pixel type or sampling
      const at = find('channels\0chlist\0');
      putInt(bytes, at + 24 + 2 + rng.int(24), rng.pick([1, 4] as const), interesting(rng));
      return bytes;
    }
    case 2: { // compression
      const at = find('compression\0compression\0');
      putInt(bytes, at + 28, 1, rng.int(12));
      return bytes;
    }
    case 3: { // a line offset, or a chunk's y or size
      const table = exrTableStart(bytes);
      const chunk = table + 8 * rng.int(4);
      if (rng.chance(0.5)) putInt(bytes, chunk, 4, interesting(rng, bytes.length));
      else if (table + 4 <= bytes.length) {
        const first = new DataView(bytes.buffer).getUint32(table, true);
        putInt(bytes, first + rng.pick([0, 4]), 4, interesting(rng));
      }
      return bytes;
    }
    default:
      return mutateBytes(rng, bytes);
  }
}

/** Where the line offset table starts: after the header's attributes (name, type, size, value) and its closing NUL. */
function exrTableStart(bytes: Uint8Array): number {
  let at = 8;
  const skipString = () => {
    while (at < bytes.length && bytes[at] !== 0) at++;
    at++;
  };
  while (at < bytes.length && bytes[at] !== 0) {
    skipString(); // name
    skipString(); // type
    if (at + 4 > bytes.length) break;
    const size = new DataView(bytes.buffer).getInt32(at, true);
    if (size < 0) break;
    at += 4 + size;
  }
  return at + 1;
}

// ---- HDR ----

function hdrSeed(rng: Rng): Uint8Array {
  const [w, h] = [8 + rng.int(40), 1 + rng.int(20)];
  const rle = rng.chance(0.6) && w >= 8;
  const head = new TextEncoder().encode(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1\n\n-Y ${h} +X ${w}\n`);
  const body: number[] = [];
  for (let y = 0; y < h; y++) {
    if (rle) {
      body.push(2, 2, w >> 8, w & 255);
      for (let c = 0; c < 4; c++) {
        // One run of the whole row per channel, or literal bytes.
        if (rng.chance(0.5)) body.push(128 + Math.min(w, 127), c === 3 ? 128 : rng.int(256), ...(w > 127 ? [128 + (w - 127), 1] : []));
        else for (let x = 0; x < w; x += 128) body.push(Math.min(128, w - x), ...Array.from({ length: Math.min(128, w - x) }, () => (c === 3 ? 128 : rng.int(256))));
      }
    } else for (let x = 0; x < w; x++) body.push(rng.int(256), rng.int(256), rng.int(256), 128);
  }
  return concat(head, new Uint8Array(body));
}

function mutateHdr(rng: Rng, seed: Uint8Array): Uint8Array {
  const text = new TextDecoder('latin1').decode(seed);
  const res = text.indexOf('-Y ');
  if (rng.chance(0.3) && res >= 0) {
    const line = text.slice(res, text.indexOf('\n', res));
    const bent = mutateLines(rng, line, 1);
    return concat(seed.subarray(0, res), new TextEncoder().encode(bent), seed.subarray(res + line.length));
  }
  return mutateBytes(rng, seed, rng.chance(0.5) ? Math.max(0, text.indexOf('\n', res) + 1) : 0);
}

// ---- PNG ----

function pngSeed(rng: Rng): Uint8Array {
  const [w, h] = [1 + rng.int(16), 1 + rng.int(16)];
  return encodePng(w, h, new Uint8Array(w * h * 4).map(() => rng.int(256)));
}

const CRC_TABLE = new Uint32Array(256).map((_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c;
});

/** IHDR fields (width, height, depth, colour type), IDAT bytes; the CRCs rewritten half the time so the decoder goes past them. */
function mutatePng(rng: Rng, seed: Uint8Array): Uint8Array {
  let bytes: Uint8Array = seed.slice();
  if (rng.chance(0.5)) putInt(bytes, rng.pick([16, 20]), 4, interesting(rng), false);
  else if (rng.chance(0.5)) bytes[rng.pick([24, 25, 26, 27, 28])] = rng.pick([0, 1, 2, 3, 4, 6, 8, 16, 255]);
  else bytes = mutateBytes(rng, bytes, 33);
  if (rng.chance(0.5)) {
    for (let at = 8; at + 12 <= bytes.length; ) {
      const len = new DataView(bytes.buffer).getUint32(at);
      if (at + 12 + len > bytes.length) break;
      let c = 0xffffffff;
      for (let i = at + 4; i < at + 8 + len; i++) c = CRC_TABLE[(c ^ bytes[i]!) & 0xff]! ^ (c >>> 8);
      putInt(bytes, at + 8 + len, 4, (c ^ 0xffffffff) >>> 0, false);
      at += 12 + len;
    }
  }
  return bytes;
}

// ---- Wolfenstein 3D ----

/** One of MAPHEAD (RLEW tag, map offsets), GAMEMAPS (map headers: plane offsets, lengths, size; compressed planes) or VSWAP (chunk count, offsets, lengths). */
let wolfSeed: NamedBytes[] | undefined;

function generateWolf(rng: Rng): NamedBytes[] {
  // A map whose objects warn by the thousand (issue 27): player starts, push-wall marks, codes no
  // object has, officers and mutants, repeated over the map.
  if (rng.chance(0.05)) {
    const codes = Array.from({ length: 1 + rng.int(6) }, () => rng.pick([19, 20, 21, 22, 98, 0, 23, 75, 89, 108, 126, 160, 216, 224, rng.int(0x10000)]));
    return wolfWarningFloodFiles(rng.pick([8, 64, 128, 181]), codes);
  }
  if (!wolfSeed) {
    const game = testGameFiles({ maps: 1 });
    wolfSeed = [game.maphead, game.gamemaps, game.vswap];
  }
  const files: Array<{ name: string; bytes: Uint8Array }> = wolfSeed.map((f) => ({ ...f, bytes: f.bytes.slice() }));
  const which = rng.int(3);
  const f = files[which]!;
  if (rng.chance(0.6)) {
    const fields: Record<number, () => number> = {
      0: () => 2 + 4 * rng.int(4),
      1: () => {
        const header = new DataView(files[0]!.bytes.buffer).getInt32(2, true);
        return Math.max(0, header) + rng.pick([0, 4, 8, 12, 14, 16, 18, 20, 22, 24]);
      },
      2: () => rng.pick([0, 2, 4, 6, 8, 10, 12, 14]),
    };
    putInt(f.bytes, fields[which]!(), rng.pick([2, 4] as const), interesting(rng));
  } else f.bytes = mutateBytes(rng, f.bytes);
  return files;
}

// ---- molecules ----

const MOLFILE = `caffeine
  Lantern           3D

  4  3  0     0  0  0  0  0  0999 V2000
    0.4700    2.5688    0.0006 O   0  0  0  0  0  0  0  0  0  0  0  0
   -0.9686   -1.3125    0.0000 N   0  0  0  0  0  0  0  0  0  0  0  0
    0.8579    0.2592   -0.0008 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.5163   -1.5787    0.0008 H   0  0  0  0  0  0  0  0  0  0  0  0
  1  3  2  0  0  0  0
  2  3  1  0  0  0  0
  3  4  1  0  0  0  0
M  END
`;

const V3000 = `ethanol
  Lantern           3D

  0  0  0     0  0  0  0  0  0999 V3000
M  V30 BEGIN CTAB
M  V30 COUNTS 3 2 0 0 0
M  V30 BEGIN ATOM
M  V30 1 C 0 0 0 0
M  V30 2 C 1.5 0 0 0
M  V30 3 O 2.2 1.2 0 0
M  V30 END ATOM
M  V30 BEGIN BOND
M  V30 1 1 1 2
M  V30 2 1 2 3
M  V30 END BOND
M  V30 END CTAB
M  END
`;

/**
 * The sizes issue 27 found unbounded: a V30 line continued over many lines, many bonds on one atom
 * (on a helix or on one line), V3000 COUNTS far past any limit.
 */
function bigMolecule(rng: Rng): string {
  switch (rng.int(3)) {
    case 0: {
      const lines = V3000.split('\n');
      const i = lines.findIndex((l) => l.startsWith('M  V30 ') && /\d/.test(l)) + rng.int(6);
      const pieces = Array.from({ length: rng.pick([1, 100, 10_000, 100_000]) }, (_, k) => `M  V30 X=${k} -`);
      if (lines[i]?.startsWith('M  V30 ')) lines.splice(i, 1, `${lines[i]} -`, ...pieces, 'M  V30 Y=1');
      return lines.join('\n');
    }
    case 1:
      return hubMolfile(rng.pick([3, 100, 5000, 20_000]), rng.pick([1, 2, 3, 4]), rng.chance(0.5));
    default: {
      const huge = rng.pick([2 ** 19 + 1, 2 ** 31, 2 ** 53, 1e15, 1e300]);
      return V3000.replace('COUNTS 3 2', rng.chance(0.5) ? `COUNTS ${huge} 2` : `COUNTS 3 ${huge}`);
    }
  }
}

function generateMolecule(rng: Rng): NamedBytes {
  if (rng.chance(0.05)) return { name: 'big.mol', bytes: new TextEncoder().encode(bigMolecule(rng)) };
  const records = Array.from({ length: 1 + rng.int(3) }, () => (rng.chance(0.7) ? MOLFILE : V3000));
  const sdf = rng.chance(0.5);
  let text = sdf ? records.map((r) => `${r}> <NAME>\nx\n\n$$$$\n`).join('') : records[0]!;
  text = mutateLines(rng, text);
  let bytes: Uint8Array = new TextEncoder().encode(text);
  if (rng.chance(0.15)) bytes = mutateBytes(rng, bytes);
  return { name: sdf ? 'fuzz.sdf' : 'fuzz.mol', bytes };
}

// ---- the targets ----

const mutated = (id: string, label: string, input: (rng: Rng) => NamedBytes[], run: (files: NamedBytes[]) => Promise<void> = infoPath): FuzzTarget => ({ id, label, input, run });

/** Each crafted input of the table, by name, built on demand (some take a second). */
const CRAFTED_WADS: Array<[string, () => Uint8Array]> = [
  ['65k-vertex sector', () => wadOf([bigSectorMap(65_000)])],
  ['140k vertices, no player start', () => wadOf([noPlayerStartMap(140_000)])],
  ['20k dangling segments', () => wadOf([danglingSegmentsMap(20_000)])],
  ['130k-linedef grid', () => wadOf([gridMap(255)])],
  ['100k random linedefs', () => wadOf([randomLinesMap(100_000, 50_000, 1000)])],
  ['100k random linedefs, 20 sectors', () => wadOf([randomLinesMap(100_000, 60_000, 20, 7)])],
  ['8000 missing patches behind 20k lumps', () => missingPatchesWad(8000, 20_000)],
  ['200k lumps', () => manyLumpsWad(200_000)],
  ['48 textures of 4096²', () => bigTexturesWad(48, 4096)],
  ['4 textures of 4096² on the walls', () => bigTexturesWad(4, 4096)],
  ['30k dangling segments spread out', () => wadOf([danglingSegmentsMap(30_000)])],
  ['grid of 230² sectors', () => wadOf([gridMap(230)])],
  ['65k-vertex sector, no player start', () => wadOf([{ ...bigSectorMap(65_000), things: [] }])],
];

/**
 * Gzip bombs: inflated size and the counts their header declares. 100 million vertices is over the
 * limit (refused from the header, before the body is inflated); 1,000 vertices and one face is not,
 * so those bodies run into decompressedBytes; 10.3 million faces is issue 27's 392 KB .ply.gz.
 */
const BOMBS: ReadonlyArray<{ bytes: number; vertices: number; faces: number }> = [
  ...[64, 256, 1024, 2560, 6144].map((mb) => ({ bytes: mb * 2 ** 20, vertices: 100_000_000, faces: 1 })),
  ...[256, 1024, 6144].map((mb) => ({ bytes: mb * 2 ** 20, vertices: 1000, faces: 1 })),
  { bytes: 134 * 2 ** 20, vertices: 3, faces: 10_300_000 },
];

export const TARGETS: readonly FuzzTarget[] = [
  mutated('wad', 'WAD, structure-aware mutations (directory, map records, textures, patches)', (rng) => {
    let bytes: Uint8Array = rng.pick(WAD_SEEDS());
    for (let r = 1 + rng.int(3); r > 0; r--) bytes = mutateWad(rng, bytes);
    return [{ name: 'fuzz.wad', bytes }];
  }),
  { id: 'wad-crafted', label: 'WAD, crafted large maps (issue 17)', count: CRAFTED_WADS.length, input: (_rng, i) => [{ name: `${CRAFTED_WADS[i % CRAFTED_WADS.length]![0]}.wad`, bytes: CRAFTED_WADS[i % CRAFTED_WADS.length]![1]() }], run: infoOnly },
  mutated('ply', 'PLY, generated with lies (counts, lists, indices, NaN/Inf, n-gons, endianness, gzip)', (rng) => [{ name: 'fuzz.ply', bytes: generatePly(rng) }]),
  { id: 'ply-bomb', label: 'PLY, gzip bombs', count: BOMBS.length, input: (_rng, i) => [{ name: 'bomb.ply.gz', bytes: plyBomb(BOMBS[i % BOMBS.length]!) }], run: infoOnly },
  mutated('gltf', 'glTF/GLB, JSON and chunk mutations', (rng) => [generateGltf(rng)]),
  mutated('exr', 'EXR, header and chunk mutations (lantern diff)', (rng) => {
    let bytes = exrSeed(rng);
    for (let r = 1 + rng.int(2); r > 0; r--) bytes = mutateExr(rng, bytes);
    return [{ name: 'fuzz.exr', bytes }];
  }, exrPath),
  { id: 'exr-huge', label: 'EXR, crafted huge dimensions (lantern diff)', count: 3, input: (_rng, i) => [{ name: 'huge.exr', bytes: [hugeExr(100_000, 100_000, 410_000), hugeExr(8000, 8000, 410_000), hugeExr(...LIMIT_SIDES, 410_000)][i % 3]! }, { name: 'small.exr', bytes: exrSeed(new Rng(1)) }], run: exrPath },
  { id: 'exr-limit', label: 'EXR pair at the imagePixels limit (lantern diff --heatmap)', count: 1, input: () => [{ name: 'a.exr', bytes: constantExr(...LIMIT_SIDES, 1) }, { name: 'b.exr', bytes: constantExr(...LIMIT_SIDES, 1.5) }], run: diffPath },
  { id: 'hdr-limit', label: 'HDR lat-long maps at the imagePixels limit, whole and truncated (--env)', count: 2, input: (_rng, i) => [{ name: 'sky.hdr', bytes: constantHdr(...LIMIT_SIDES, i % 2 === 1) }], run: environmentPath },
  mutated('hdr', 'HDR, header and RLE mutations', (rng) => [{ name: 'fuzz.hdr', bytes: mutateHdr(rng, hdrSeed(rng)) }], async (files) => void decodeHdr(files[0]!.bytes, files[0]!.name)),
  mutated('png', 'PNG, IHDR and IDAT mutations', (rng) => [{ name: 'fuzz.png', bytes: mutatePng(rng, pngSeed(rng)) }], async (files) => void decodePng(files[0]!.bytes, files[0]!.name)),
  mutated('wolf3d', 'Wolfenstein 3D, MAPHEAD/GAMEMAPS/VSWAP mutations', (rng) => generateWolf(rng)),
  mutated('molecule', 'Molecule files (MDL molfile V2000/V3000, SDF), line mutations', (rng) => [generateMolecule(rng)]),
  { id: 'gltf-crafted', label: 'glTF, crafted counts, shared and costly images, degenerate nodes, escaping URIs (issue 27)', count: CRAFTED_GLTF.length, input: (_rng, i) => [CRAFTED_GLTF[i % CRAFTED_GLTF.length]![1]()], run: infoPath },
  mutated('camera-path', 'Camera paths (render --path): times, positions and fields of view at the edges', (rng) => [generatePath(rng)], pathPath),
];

/**
 * A PLY whose gzip stream inflates to about `bytes`: a valid header declaring the counts, then
 * members of 64 MiB of zeros concatenated (gzip allows several members; each compresses to ~64 KB),
 * so big bombs cost little to build.
 */
export function plyBomb({ bytes, vertices, faces }: { bytes: number; vertices: number; faces: number }): Uint8Array {
  const header = gzipSync(new TextEncoder().encode(`ply\nformat binary_little_endian 1.0\nelement vertex ${vertices}\nproperty float x\nproperty float y\nproperty float z\nelement face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`));
  const member = gzipBomb(Math.min(bytes, 64 * 2 ** 20));
  const parts: Uint8Array[] = [new Uint8Array(header)];
  for (let n = 0; n < bytes; n += 64 * 2 ** 20) parts.push(member);
  return concat(...parts);
}

export type Outcome = { readonly kind: 'ok' | 'clean'; readonly message?: string } | { readonly kind: 'crash'; readonly message: string };

/** Runs one input through its target: ok, a clean refusal (LanternError), or a crash (anything else). */
export async function runInput(target: FuzzTarget, files: NamedBytes[]): Promise<Outcome> {
  try {
    await target.run(files);
    return { kind: 'ok' };
  } catch (e) {
    if (e instanceof LanternError) return { kind: 'clean', message: e.userMessage };
    return { kind: 'crash', message: e instanceof Error ? `${e.name}: ${e.message}` : String(e) };
  }
}
