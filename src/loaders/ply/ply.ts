/**
 * Stanford PLY loader: one triangle mesh from the `vertex` and `face` elements of an ascii or binary
 * (either endianness) file, optionally gzip-compressed. Everything else in the file is skipped.
 * Pure: bytes in, Scene out; runs in Node, the browser and Web Workers alike.
 */
import { LanternError } from '../../errors.ts';
import { checkLimit } from '../../budgets.ts';
import { gunzipCapped, isGzip } from '../gzip.ts';
import { studioScene } from '../../scene/studio.ts';
import { diffuse, type Material, type Mesh, type Scene } from '../../scene/types.ts';
import { MAX_HEADER_BYTES, parsePlyHeader, SCALAR_SIZE, type PlyElement, type PlyHeader, type PlyProperty } from './header.ts';
import { AsciiReader, BinaryReader, PlyBadValue, PlyEndOfData, readListCount, type ValueReader } from './readers.ts';
import { readFaces, readVertices, type FaceData, type VertexData } from './elements.ts';

export interface ParsedPly {
  readonly mesh: Mesh;
  readonly header: PlyHeader;
  /** Things that did not stop the load but that a user may want to know (skipped faces, dropped normals). */
  readonly warnings: readonly string[];
}

export interface LoadPlyOptions {
  onWarning?: (message: string) => void;
}

/** A PLY mesh in a lit studio (floor, two area lights, three-quarter camera) with one white diffuse material. */
export function loadPly(bytes: Uint8Array, name: string, options: LoadPlyOptions = {}): Scene {
  const { mesh, warnings } = parsePly(bytes, name);
  for (const w of warnings) options.onWarning?.(w);
  const white: Material = diffuse('ply diffuse', [0.8, 0.8, 0.8]);
  return studioScene(name, [mesh], [white]);
}

/** The mesh alone, with material id 0 on every triangle. */
export function parsePly(input: Uint8Array, name: string): ParsedPly {
  // A gzipped file's header is read (and its counts checked) before the rest is inflated.
  const bytes = isGzip(input) ? gunzipCapped(input, name, { bytes: MAX_HEADER_BYTES, check: (head) => void meshElements(parsePlyHeader(head, name), name, true) }) : input;
  const header = parsePlyHeader(bytes, name);
  const { vertexElement, faceElement } = meshElements(header, name, false);
  checkMinimumSize(bytes.length - header.bodyOffset, header, name);
  checkCounts(vertexElement, faceElement, name);

  const reader: ValueReader =
    header.format === 'ascii'
      ? new AsciiReader(bytes, header.bodyOffset)
      : new BinaryReader(bytes, header.bodyOffset, header.format === 'binary_little_endian');
  const warnings: string[] = [];
  let vertices: VertexData | undefined;
  let faces: FaceData | undefined;

  // Elements are read in file order: the face element may legally precede the vertex element, so
  // face indices are checked against the vertex count declared in the header, not the one read so far.
  for (const element of header.elements) {
    const context = { index: 0 };
    try {
      if (element === vertexElement) vertices = readVertices(reader, element, name, context);
      else if (element === faceElement) faces = readFaces(reader, element, vertexElement.count, name, context);
      else skipElement(reader, element, context);
    } catch (e) {
      throw describeReadError(e, name, element, context.index);
    }
  }
  if (!vertices || !faces) throw new Error('unreachable: both elements were read');
  if (faces.skipped > 0) warnings.push(`${name}: skipped ${faces.skipped} face(s) with fewer than 3 vertices`);
  if (faces.indices.length === 0) {
    throw new LanternError(`${name}: the PLY file has no faces (${faceElement.count} face records, none with 3 or more vertices)`);
  }
  if (vertices.droppedNormals) warnings.push(`${name}: ignored the vertex normals: ${vertices.droppedNormals}`);

  const mesh: Mesh = {
    name,
    positions: vertices.positions,
    indices: faces.indices,
    materialIds: new Uint32Array(faces.indices.length / 3),
    ...(vertices.normals ? { normals: vertices.normals } : {}),
    ...(vertices.uvs ? { uvs: vertices.uvs } : {}),
  };
  return { mesh, header, warnings };
}

