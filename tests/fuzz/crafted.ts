/**
 * The large or degenerate inputs of issue 17's table, built in code: each one once crashed, hung or
 * took gigabytes. They are legal (or nearly) files, so they test sizes and shapes, not parsing.
 */
import { constants, deflateRawSync, gzipSync } from 'node:zlib';
import { encodeExr } from '../../src/image/exr.ts';
import { glbOf } from '../../src/loaders/gltf/test-glb.ts';
import { encodePng } from '../../src/image/png.ts';
import type { DoomMap, Linedef, MapVertex, Sector, Sidedef, Thing } from '../../src/loaders/doom/map-types.ts';
import { NO_SIDEDEF } from '../../src/loaders/doom/map-types.ts';
import { encodeFlat, encodeMap, encodePalette, encodePatch, encodePnames, encodeTextureLump, WadBuilder } from '../../src/loaders/doom/test-wad.ts';
import type { NamedBytes } from '../../src/loaders/format.ts';
import { PUSHABLETILE } from '../../src/loaders/wolf3d/map-codes.ts';
import { TEST_CODES, testGameFiles, writeMapFiles } from '../../src/loaders/wolf3d/test-files.ts';

const room = (floorFlat = 'FLOOR'): Sector => ({ floorHeight: 0, ceilingHeight: 128, floorFlat, ceilingFlat: 'FLOOR', lightLevel: 160, special: 0, tag: 0 });
const side = (sector: number, middle = '-'): Sidedef => ({ xOffset: 0, yOffset: 0, upper: '-', lower: '-', middle, sector });
const line = (v1: number, v2: number, front: number, back = NO_SIDEDEF): Linedef => ({ v1, v2, flags: back === NO_SIDEDEF ? 1 : 4, special: 0, tag: 0, front, back });
const PLAYER = (x: number, y: number): Thing => ({ x, y, angle: 90, type: 1, flags: 7 });

/** A WAD of the maps with the palette and one flat (FLOOR) they name, so the whole Doom pipeline runs. */
export function wadOf(maps: readonly DoomMap[], extra: (w: WadBuilder) => void = () => {}): Uint8Array {
  const w = new WadBuilder().lump('PLAYPAL', encodePalette());
  for (const m of maps) w.lumps(encodeMap(m));
  extra(w);
  return w.marker('F_START').lump('FLOOR', encodeFlat(7)).marker('F_END').build('IWAD');
}

/**
 * One sector whose boundary has `n` vertices: a rectangle whose bottom edge is cut into n − 3 unit
 * segments. Its sidedefs are shared (one per sector, as packed WADs do), so n may reach 65,535.
 */
export function bigSectorMap(n: number): DoomMap {
  const w = n - 3;
  const vertices: MapVertex[] = [{ x: 0, y: 0 }, { x: 0, y: 1000 }, { x: w, y: 1000 }];
  for (let x = w; x >= 1; x--) vertices.push({ x, y: 0 });
  // Clockwise: the inside is on the right, where the front sidedef faces.
  const linedefs = vertices.map((_, i) => line(i, (i + 1) % vertices.length, 0));
  return { name: 'MAP01', vertices, linedefs, sidedefs: [side(0, 'WALL')], sectors: [room()], things: [PLAYER(w / 2, 500)] };
}

/** A square room plus `extra` vertices no line uses, and no player start: the camera is placed from all vertices. */
export function noPlayerStartMap(extra: number): DoomMap {
  const vertices: MapVertex[] = [{ x: 0, y: 0 }, { x: 0, y: 256 }, { x: 256, y: 256 }, { x: 256, y: 0 }];
  for (let i = 0; i < extra; i++) vertices.push({ x: (i * 7919) % 512 - 128, y: (i * 104729) % 512 - 128 });
  const linedefs = [0, 1, 2, 3].map((i) => line(i, (i + 1) % 4, 0));
  return { name: 'MAP01', vertices, linedefs, sidedefs: [side(0, 'WALL')], sectors: [room()], things: [] };
}

/**
 * A closed room (sector 0) and sector 1 made of `segments` disconnected unit-spaced segments packed
 * into a square, every end within the gap tolerance of thousands of starts: the repair that joins
 * gaps once considered every pair.
 */
