/**
 * The glTF JSON's counts, checked before anything is read. glTF-Transform allocates every accessor
 * while it parses (count × element size, zero-filled when the accessor has no buffer view), copies
 * every image out of its buffer view and decodes meshopt views to count × stride bytes, all before
 * Lantern sees a mesh: a 268-byte file declaring 1.5·10⁸ vertices aborted V8 at 2.8 GB, a sparse
 * count of 10⁹ ran for minutes, 10⁷ EXT_mesh_gpu_instancing rows took 4.5 GB. So, from the JSON:
 *
 * - every accessor's count is a whole number, its elements fit in the buffer view it names, and the
 *   view in its buffer; a sparse accessor's count is from 1 to its accessor's;
 * - the bytes glTF-Transform will allocate or copy (accessor elements, sparse indices and values,
 *   meshopt-decoded views, images in buffer views), summed, are within `gltfBytes`: summed, because
 *   a thousand accessors or images may name one view, and each is copied;
 * - what Lantern builds from the scene is within `vertices` (of the meshes it places), `instances`
 *   (nodes with a mesh, and EXT_mesh_gpu_instancing rows) and `faces` (the triangles of every
 *   placement: the world-space list the BVH is built over).
 *
 * The JSON is untrusted: any member may be missing or of any type. What this check cannot size
 * (a missing mesh, a node that is not an object) is left to glTF-Transform, which refuses it.
 */
import { checkLimit } from '../../budgets.ts';
import { LanternError } from '../../errors.ts';

type Json = Readonly<Record<string, unknown>>;

const COMPONENT_BYTES: Readonly<Record<number, number>> = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
const COMPONENTS: Readonly<Record<string, number>> = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4, MAT2: 4, MAT3: 9, MAT4: 16 };
/** glTF primitive modes that make triangles (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN). */
const TRIANGLES = 4, STRIP = 5, FAN = 6;
/** The largest buffer a typed array holds (V8, Node 20+): a missing buffer's zero-filled stand-in is one. */
const MAX_BUFFER_BYTES = 2 ** 32;
const INSTANCING = 'EXT_mesh_gpu_instancing';

const obj = (v: unknown): Json | undefined => (typeof v === 'object' && v !== null && !Array.isArray(v) ? (v as Json) : undefined);
const list = (v: unknown): readonly unknown[] => (Array.isArray(v) ? v : []);
const isCount = (v: unknown): v is number => typeof v === 'number' && Number.isSafeInteger(v) && v >= 0;
const show = (v: unknown): string => (typeof v === 'number' ? v.toLocaleString('en-US') : JSON.stringify(v) ?? String(v));