/** The vertex and face elements, which a mesh must have; `counts`: their counts checked against the limits too. */
function meshElements(header: PlyHeader, name: string, counts: boolean): { vertexElement: PlyElement; faceElement: PlyElement } {
  const vertexElement = header.elements.find((e) => e.name === 'vertex');
  if (!vertexElement) throw new LanternError(`${name}: the PLY file has no 'vertex' element`);
  const faceElement = header.elements.find((e) => e.name === 'face');
  if (!faceElement) {
    throw new LanternError(`${name}: the PLY file has no faces (no 'face' element)`, 'Lantern renders triangle meshes, not point clouds');
  }
  if (counts) checkCounts(vertexElement, faceElement, name);
  return { vertexElement, faceElement };
}

function checkCounts(vertexElement: PlyElement, faceElement: PlyElement, name: string): void {
  checkLimit('vertices', vertexElement.count, `${name}: vertices`);
  checkLimit('faces', faceElement.count, `${name}: faces`);
}

/**
 * Each record takes at least a known number of bytes (binary: its fixed scalars plus list counts;
 * ascii: one token and one separator per property), so a header declaring more records than the body
 * could hold is rejected before anything is allocated or looped over.
 */
function checkMinimumSize(available: number, header: PlyHeader, name: string): void {
  let needed = 0;
  // While every element so far has fixed-size binary records, "at least" is "exactly", and the
  // record in which the data runs out is known.
  let exact = header.format !== 'ascii';
  // An ascii file may omit the separator after its very last token.
  const slack = header.format === 'ascii' ? 1 : 0;
  for (const e of header.elements) {
    exact &&= e.properties.every((p) => p.kind === 'scalar');
    const perRecord =
      header.format === 'ascii'
        ? 2 * e.properties.length
        : e.properties.reduce((s, p) => s + SCALAR_SIZE[p.kind === 'list' ? p.countType : p.type], 0);
    if (needed + e.count * perRecord - slack > available) {
      if (exact) {
        const index = Math.floor((available - needed) / perRecord);
        throw new LanternError(`${name}: the PLY data ends inside ${e.name} ${index} of ${e.count}`, TRUNCATED_HINT);
      }
      throw new LanternError(
        `${name}: the PLY data is truncated: element '${e.name}' declares ${e.count} records, more than the ${available} bytes after the header can hold`,
        TRUNCATED_HINT,
      );
    }
    needed += e.count * perRecord;
  }
}

const TRUNCATED_HINT = 'the file is truncated or its header counts are wrong';

function skipElement(reader: ValueReader, element: PlyElement, context: { index: number }): void {
  const props: readonly PlyProperty[] = element.properties;
  if (props.length === 0) return; // nothing to read, however many records it declares
  if (reader instanceof BinaryReader && props.every((p) => p.kind === 'scalar')) {
    const stride = props.reduce((s, p) => s + SCALAR_SIZE[p.kind === 'scalar' ? p.type : 'uint8'], 0);
    if (stride * element.count > reader.remaining) {
      context.index = Math.floor(reader.remaining / stride);
      throw new PlyEndOfData();
    }
    reader.pos += stride * element.count;
    return;
  }
  for (let i = 0; i < element.count; i++) {
    context.index = i;
    for (const p of props) {
      if (p.kind === 'scalar') reader.skip(p.type, 1);
      else reader.skip(p.itemType, readListCount(reader, p));
    }
  }
}

function describeReadError(e: unknown, name: string, element: PlyElement, index: number): unknown {
  const where = `${element.name} ${index} of ${element.count}`;
  if (e instanceof PlyEndOfData) {
    return new LanternError(`${name}: the PLY data ends inside ${where}`, TRUNCATED_HINT);
  }
  if (e instanceof PlyBadValue) return new LanternError(`${name}: ${where}: ${e.detail}`);
  return e;
}