export function danglingSegmentsMap(segments: number): DoomMap {
  const vertices: MapVertex[] = [{ x: -64, y: -64 }, { x: -64, y: 4096 }, { x: 4096, y: 4096 }, { x: 4096, y: -64 }];
  const linedefs = [0, 1, 2, 3].map((i) => line(i, (i + 1) % 4, 0));
  const perRow = Math.ceil(Math.sqrt(segments));
  for (let k = 0; k < segments; k++) {
    const [x, y] = [(k % perRow) * 12, Math.floor(k / perRow) * 12];
    vertices.push({ x, y }, { x: x + 5, y: y + 3 });
    linedefs.push(line(vertices.length - 2, vertices.length - 1, 1));
  }
  return { name: 'MAP01', vertices, linedefs, sidedefs: [side(0, 'WALL'), side(1, 'WALL')], sectors: [room(), room()], things: [PLAYER(-32, -32)] };
}

/**
 * An n × n grid of square sectors, 64 units a side: 2n(n + 1) linedefs (n = 230: 106,260), each
 * interior line two-sided. One sidedef per sector, shared by its lines.
 */
export function gridMap(n: number): DoomMap {
  const vertices: MapVertex[] = [];
  const at = (i: number, j: number) => j * (n + 1) + i;
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) vertices.push({ x: i * 64, y: j * 64 });
  const cell = (i: number, j: number) => (i >= 0 && j >= 0 && i < n && j < n ? j * n + i : NO_SIDEDEF);
  const linedefs: Linedef[] = [];
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i < n; i++) {
      // Horizontal line (i, j) → (i + 1, j): its right side is below (the cell j − 1).
      const [right, left] = [cell(i, j - 1), cell(i, j)];
      if (right !== NO_SIDEDEF) linedefs.push(line(at(i, j), at(i + 1, j), right, left));
      else linedefs.push(line(at(i + 1, j), at(i, j), left));
    }
  }
  for (let i = 0; i <= n; i++) {
    for (let j = 0; j < n; j++) {
      // Vertical line (i, j + 1) → (i, j), heading south: its right side is west, the cell i − 1.
      const [right, left] = [cell(i - 1, j), cell(i, j)];
      if (right !== NO_SIDEDEF) linedefs.push(line(at(i, j + 1), at(i, j), right, left));
      else linedefs.push(line(at(i, j), at(i, j + 1), left));
    }
  }
  const sectors = Array.from({ length: n * n }, () => room());
  const sidedefs = sectors.map((_, s) => side(s));
  return { name: 'MAP01', vertices, linedefs, sidedefs, sectors, things: [PLAYER(32, 32)] };
}

/**
 * `lines` random linedefs between `points` random vertices, each side naming one of `sectors`
 * sectors at random: legal records, nonsense geometry. A fixed LCG keeps it the same every run.
 */
export function randomLinesMap(lines: number, points: number, sectors: number, seed = 1): DoomMap {
  let s = seed >>> 0;
  const rand = (n: number) => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) % n);
  const vertices: MapVertex[] = Array.from({ length: points }, () => ({ x: rand(16384) - 8192, y: rand(16384) - 8192 }));
  const linedefs: Linedef[] = Array.from({ length: lines }, () => line(rand(points), rand(points), rand(sectors), rand(3) === 0 ? NO_SIDEDEF : rand(sectors)));
  const all = Array.from({ length: sectors }, () => room());
  return { name: 'MAP01', vertices, linedefs, sidedefs: all.map((_, i) => side(i, 'WALL')), sectors: all, things: [PLAYER(0, 0)] };
}

/** A square room and `lumps` empty filler lumps in the directory. */
export function manyLumpsWad(lumps: number): Uint8Array {
  return wadOf([squareMap()], (w) => {
    for (let i = 0; i < lumps; i++) w.marker(`L${i}`);
  });
}

/** A 256-unit square room with a player start. */
function squareMap(): DoomMap {
  return { ...noPlayerStartMap(0), things: [PLAYER(128, 128)] };
}

/**
 * A room whose walls use `count` textures of side × side, each drawn from one small patch tiled
 * over it: a few KB asking for count · side² texels.
 */
