/**
 * glTF container and resources: sniffs .glb vs .gltf, splits a GLB into its JSON and binary chunk,
 * and supplies every buffer and image the JSON names (data: URIs decoded here, other URIs through the
 * caller's resolver) before glTF-Transform parses anything, so nothing is ever fetched.
 *
 * A missing buffer does not stop the load: glTF-Transform cannot parse a document whose buffer is
 * absent, so it gets a zero-filled stand-in of the declared length, and the buffer's index is
 * recorded; meshes.ts drops every primitive whose data lives in it.
 */
import { Logger, WebIO, type Document } from '@gltf-transform/core';
import { ALL_EXTENSIONS, KHRDracoMeshCompression } from '@gltf-transform/extensions';
import { MeshoptDecoder } from 'meshoptimizer/decoder';
import { LanternError } from '../../errors.ts';
import { siblingPath } from '../sibling-uri.ts';
import { decodeDataUri } from './data-uri.ts';
import { dracoDecoder } from './draco.ts';
import { byteSizes, GLB_MAGIC, glbChunks, isGlb, type ReadRange } from './glb.ts';
import { checkGltfCounts } from './preflight.ts';
import type { Warnings } from './warnings.ts';

/** Loose view of the raw glTF JSON: only what is read before glTF-Transform takes over. */
interface GltfJson {
  asset?: unknown;
  buffers?: { uri?: string; byteLength?: number; extensions?: { EXT_meshopt_compression?: { fallback?: boolean } } }[];
  bufferViews?: { buffer?: number; byteOffset?: number; byteLength?: number; extensions?: { EXT_meshopt_compression?: { buffer?: number } } }[];
  images?: { uri?: string; bufferView?: number; mimeType?: string; name?: string }[];
  accessors?: { bufferView?: number; sparse?: { indices?: { bufferView?: number }; values?: { bufferView?: number } } }[];
  meshes?: { primitives?: { attributes?: Record<string, number>; indices?: number; extensions?: { KHR_draco_mesh_compression?: { bufferView?: number } } }[] }[];
  extensionsUsed?: string[];
  extensionsRequired?: string[];
}

export interface GltfSource {
  readonly doc: Document;
  /** Per glTF mesh, per primitive: the URI of a missing buffer the primitive reads, if any. */
  readonly missingData: readonly (readonly (string | undefined)[])[];
  /** Per glTF image (same order as Document textures): the URI as written, or a label for embedded ones. */
  readonly imageNames: readonly string[];
  /** Per glTF image: true when its file could not be had (the texture's image is then empty). */
  readonly imageMissing: readonly boolean[];
}

/** The resource key glTF-Transform uses for a GLB's binary chunk. */
const GLB_BUFFER = '@glb.bin';

/** The extensions glTF-Transform knows; Draco is added per file, as its decoder is large (draco.ts). */
const EXTENSIONS = ALL_EXTENSIONS.filter((e) => e.EXTENSION_NAME !== KHRDracoMeshCompression.EXTENSION_NAME);