/** Throws a LanternError when the counts of `json` (a glTF's parsed JSON) ask for more than the limits allow. */
export function checkGltfCounts(name: string, json: unknown): void {
  const root = obj(json) ?? {};
  const damaged = (what: string) => new LanternError(`${name}: ${what}`, 'the file is damaged; re-export it');
  const buffers = list(root.buffers), views = list(root.bufferViews), accessors = list(root.accessors);

  for (let b = 0; b < buffers.length; b++) {
    const length = obj(buffers[b])?.byteLength;
    if (!isCount(length) || length > MAX_BUFFER_BYTES) throw damaged(length === undefined ? `buffer ${b} declares no byteLength` : `buffer ${b} declares ${show(length)} bytes`);
  }

  // Each view once: inside its buffer; a meshopt view is decoded to count × byteStride new bytes.
  let bytes = 0;
  const viewLength = new Map<number, number>();
  const view = (index: unknown, what: string): number => {
    const known = typeof index === 'number' ? viewLength.get(index) : undefined;
    if (known !== undefined) return known;
    const v = isCount(index) ? obj(views[index]) : undefined;
    if (!v) throw damaged(`${what} names buffer view ${show(index)}, which does not exist`);
    const [offset, length] = [v.byteOffset ?? 0, v.byteLength];
    const buffer = isCount(v.buffer) ? obj(buffers[v.buffer]) : undefined;
    if (!buffer) throw damaged(`buffer view ${index} names buffer ${show(v.buffer)}, which does not exist`);
    if (!isCount(offset) || !isCount(length) || offset + length > (buffer.byteLength as number)) {
      throw damaged(`buffer view ${index} (${show(offset)} + ${show(length)} bytes) does not fit in buffer ${show(v.buffer)} (${show(buffer.byteLength)} bytes)`);
    }
    const meshopt = obj(obj(v.extensions)?.EXT_meshopt_compression);
    if (meshopt) {
      const [count, stride] = [meshopt.count, meshopt.byteStride];
      if (!isCount(count) || !isCount(stride)) throw damaged(`buffer view ${index}: EXT_meshopt_compression's count ${show(count)} and byteStride ${show(stride)} must be whole numbers`);
      bytes += count * stride;
    }
    viewLength.set(index as number, length);
    return length;
  };
  /** Checks that `count` elements of `elementBytes` from `byteOffset` of a view (at its stride) lie inside it. */
  const fits = (what: string, viewIndex: unknown, byteOffset: unknown, count: number, elementBytes: number) => {
    const length = view(viewIndex, what);
    const rawStride = obj(views[viewIndex as number])?.byteStride;
    const stride = rawStride === undefined ? elementBytes : rawStride;
    const offset = byteOffset ?? 0;
    if (!isCount(offset) || !isCount(stride) || stride === 0) throw damaged(`${what}: byteOffset ${show(offset)} and byteStride ${show(stride)} must be whole numbers`);
    const needed = count === 0 ? 0 : offset + stride * (count - 1) + elementBytes;
    if (needed > length) throw damaged(`${what} reads ${show(needed)} bytes of buffer view ${show(viewIndex)}, which has ${show(length)}`);
  };

  const counts: number[] = [];
  for (let i = 0; i < accessors.length; i++) {
    const a = obj(accessors[i]);
    if (!a) throw damaged(`accessor ${i} is not an object`);
    const count = a.count;
    if (!isCount(count)) throw damaged(`accessor ${i}: count ${show(count)} is not a whole number of elements`);
    const componentBytes = COMPONENT_BYTES[a.componentType as number];
    const components = COMPONENTS[a.type as string];
    if (componentBytes === undefined || components === undefined) throw damaged(`accessor ${i}: componentType ${show(a.componentType)} and type ${show(a.type)} are not ones glTF defines`);
    const elementBytes = componentBytes * components;
    if (a.bufferView !== undefined) fits(`accessor ${i}`, a.bufferView, a.byteOffset, count, elementBytes);
    bytes += count * elementBytes;
    if (a.sparse !== undefined) {
      const sparse = obj(a.sparse), indices = obj(sparse?.indices), values = obj(sparse?.values);
      const sparseCount = sparse?.count;
      if (!isCount(sparseCount) || sparseCount < 1 || sparseCount > count) throw damaged(`accessor ${i}: its sparse count ${show(sparseCount)} is not from 1 to its count ${show(count)}`);
      const indexBytes = COMPONENT_BYTES[indices?.componentType as number];
      if (!indices || !values || indexBytes === undefined) throw damaged(`accessor ${i}: its sparse indices or values are not described`);
      fits(`accessor ${i}'s sparse indices`, indices.bufferView, indices.byteOffset, sparseCount, indexBytes);
      fits(`accessor ${i}'s sparse values`, values.bufferView, values.byteOffset, sparseCount, elementBytes);
      bytes += sparseCount * (indexBytes + elementBytes);
    }
    counts.push(count);
  }
  // glTF-Transform copies each image in a buffer view out of it (a hundred images of one view: a hundred copies).
  for (const image of list(root.images)) {
    const at = obj(image)?.bufferView;
    if (at !== undefined) bytes += view(at, 'an image');
  }

  // What Lantern builds: each placed mesh's vertices once, every placement's triangles.
  const countOf = (accessor: unknown) => (isCount(accessor) ? (counts[accessor] ?? 0) : 0);
  const meshes = list(root.meshes);
  // Once per mesh: half a million nodes may place one mesh of ten thousand primitives.
  const sizes = new Map<number, { vertices: number; triangles: number }>();
  const meshSize = (mesh: number) => {
    const known = sizes.get(mesh);
    if (known) return known;
    let vertices = 0, triangles = 0;
    for (const p of list(obj(meshes[mesh])?.primitives)) {
      const primitive = obj(p);
      const positions = countOf(obj(primitive?.attributes)?.POSITION);
      const corners = primitive?.indices === undefined ? positions : countOf(primitive.indices);
      const mode = primitive?.mode ?? TRIANGLES;
      vertices += positions;
      triangles += mode === TRIANGLES ? Math.floor(corners / 3) : mode === STRIP || mode === FAN ? Math.max(0, corners - 2) : 0;
    }
    sizes.set(mesh, { vertices, triangles });
    return { vertices, triangles };
  };
  const instancing = list(root.extensionsUsed).includes(INSTANCING);
  const nodes = list(root.nodes), scenes = list(root.scenes);
  const scene = obj(scenes[isCount(root.scene) ? root.scene : 0]) ?? obj(scenes[0]);
  const pending = list(scene?.nodes).slice();
  const visited = new Set<unknown>();
  let vertices = 0, placements = 0, triangles = 0;
  while (pending.length > 0) {
    const index = pending.pop();
    if (visited.has(index)) continue;
    visited.add(index);
    const node = isCount(index) ? obj(nodes[index]) : undefined;
    if (!node) continue;
    for (const child of list(node.children)) pending.push(child);
    if (!isCount(node.mesh) || node.mesh >= meshes.length) continue;
    if (!sizes.has(node.mesh)) vertices += meshSize(node.mesh).vertices;
    const size = meshSize(node.mesh);
    // One placement per EXT_mesh_gpu_instancing row (the longest of its attributes), else one.
    const rows = instancing ? Object.values(obj(obj(obj(node.extensions)?.[INSTANCING])?.attributes) ?? {}).map(countOf) : [];
    const copies = rows.length > 0 ? rows.reduce((a, b) => Math.max(a, b), 0) : 1;
    placements += copies;
    triangles += copies * size.triangles;
  }

  checkLimit('vertices', vertices, `${name}: vertices of the meshes it places`);
  checkLimit('instances', placements, `${name}: instances (nodes with a mesh, EXT_mesh_gpu_instancing rows)`);
  checkLimit('faces', triangles, `${name}: triangles in the scene (each mesh's, once per instance)`);
  checkLimit('gltfBytes', bytes, `${name}: bytes of accessor and image data to read`);
}