export function bigTexturesWad(count: number, side: number): Uint8Array {
  const names = Array.from({ length: count }, (_, i) => `BIG${i}`);
  const map = squareMap();
  // One sidedef per wall line, cycling through the textures so the map needs all of them.
  const sidedefs = names.map((name) => ({ xOffset: 0, yOffset: 0, upper: '-', lower: '-', middle: name, sector: 0 }));
  const linedefs = [0, 1, 2, 3].map((i) => line(i, (i + 1) % 4, i % count));
  // The room's four walls name the first four textures; tests reach the rest through DoomGraphics.
  return wadOf([{ ...map, linedefs, sidedefs }], (w) => {
    w.lump('PNAMES', encodePnames(['TILE']));
    w.lump('TEXTURE1', encodeTextureLump(names.map((name) => ({ name, width: side, height: side, patches: [{ x: 0, y: 0, patch: 0 }] }))));
    w.marker('P_START').lump('TILE', encodePatch(8, 8, new Array<number>(64).fill(3))).marker('P_END');
  });
}

/** A room and `count` textures each made of its own patch, none of which exists, behind `filler` lumps. */
export function missingPatchesWad(count: number, filler: number): Uint8Array {
  const names = Array.from({ length: count }, (_, i) => `MP${i}`);
  return wadOf([squareMap()], (w) => {
    w.lump('PNAMES', encodePnames(names.map((n) => `${n}P`)));
    w.lump('TEXTURE1', encodeTextureLump(names.map((name, i) => ({ name, width: 64, height: 64, patches: [{ x: 0, y: 0, patch: i }] }))));
    for (let i = 0; i < filler; i++) w.lump(`F${i}`, new Uint8Array([1]));
  });
}

/** `bytes` zeros, gzip-compressed (about 1/1000 of the size). */
export function gzipBomb(bytes: number): Uint8Array {
  return new Uint8Array(gzipSync(new Uint8Array(bytes), { level: 9 }));
}

/**
 * A valid small EXR whose data window is then rewritten to width × height (its chunk table and data
 * stay those of the small image), padded to `fileBytes`: what a hostile or truncated header looks like.
 */
export function hugeExr(width: number, height: number, fileBytes = 0): Uint8Array {
  const small = encodeExr(2, 2, new Float32Array(12), { compression: 'zip', pixelType: 'half' });
  const out = new Uint8Array(Math.max(small.length, fileBytes));
  out.set(small);
  for (const attr of ['dataWindow', 'displayWindow']) {
    const at = indexOfAscii(out, `${attr}\0box2i\0`);
    if (at < 0) throw new Error(`crafted: no ${attr} in the EXR`);
    const view = new DataView(out.buffer, at + attr.length + 7 + 4, 16);
    view.setInt32(0, 0, true);
    view.setInt32(4, 0, true);
    view.setInt32(8, width - 1, true);
    view.setInt32(12, height - 1, true);
  }
  return out;
}

function indexOfAscii(bytes: Uint8Array, text: string): number {
  outer: for (let i = 0; i + text.length <= bytes.length; i++) {
    for (let k = 0; k < text.length; k++) if (bytes[i + k] !== text.charCodeAt(k)) continue outer;
    return i;
  }
  return -1;
}

// ---- glTF inputs of issue 27 (§6): counts, images, transforms and URIs that a few bytes of JSON ask for ----

/** A .gltf (JSON text) from its object, with the asset, scene and node a viewer needs added. */
function gltfText(json: Record<string, unknown>): Uint8Array {
  return new TextEncoder().encode(JSON.stringify({ asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }], ...json }));
}

/** Three float positions (36 bytes) as a base64 data: URI buffer, for inputs that need some real data. */
const TRIANGLE_BUFFER = { byteLength: 36, uri: `data:application/octet-stream;base64,${Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer).toString('base64')}` };
const TRIANGLE_ACCESSOR = { bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] };

/**
 * How a few hundred bytes of glTF JSON declare `count` elements without the bytes for them:
 * - 'positions': a POSITION accessor with no buffer view (glTF-Transform zero-fills it: count × 12 bytes);
 * - 'indices': an index accessor with no buffer view over a real triangle;
 * - 'sparse': a sparse POSITION accessor whose sparse count is `count`, its indices and values in 36 bytes;
 * - 'interleaved': a POSITION accessor of `count` elements over a 36-byte view with a byte stride;
 * - 'instances': EXT_mesh_gpu_instancing with `count` translations and no buffer view.
 */
export type CountBomb = 'positions' | 'indices' | 'sparse' | 'interleaved' | 'instances';