export async function readGltfSource(
  main: { name: string; bytes: Uint8Array },
  resolve: (uri: string) => Promise<Uint8Array | undefined>,
  warnings: Warnings,
): Promise<GltfSource> {
  const { json, bin } = splitContainer(main);
  checkRequiredExtensions(main.name, json);
  checkGltfCounts(main.name, json);

  // Every external file is asked for at once: a resolver in a browser may answer over messages.
  const buffers = json.buffers ?? [];
  const images = json.images ?? [];
  const [bufferBytes, imageBytes] = await Promise.all([
    Promise.all(buffers.map((b) => (b.uri === undefined ? undefined : fetchResource(b.uri, resolve)))),
    Promise.all(images.map((im) => (im.uri === undefined ? undefined : fetchResource(im.uri, resolve)))),
  ]);

  const resources: Record<string, Uint8Array> = {};
  // Resources are keyed "__lantern…": glTF-Transform treats "__"-prefixed URIs as internal names.
  const missingBuffers = new Map<number, string>();
  buffers.forEach((def, i) => {
    if (def.uri === undefined) {
      // EXT_meshopt_compression's fallback buffer holds no bytes; the decoder fills its views.
      if (def.extensions?.EXT_meshopt_compression?.fallback) return;
      if (i !== 0 || !bin) throw new LanternError(`${main.name}: buffer ${i} has no uri and there is no GLB binary chunk`, 'the file is damaged; re-export it');
      checkBinChunk(main.name, json, bin.length);
      resources[GLB_BUFFER] = bin;
      return;
    }
    const key = `__lantern_buffer_${i}`;
    const bytes = bufferBytes[i];
    if (!bytes) missingBuffers.set(i, def.uri);
    else if (def.byteLength !== undefined && bytes.length < def.byteLength) {
      const [has, declared] = byteSizes(bytes.length, def.byteLength);
      const which = def.uri.startsWith('data:') ? `buffer ${i} (a data: URI)` : `buffer ${i} ('${def.uri}')`;
      throw new LanternError(`${main.name}: ${which} has ${has}, the model declares ${declared}`, 'The buffer file is truncated or from another export: get the model again');
    }
    // glTF-Transform cannot parse around a missing buffer: a zero-filled stand-in takes its place,
    // and the primitives that read it are dropped (missingData below).
    resources[key] = bytes ?? new Uint8Array(def.byteLength ?? 0);
    def.uri = key;
  });

  const imageNames: string[] = [];
  const imageMissing: boolean[] = [];
  images.forEach((def, i) => {
    if (def.uri === undefined) {
      imageNames.push(def.name ?? `image ${i}`);
      imageMissing.push(false);
      return;
    }
    imageNames.push(def.uri.startsWith('data:') ? (def.name ?? `image ${i}`) : def.uri);
    const key = `__lantern_image_${i}`;
    const bytes = imageBytes[i];
    imageMissing.push(!bytes);
    resources[key] = bytes ?? new Uint8Array(0);
    def.uri = key;
  });

  const missingData = (json.meshes ?? []).map((mesh) =>
    (mesh.primitives ?? []).map((p) => {
      const accessors = [...Object.values(p.attributes ?? {}), ...(p.indices === undefined ? [] : [p.indices])];
      for (const a of accessors) {
        const uri = missingBufferOfAccessor(json, a, missingBuffers);
        if (uri) return uri;
      }
      // Draco primitives keep their compressed data in a view named by the extension.
      const draco = p.extensions?.KHR_draco_mesh_compression?.bufferView;
      const buffer = draco === undefined ? undefined : json.bufferViews?.[draco]?.buffer;
      return buffer === undefined ? undefined : missingBuffers.get(buffer);
    }),
  );
  for (const uri of new Set(missingData.flat().filter((u) => u !== undefined))) {
    warnings.missingFile(uri, 'the parts of the model stored in it are left out');
  }
  // A missing buffer no primitive reads (it held images, animations...) is still named once.
  for (const uri of missingBuffers.values()) warnings.missingFile(uri, 'what is stored in it is left out');

  await MeshoptDecoder.ready;
  const io = new WebIO()
    .setLogger(new Logger(Logger.Verbosity.SILENT))
    .registerExtensions(EXTENSIONS)
    .registerDependencies({ 'meshopt.decoder': MeshoptDecoder });
  if (json.extensionsUsed?.includes(KHRDracoMeshCompression.EXTENSION_NAME)) {
    let decoder: unknown;
    try {
      decoder = await dracoDecoder();
    } catch (e) {
      throw new LanternError(`${main.name}: the Draco decoder (KHR_draco_mesh_compression) could not be started (${(e as Error).message})`, 're-export the model without Draco compression', { cause: e });
    }
    io.registerExtensions([KHRDracoMeshCompression]).registerDependencies({ 'draco3d.decoder': decoder });
  }
  let doc: Document;
  try {
    doc = await io.readJSON({ json: json as never, resources: resources as Record<string, Uint8Array<ArrayBuffer>> });
  } catch (e) {
    throw new LanternError(`${main.name}: not a readable glTF file (${(e as Error).message})`, undefined, { cause: e });
  }
  return { doc, missingData, imageNames, imageMissing };
}

/** .glb: header, JSON chunk, optional BIN chunk. .gltf: UTF-8 JSON with an "asset" object. */
/**
 * Whether the first bytes are glTF: the GLB magic, or JSON whose top-level object has an "asset"
 * member within the head (the specification requires one; exporters write it first or near it).
 */
export function sniffGltf(head: Uint8Array): boolean {
  if (head.length >= 4 && new DataView(head.buffer, head.byteOffset, head.byteLength).getUint32(0, true) === GLB_MAGIC) return true;
  let i = 0;
  if (head[0] === 0xef && head[1] === 0xbb && head[2] === 0xbf) i = 3; // a UTF-8 byte order mark
  while (i < head.length && (head[i] === 0x20 || head[i] === 0x0a || head[i] === 0x0d || head[i] === 0x09)) i++;
  if (head[i] !== 0x7b) return false; // '{'
  return /"asset"\s*:/.test(new TextDecoder().decode(head));
}

/** The files a glTF refers to (external buffers and images), as paths relative to its folder. */
export function gltfSiblings(main: { name: string; bytes: Uint8Array }): string[] {
  let json: GltfJson;
  try {
    json = splitContainer(main).json;
  } catch {
    return [];
  }
  const uris = [...(json.buffers ?? []), ...(json.images ?? [])].map((r) => r.uri).filter((u): u is string => typeof u === 'string' && !u.startsWith('data:'));
  // Only what the model may name (sibling-uri.ts): the loader refuses the rest with a warning.
  return [...new Set(uris.flatMap((u) => { const sibling = siblingPath(u); return sibling.ok ? [sibling.path] : []; }))];
}

