/**
 * Readers for the two PLY elements Lantern uses: `vertex` (positions, optional normals and uvs) and
 * `face` (polygons, fan-triangulated). Both walk every property of every record so that unknown
 * properties, lists included, are skipped in step with the data.
 */
import { LanternError } from '../../errors.ts';
import { limits } from '../../budgets.ts';
import { SCALAR_SIZE, type PlyElement, type PlyListProperty, type PlyScalarType } from './header.ts';
import { BinaryReader, getScalar, PlyBadValue, PlyEndOfData, readListCount, type ValueReader } from './readers.ts';

/** Written by the loops below so an error can say which record it happened in. */
export interface ReadContext {
  index: number;
}

export interface VertexData {
  positions: Float32Array;
  normals?: Float32Array;
  uvs?: Float32Array;
  /** Why the normals were dropped, if they were. */
  droppedNormals?: string;
}

// Slots of the per-record scratch row; IGNORE collects properties nobody asked for.
const X = 0, NX = 3, U = 6, IGNORE = 8;
const UV_NAMES: readonly (readonly [string, string])[] = [
  ['u', 'v'], ['s', 't'], ['texture_u', 'texture_v'], ['texture_s', 'texture_t'],
];

export function readVertices(reader: ValueReader, element: PlyElement, name: string, context: ReadContext): VertexData {
  const props = element.properties;
  const slotOf = (prop: string): number => props.findIndex((p) => p.name === prop && p.kind === 'scalar');
  const xyz = ['x', 'y', 'z'].map(slotOf);
  const missing = ['x', 'y', 'z'].filter((_, i) => xyz[i] === -1);
  if (missing.length > 0) {
    throw new LanternError(`${name}: the PLY vertex element has no scalar '${missing.join("', '")}' propert${missing.length > 1 ? 'ies' : 'y'}`);
  }
  const nxyz = ['nx', 'ny', 'nz'].map(slotOf);
  const hasNormals = nxyz.every((k) => k >= 0);
  const uvPair = UV_NAMES.map((pair) => pair.map(slotOf)).find((ks) => ks.every((k) => k >= 0));

  const slots = new Int32Array(props.length).fill(IGNORE);
  xyz.forEach((k, c) => (slots[k] = X + c));
  if (hasNormals) nxyz.forEach((k, c) => (slots[k] = NX + c));
  uvPair?.forEach((k, c) => (slots[k] = U + c));

  const count = element.count;
  const positions = new Float32Array(count * 3);
  const normals = hasNormals ? new Float32Array(count * 3) : undefined;
  const uvs = uvPair ? new Float32Array(count * 2) : undefined;
  const row = new Float64Array(IGNORE + 1);
  const fixed = reader instanceof BinaryReader ? fixedLayout(reader, element, slots, context) : undefined;
  for (let i = 0; i < count; i++) {
    context.index = i;
    if (fixed) {
      const base = fixed.start + i * fixed.stride;
      for (let j = 0; j < fixed.offsets.length; j++) {
        row[fixed.slots[j]!] = getScalar(fixed.view, base + fixed.offsets[j]!, fixed.types[j]!, fixed.little);
      }
    } else {
      for (let k = 0; k < props.length; k++) {
        const p = props[k]!;
        if (p.kind === 'list') reader.skip(p.itemType, readListCount(reader, p));
        else row[slots[k]!] = reader.read(p.type);
      }
    }
    positions[3 * i] = row[X]!;
    positions[3 * i + 1] = row[X + 1]!;
    positions[3 * i + 2] = row[X + 2]!;
    if (normals) {
      normals[3 * i] = row[NX]!;
      normals[3 * i + 1] = row[NX + 1]!;
      normals[3 * i + 2] = row[NX + 2]!;
    }
    if (uvs) {
      uvs[2 * i] = row[U]!;
      uvs[2 * i + 1] = row[U + 1]!;
    }
  }
  if (fixed) reader.pos = fixed.start + count * fixed.stride;
  for (let i = 0; i < positions.length; i++) {
    if (!Number.isFinite(positions[i]!)) {
      context.index = Math.floor(i / 3);
      throw new PlyBadValue('the vertex has a non-finite coordinate (or one too large for 32-bit floats)');
    }
  }
  const result: VertexData = { positions };
  if (uvs) result.uvs = uvs;
  if (normals) {
    const problem = normalizeInPlace(normals);
    if (problem) result.droppedNormals = problem;
    else result.normals = normals;
  }
  return result;
}

interface FixedLayout {
  view: DataView;
  little: boolean;
  start: number;
  stride: number;
  /** Byte offset within the record, type and row slot of each wanted property. */
  offsets: number[];
  types: PlyScalarType[];
  slots: number[];
}

/**
 * Binary records without lists all have the same size, so the wanted properties can be read at fixed
 * offsets without walking the others, and truncation is known before reading anything.
 */
function fixedLayout(reader: BinaryReader, element: PlyElement, slots: Int32Array, context: ReadContext): FixedLayout | undefined {
  const layout: FixedLayout = { view: reader.view, little: reader.little, start: reader.pos, stride: 0, offsets: [], types: [], slots: [] };
  for (const [k, p] of element.properties.entries()) {
    if (p.kind === 'list') return undefined;
    if (slots[k] !== IGNORE) {
      layout.offsets.push(layout.stride);
      layout.types.push(p.type);
      layout.slots.push(slots[k]!);
    }
    layout.stride += SCALAR_SIZE[p.type];
  }
  if (element.count * layout.stride > reader.remaining) {
    context.index = Math.floor(reader.remaining / layout.stride);
    throw new PlyEndOfData();
  }
  return layout;
}