export function countBombGltf(kind: CountBomb, count: number): Uint8Array {
  const buffers = [TRIANGLE_BUFFER];
  const bufferViews: Array<Record<string, number>> = [{ buffer: 0, byteOffset: 0, byteLength: 36 }];
  switch (kind) {
    case 'positions':
      return gltfText({ meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }], accessors: [{ componentType: 5126, count, type: 'VEC3' }] });
    case 'indices':
      return gltfText({ meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }], accessors: [TRIANGLE_ACCESSOR, { componentType: 5125, count, type: 'SCALAR' }], bufferViews, buffers });
    case 'sparse':
      return gltfText({
        meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
        accessors: [{ componentType: 5126, count: 3, type: 'VEC3', sparse: { count, indices: { bufferView: 0, componentType: 5125 }, values: { bufferView: 0 } } }],
        bufferViews, buffers,
      });
    case 'interleaved':
      return gltfText({ meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }], accessors: [{ ...TRIANGLE_ACCESSOR, count }], bufferViews: [{ ...bufferViews[0]!, byteStride: 16 }], buffers });
    case 'instances':
      return gltfText({
        extensionsUsed: ['EXT_mesh_gpu_instancing'],
        nodes: [{ mesh: 0, extensions: { EXT_mesh_gpu_instancing: { attributes: { TRANSLATION: 1 } } } }],
        meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
        accessors: [TRIANGLE_ACCESSOR, { componentType: 5126, count, type: 'VEC3' }],
        bufferViews, buffers,
      });
  }
}

/**
 * A GLB of `images` glTF images that all name one encoded image (PNG or JPEG, in one buffer view),
 * each the base colour of its own material on its own pair of triangles: a PNG of zeros compresses
 * about 1000:1, so 5792² (the most imagePixels admits) is 145 KB, and every image decoded on its own
 * costs 134 MB and seconds.
 */
export function sharedImageGlb(images: number, image: Uint8Array): Uint8Array {
  const positions = new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]).buffer);
  const uvs = new Uint8Array(new Float32Array([0, 0, 1, 0, 0, 1, 1, 1]).buffer);
  const bin = new Uint8Array(48 + 32 + ((image.length + 3) & ~3));
  bin.set(positions, 0);
  bin.set(uvs, 48);
  bin.set(image, 80);
  const primitives = Array.from({ length: images }, (_, i) => ({ attributes: { POSITION: 0, TEXCOORD_0: 1 }, mode: 5, material: i }));
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives }],
    materials: primitives.map((_, i) => ({ pbrMetallicRoughness: { baseColorTexture: { index: i } } })),
    textures: primitives.map((_, i) => ({ source: i })),
    images: primitives.map(() => ({ bufferView: 2, mimeType: 'image/png' })),
    accessors: [
      { bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] },
      { bufferView: 1, componentType: 5126, count: 4, type: 'VEC2' },
    ],
    bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 48 }, { buffer: 0, byteOffset: 48, byteLength: 32 }, { buffer: 0, byteOffset: 80, byteLength: image.length }],
    buffers: [{ byteLength: bin.length }],
  };
  return glbOf(json, bin);
}


/**
 * A progressive greyscale JPEG of width × height with `scans` AC scans, each coded as end-of-band
 * runs of 32,767 blocks (three bytes a run): each scan costs the decoder a pass over every block
 * while the file grows by about 20 bytes a scan. One DC scan comes first, as encoders write it.
 */
export function progressiveJpeg(width: number, height: number, scans: number): Uint8Array {
  const out: number[] = [0xff, 0xd8];
  const segment = (marker: number, body: readonly number[]) => out.push(0xff, marker, (body.length + 2) >> 8, (body.length + 2) & 255, ...body);
  segment(0xdb, [0, ...new Array<number>(64).fill(1)]); // DQT: table 0, all ones
  segment(0xc2, [8, height >> 8, height & 255, width >> 8, width & 255, 1, 1, 0x11, 0]); // SOF2: one component, 1×1 sampling
  // DHT: DC table 0 with one code of length 1 for category 0; AC table 0 with one code for EOB14 (0xE0).
  segment(0xc4, [0x00, 1, ...new Array<number>(15).fill(0), 0x00]);
  segment(0xc4, [0x10, 1, ...new Array<number>(15).fill(0), 0xe0]);
  const blocks = Math.ceil(width / 8) * Math.ceil(height / 8);
  const entropy = (bits: string) => {
    const padded = bits + '1'.repeat((8 - (bits.length % 8)) % 8);
    for (let i = 0; i < padded.length; i += 8) {
      const byte = parseInt(padded.slice(i, i + 8), 2);
      out.push(byte);
      if (byte === 0xff) out.push(0); // stuffed
    }
  };
  // DC first scan: one '0' bit (category 0) per block.
  segment(0xda, [1, 1, 0x00, 0, 0, 0]);
  entropy('0'.repeat(blocks));
  // AC first scans over bands 1–63: EOB14 ('0') then 14 bits of run length (all ones: 16,384 + 16,383).
  const run = '0' + '1'.repeat(14);
  const acBits = run.repeat(Math.ceil(blocks / 32_767));
  for (let s = 0; s < scans; s++) {
    segment(0xda, [1, 1, 0x00, 1, 63, 0]);
    entropy(acBits);
  }
  out.push(0xff, 0xd9);
  return new Uint8Array(out);
}