function splitContainer(main: { name: string; bytes: Uint8Array }): { json: GltfJson; bin?: Uint8Array } {
  const { bytes, name } = main;
  const read: ReadRange = (offset, length) => bytes.subarray(offset, offset + length);
  if (!isGlb(bytes.length, read)) return { json: parseJson(name, bytes) };
  const chunks = glbChunks(name, bytes.length, read);
  const json = parseJson(name, read(chunks.json.offset, chunks.json.length), 'its JSON chunk');
  return chunks.bin ? { json, bin: read(chunks.bin.offset, chunks.bin.length) } : { json };
}

/**
 * What can be told of a GLB from its size and a few ranges of it, before it is read whole: a truncated
 * file, a chunk past the end, a JSON chunk that is not glTF JSON, a BIN chunk shorter than the buffer
 * it holds. A .gltf is JSON throughout (parsing it is its load's work): nothing is checked early. The
 * loader finds all of these again (splitContainer, readGltfSource).
 */
export function checkGltfFile(name: string, size: number, read: ReadRange): void {
  if (!isGlb(size, read)) return;
  const chunks = glbChunks(name, size, read);
  const json = parseJson(name, read(chunks.json.offset, chunks.json.length), 'its JSON chunk');
  checkBinChunk(name, json, chunks.bin?.length);
}

/** The GLB's buffer (the first, without a uri) must fit in the BIN chunk; it may be up to 3 bytes shorter (padding). */
function checkBinChunk(name: string, json: GltfJson, binLength: number | undefined): void {
  const first = json.buffers?.[0];
  if (binLength === undefined || !first || first.uri !== undefined || first.byteLength === undefined || binLength >= first.byteLength) return;
  const [has, declared] = byteSizes(binLength, first.byteLength);
  throw new LanternError(`${name} is truncated: its BIN chunk holds ${has}, its buffer 0 declares ${declared}`, 'Re-export the model, or get the file again');
}

/** The glTF JSON of a .gltf file or of a GLB's JSON chunk (`what`), or a LanternError saying why not. */
/** V8's longest string (2^29 − 24 UTF-16 units): glTF JSON longer than that in bytes may not decode to one. */
const MAX_JSON_BYTES = 2 ** 29 - 24;

function parseJson(name: string, bytes: Uint8Array, what?: string): GltfJson {
  if (bytes.length > MAX_JSON_BYTES) throw new LanternError(`${name}: ${what ?? 'its JSON'} is ${bytes.length.toLocaleString('en-US')} bytes, more than JavaScript can hold as one string (${MAX_JSON_BYTES.toLocaleString('en-US')})`, 'Store the geometry in a .bin or a .glb binary chunk');
  let json: unknown;
  let why = '';
  try {
    json = JSON.parse(new TextDecoder().decode(bytes));
  } catch (e) {
    why = (e as Error).message;
  }
  if (what && why) throw new LanternError(`${name} is damaged: ${what} is not JSON (${why})`, 'Re-export the model, or get the file again');
  if (typeof json !== 'object' || json === null || typeof (json as GltfJson).asset !== 'object') {
    if (what) throw new LanternError(`${name} is damaged: ${what} has no "asset" object`, 'Re-export the model');
    throw new LanternError(`${name} is not a glTF file (neither GLB nor JSON with an "asset" object${why ? `: ${why}` : ''})`);
  }
  return json as GltfJson;
}

/** A required extension Lantern cannot read must stop the load (glTF 2.0 §3.12). */
function checkRequiredExtensions(name: string, json: GltfJson): void {
  const known = new Set<string>([...EXTENSIONS.map((e) => e.EXTENSION_NAME), KHRDracoMeshCompression.EXTENSION_NAME]);
  for (const ext of json.extensionsRequired ?? []) {
    if (!known.has(ext)) throw new LanternError(`${name} requires the glTF extension ${ext}, which Lantern does not support`);
  }
}

async function fetchResource(uri: string, resolve: (uri: string) => Promise<Uint8Array | undefined>): Promise<Uint8Array | undefined> {
  if (uri.startsWith('data:')) return decodeDataUri(uri);
  try {
    return await resolve(uri);
  } catch {
    // A resolver that throws (a file system error, a network error upstream) counts as missing.
    return undefined;
  }
}

function missingBufferOfAccessor(json: GltfJson, accessor: number, missing: ReadonlyMap<number, string>): string | undefined {
  if (missing.size === 0) return undefined;
  const def = json.accessors?.[accessor];
  const views = [def?.bufferView, def?.sparse?.indices?.bufferView, def?.sparse?.values?.bufferView];
  for (const v of views) {
    if (v === undefined) continue;
    const view = json.bufferViews?.[v];
    // A meshopt-compressed view reads its bytes from the extension's buffer, not its own fallback.
    for (const b of [view?.buffer, view?.extensions?.EXT_meshopt_compression?.buffer]) {
      const uri = b === undefined ? undefined : missing.get(b);
      if (uri) return uri;
    }
  }
  return undefined;
}