/**
 * Scanners often write normals that are not quite unit length; the Mesh contract wants unit ones. A
 * zero or non-finite normal cannot be repaired, and one bad normal makes the whole set suspect, so
 * the caller falls back to geometric normals.
 */
function normalizeInPlace(n: Float32Array): string | undefined {
  for (let i = 0; i < n.length; i += 3) {
    const x = n[i]!, y = n[i + 1]!, z = n[i + 2]!;
    const len = Math.sqrt(x * x + y * y + z * z);
    if (!(len > 0 && len < Infinity)) return `vertex ${i / 3} has a zero or non-finite normal`;
    n[i] = x / len;
    n[i + 1] = y / len;
    n[i + 2] = z / len;
  }
  return undefined;
}

export interface FaceData {
  /** Three vertex indices per triangle. */
  indices: Uint32Array;
  /** Faces with fewer than 3 vertices, which have no area and are dropped. */
  skipped: number;
}

const INDEX_NAMES = ['vertex_indices', 'vertex_index'];

export function readFaces(reader: ValueReader, element: PlyElement, vertexCount: number, name: string, context: ReadContext): FaceData {
  const props = element.properties;
  const listAt = props.findIndex((p) => p.kind === 'list' && INDEX_NAMES.includes(p.name));
  if (listAt < 0) {
    throw new LanternError(`${name}: the PLY face element has no list property 'vertex_indices' (or 'vertex_index')`);
  }
  const list = props[listAt] as PlyListProperty;
  if (reader instanceof BinaryReader && props.length === 1) {
    return readBinaryFaceList(reader, list, element.count, vertexCount, context);
  }

  // Sized for all-triangle meshes, the common case; polygons grow it.
  let indices: Uint32Array = new Uint32Array(element.count * 3);
  let n = 0, skipped = 0;
  const maxCorners = limits().polygonVertices;
  const index = (): number => {
    const v = reader.read(list.itemType);
    if (!(v >= 0 && v < vertexCount && Number.isInteger(v))) throw outOfRange(v, vertexCount);
    return v;
  };
  for (let i = 0; i < element.count; i++) {
    context.index = i;
    for (let k = 0; k < props.length; k++) {
      const p = props[k]!;
      if (k !== listAt) {
        if (p.kind === 'list') reader.skip(p.itemType, readListCount(reader, p));
        else reader.skip(p.type, 1);
        continue;
      }
      const m = readListCount(reader, list);
      if (m > maxCorners) throw tooManyCorners(m, maxCorners);
      if (m < 3) {
        reader.skip(list.itemType, m);
        skipped++;
        continue;
      }
      if (n + 3 * (m - 2) > indices.length) indices = grow(indices, n + 3 * (m - 2));
      // Fan around the first vertex: (v0, v1, v2), (v0, v2, v3), ... keeps the polygon's winding.
      const first = index();
      let previous = index();
      for (let j = 2; j < m; j++) {
        const current = index();
        indices[n++] = first;
        indices[n++] = previous;
        indices[n++] = current;
        previous = current;
      }
    }
  }
  return { indices: n === indices.length ? indices : indices.slice(0, n), skipped };
}

/**
 * The overwhelmingly common binary layout (a face is only its index list) read straight from the
 * DataView, without the per-value calls of the general loop. Same results and errors.
 */
function readBinaryFaceList(reader: BinaryReader, list: PlyListProperty, count: number, vertexCount: number, context: ReadContext): FaceData {
  const { view, little } = reader;
  const end = view.byteLength;
  const countSize = SCALAR_SIZE[list.countType], itemSize = SCALAR_SIZE[list.itemType];
  const countType = list.countType, itemType = list.itemType;
  let indices: Uint32Array = new Uint32Array(count * 3);
  let n = 0, skipped = 0, pos = reader.pos;
  const maxCorners = limits().polygonVertices;
  const index = (at: number): number => {
    const v = getScalar(view, at, itemType, little);
    if (!(v >= 0 && v < vertexCount && Number.isInteger(v))) throw outOfRange(v, vertexCount);
    return v;
  };
  for (let i = 0; i < count; i++) {
    context.index = i;
    if (pos + countSize > end) throw new PlyEndOfData();
    const m = getScalar(view, pos, countType, little);
    if (m < 0) throw new PlyBadValue(`list '${list.name}' has an invalid entry count ${m}`);
    pos += countSize;
    if (pos + m * itemSize > end) throw new PlyEndOfData();
    if (m > maxCorners) throw tooManyCorners(m, maxCorners);
    if (m < 3) {
      pos += m * itemSize;
      skipped++;
      continue;
    }
    if (n + 3 * (m - 2) > indices.length) indices = grow(indices, n + 3 * (m - 2));
    const first = index(pos);
    let previous = index(pos + itemSize);
    for (let j = 2; j < m; j++) {
      const current = index(pos + j * itemSize);
      indices[n++] = first;
      indices[n++] = previous;
      indices[n++] = current;
      previous = current;
    }
    pos += m * itemSize;
  }
  reader.pos = pos;
  return { indices: n === indices.length ? indices : indices.slice(0, n), skipped };
}

function grow(a: Uint32Array, needed: number): Uint32Array {
  const b = new Uint32Array(Math.max(needed, a.length * 2));
  b.set(a);
  return b;
}

const outOfRange = (v: number, vertexCount: number): PlyBadValue =>
  new PlyBadValue(`vertex index ${v} is out of range (the file has ${vertexCount} vertices)`);

/** A polygon past the limit: fanned into triangles it would multiply the mesh. */
const tooManyCorners = (m: number, max: number): PlyBadValue =>
  new PlyBadValue(`a face has ${m} corners, over the limit polygonVertices=${max} (raise it with --limits polygonVertices=N)`);