/** A triangle and, on a node scaled to zero, a camera ('camera') or a KHR_lights_punctual light of that type. */
export function zeroScaleGltf(what: 'camera' | 'spot' | 'directional' | 'point' | 'mesh'): Uint8Array {
  const zero = { scale: [0, 0, 0] };
  const triangle = { meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }], accessors: [TRIANGLE_ACCESSOR], bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 36 }], buffers: [TRIANGLE_BUFFER] };
  if (what === 'mesh') return gltfText({ ...triangle, scenes: [{ nodes: [0, 1] }], nodes: [{ mesh: 0 }, { mesh: 0, ...zero }] });
  if (what === 'camera') return gltfText({ ...triangle, scenes: [{ nodes: [0, 1] }], nodes: [{ mesh: 0 }, { camera: 0, ...zero }], cameras: [{ type: 'perspective', perspective: { yfov: 0.8, znear: 0.1 } }] });
  return gltfText({
    ...triangle,
    extensionsUsed: ['KHR_lights_punctual'],
    extensions: { KHR_lights_punctual: { lights: [{ type: what, intensity: 10, ...(what === 'spot' ? { spot: {} } : {}) }] } },
    scenes: [{ nodes: [0, 1] }],
    nodes: [{ mesh: 0 }, { extensions: { KHR_lights_punctual: { light: 0 } }, ...zero }],
  });
}

/** A triangle whose buffer is an external file named by `uri` (a path out of the folder, an absolute one, a file: or http: URI). */
export function externalBufferGltf(uri: string): Uint8Array {
  return gltfText({ meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }], accessors: [TRIANGLE_ACCESSOR], bufferViews: [{ buffer: 0, byteOffset: 0, byteLength: 36 }], buffers: [{ byteLength: 36, uri }] });
}

/**
 * A side × side PNG whose zlib stream inflates to `bytes` zeros (its pixels, then far more): deflate
 * blocks of 64 MiB of zeros (64 KB each) repeated, so a 512 MB stream costs little to build.
 */
export function pngStreamBomb(side: number, bytes: number): Uint8Array {
  const block = 64 * 2 ** 20;
  const repeated = new Uint8Array(deflateRawSync(new Uint8Array(Math.min(bytes, block)), { level: 9, finishFlush: constants.Z_SYNC_FLUSH }));
  const copies = Math.ceil(bytes / block);
  const total = copies * Math.min(bytes, block);
  const last = new Uint8Array(deflateRawSync(new Uint8Array(0)));
  const stream = new Uint8Array(2 + copies * repeated.length + last.length + 4);
  stream.set([0x78, 0x9c]);
  for (let c = 0; c < copies; c++) stream.set(repeated, 2 + c * repeated.length);
  stream.set(last, 2 + copies * repeated.length);
  // Adler-32 of n zeros: A stays 1, B grows by 1 a byte.
  new DataView(stream.buffer).setUint32(stream.length - 4, (((total % 65521) << 16) | 1) >>> 0);
  return encodePng(side, side, new Uint8Array(side * side * 4), () => stream);
}

// ---- molecules (issue 27) ----

/** A V3000 molfile of the given atom lines ("index symbol x y z") and bond lines ("index type a b"); COUNTS as given or as the blocks hold. */
export function v3000Molfile(atoms: readonly string[], bonds: readonly string[], counts = `${atoms.length} ${bonds.length}`): string {
  return [
    'crafted', '  Lantern           3D', '', '  0  0  0     0  0  0  0  0  0999 V3000',
    'M  V30 BEGIN CTAB', `M  V30 COUNTS ${counts} 0 0 0`,
    'M  V30 BEGIN ATOM', ...atoms.map((a) => `M  V30 ${a}`), 'M  V30 END ATOM',
    ...(bonds.length > 0 ? ['M  V30 BEGIN BOND', ...bonds.map((b) => `M  V30 ${b}`), 'M  V30 END BOND'] : []),
    'M  V30 END CTAB', 'M  END', '',
  ].join('\n');
}

/**
 * Two bonded atoms, the first atom's line continued over `lines` more lines of properties: joining
 * the pieces one at a time re-read the whole line at each (over 60 s at 100,000).
 */
export function continuedLineMolfile(lines: number): string {
  const text = v3000Molfile(['1 C 0 0 0 0', '2 O 1.2 0 0 0'], ['1 2 1 2']);
  const continued = ['M  V30 1 C 0 0 0 0 -', ...Array.from({ length: lines }, (_, i) => `M  V30 CHG=${i % 3} -`), 'M  V30 MASS=12'].join('\n');
  return text.replace('M  V30 1 C 0 0 0 0', continued);
}

/**
 * One carbon with `bonds` bonds of `type` to as many oxygens, on a helix round it (or, `collinear`,
 * all on one line, so that no neighbour gives a bond its side): each bond's side direction once
 * looked at every other bond (over 60 s at 20,000).
 */
export function hubMolfile(bonds: number, type = 2, collinear = false): string {
  const atoms = ['1 C 0 0 0 0'];
  for (let i = 0; i < bonds; i++) atoms.push(collinear ? `${i + 2} O ${i + 1} 0 0 0` : `${i + 2} O ${Math.cos(i).toFixed(4)} ${Math.sin(i).toFixed(4)} ${(i * 1e-3).toFixed(4)} 0`);
  return v3000Molfile(atoms, Array.from({ length: bonds }, (_, i) => `${i + 1} ${type} 1 ${i + 2}`));
}

// ---- Wolfenstein 3D (issue 27) ----

/**
 * A game of one `side` × `side` map (181: the largest a plane holds is 32,767 tiles) of open floor
 * inside a wall, every tile of its object plane a warning: player starts on even rows (all but the
 * first a "second player start"), push-wall marks off any wall on odd rows; or, given `codes`, tile
 * i holds codes[i % codes.length]. One such map printed 32,040 warning lines.
 */
export function wolfWarningFloodFiles(side = 181, codes?: readonly number[]): NamedBytes[] {
  const walls = new Uint16Array(side * side).fill(TEST_CODES.walls[0]);
  const objects = new Uint16Array(side * side);
  for (let y = 1; y < side - 1; y++) {
    for (let x = 1; x < side - 1; x++) {
      const i = y * side + x;
      walls[i] = TEST_CODES.floor;
      objects[i] = codes ? codes[i % codes.length]! : y % 2 === 0 ? TEST_CODES.playerStart.north + (x % 4) : PUSHABLETILE;
    }
  }
  const { maphead, gamemaps } = writeMapFiles([{ title: 'Flood', width: side, height: side, planes: [walls, objects, new Uint16Array(side * side)] }]);
  const game = testGameFiles({ maps: 1 });
  return [{ name: 'MAPHEAD.WL1', bytes: maphead }, { name: 'GAMEMAPS.WL1', bytes: gamemaps }, game.vswap];
}

// ---- images at the pixel limit (issue 27) ----

/**
 * An EXR of exactly `width` × `height` half RGB pixels of one value: legal and cheap to build at any
 * size (a constant compresses to almost nothing), so `lantern diff` can be run at the imagePixels
 * limit, where it once took over 60 s and 2 GB.
 */
export function constantExr(width: number, height: number, value: number): Uint8Array {
  return encodeExr(width, height, new Float32Array(width * height * 3).fill(value), { compression: 'zip', pixelType: 'half' });
}

/**
 * A run-length Radiance file of `width` × `height` pixels of one colour (each scanline four runs per
 * 127 pixels), or with `truncated` its header and first scanline only: a limit-sized lat-long map
 * in a few MB.
 */
export function constantHdr(width: number, height: number, truncated = false): Uint8Array {
  const head = new TextEncoder().encode(`#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`);
  const line: number[] = [2, 2, width >> 8, width & 255];
  for (const byte of [128, 64, 32, 129]) for (let x = 0; x < width; x += 127) line.push(128 + Math.min(127, width - x), byte);
  const out = new Uint8Array(head.length + line.length * (truncated ? 1 : height));
  out.set(head);
  for (let y = 0; y < (truncated ? 1 : height); y++) out.set(line, head.length + y * line.length);
  return out;
}

export { glbOf };
