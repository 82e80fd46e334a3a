/**
 * A packed scene as textures only (issue #30): what the fragment tracer binds in group 0 where the
 * compute kernels bind storage buffers, for WebGL2 (no storage buffers) and for the same tracer on
 * WebGPU. The six record arrays (bvh_nodes, triangles_hot, triangles_shading, materials, light_slots,
 * texture_refs) become rgba32uint textures that shaders/scene/bindings-textures.wgsl reads: record i
 * of a struct of S bytes takes the ceil(S / 16) texels from i · ceil(S / 16) on (its bytes in storage
 * order, the last texel zero-padded), texel k at (k mod W, k div W) for a row width W = 2^rowShift.
 * The scene's other textures (atlases, environment map and CDFs, BSDF tables, triangle attributes,
 * instance records) are listed as they are uploaded to WebGPU, so that one list is every texture of
 * group 0. Uniforms (scene_info, punctual_lights, environment_info) stay buffers: WebGL2 has uniform
 * blocks. Pure: bytes in, bytes out.
 */
import { LanternError } from '../../errors.ts';
import { bsdfTableTexture, BSDF_TABLE_TEXTURE_FORMAT } from './bsdf-tables.ts';
import { ENVIRONMENT_CDF_FORMAT, ENVIRONMENT_MAP_FORMAT } from './environment-pack.ts';
import { INSTANCE_TEXELS, INSTANCES_PER_ROW, sceneLayouts, type PackedScene } from './scene-pack.ts';

/** WebGL2's guaranteed MAX_TEXTURE_SIZE: the default limit of every side. */
export const WEBGL2_MAX_TEXTURE_SIZE = 2048;
/** The row width of the record textures on a device whose limit is WEBGL2_MAX_TEXTURE_SIZE (2^11). */
export const DEFAULT_ROW_SHIFT = 11;

export type SceneTextureFormat = 'rgba32uint' | 'r32uint' | 'rgba8unorm' | 'rgba8unorm-srgb';

/** One texture of group 0: its WGSL variable, binding and texels. */
export interface SceneTexture {
  /** The WGSL variable (shaders/scene/bindings-textures.wgsl, bindings-shared.wgsl). */
  readonly name: string;
  readonly group: 0;
  readonly binding: number;
  readonly format: SceneTextureFormat;
  readonly width: number;
  readonly height: number;
  /** 1 for a 2D texture; the pages of a 2D array texture (the atlases, bound as texture_2d_array). */
  readonly depthOrLayers: number;
  /** Whether the WGSL declares a texture_2d_array (the atlases) rather than a texture_2d. */
  readonly array: boolean;
  /** width × height × depthOrLayers texels, rows in order, layers after each other; bytes per texel by format. */
  readonly data: Uint8Array;
}

/** The record arrays, their bindings and struct names (shaders/scene/bindings.wgsl). */
export const RECORD_TEXTURES = [
  { name: 'bvh_nodes', binding: 1, layout: 'node' },
  { name: 'triangles_hot', binding: 2, layout: 'hot' },
  { name: 'triangles_shading', binding: 3, layout: 'shading' },
  { name: 'materials', binding: 4, layout: 'material' },
  { name: 'light_slots', binding: 5, layout: 'lightSlot' },
  { name: 'texture_refs', binding: 6, layout: 'textureRef' },
] as const;

export type RecordTextureName = (typeof RECORD_TEXTURES)[number]['name'];

export interface SceneTextures {
  readonly textures: readonly SceneTexture[];
  /** log2 of the record textures' row width: SCENE_TEXTURE_ROW_SHIFT of bindings-textures.wgsl. */
  readonly rowShift: number;
  /** Texels per record of each record texture (the struct's stride over 16, rounded up). */
  readonly texelsPerRecord: Readonly<Record<RecordTextureName, number>>;
  /** Bytes of every texture together. */
  readonly byteSize: number;
}

export interface SceneTextureOptions {
  /** The device's maxTextureDimension2D (WebGL2: MAX_TEXTURE_SIZE); default WebGL2's guaranteed 2048. */
  readonly maxTextureDimension2D?: number;
  /** The device's maxTextureArrayLayers (WebGL2: MAX_ARRAY_TEXTURE_LAYERS, 256 guaranteed); default 256. */
  readonly maxTextureArrayLayers?: number;
  /** Label for messages. */
  readonly label?: string;
  /** log2 of the record textures' row width, instead of sceneTextureRowShift's choice (tests: rows of a few texels). */
  readonly rowShift?: number;
}

const RECORD_FORMAT = 'rgba32uint';
const TEXEL_BYTES = 16;

/** Texels per record of a struct of `stride` bytes. */
export const texelsPerRecord = (stride: number): number => Math.ceil(stride / TEXEL_BYTES);

/** Where texel k of a record texture of row width 2^rowShift lies (bindings-textures.wgsl scene_texel_coord). */
export const texelCoord = (k: number, rowShift: number): { x: number; y: number } => ({ x: k % 2 ** rowShift, y: Math.floor(k / 2 ** rowShift) });

/** The size of a record texture of `texels` texels: one row when they fit, else whole rows of 2^rowShift. */
export function recordTextureSize(texels: number, rowShift: number): { width: number; height: number } {
  const row = 2 ** rowShift;
  const n = Math.max(1, texels);
  return n <= row ? { width: n, height: 1 } : { width: row, height: Math.ceil(n / row) };
}

/**
 * The row shift for record textures of these texel counts on a device of side `limit`: 2048-wide
 * rows (11) where everything fits 2048 × 2048 or the limit is no larger, else the narrowest power
 * of two up to the limit that fits; undefined when none does.
 */
export function sceneTextureRowShift(texelCounts: readonly number[], limit: number): number | undefined {
  const most = Math.max(1, ...texelCounts);
  const top = Math.floor(Math.log2(limit));
  for (let shift = Math.min(DEFAULT_ROW_SHIFT, top); shift <= top; shift++) {
    if (Math.ceil(most / 2 ** shift) <= limit) return shift;
  }
  return undefined;
}

/** The records of `bytes` (records of `stride` bytes) laid out `perRecord` texels each. */
function recordTexels(bytes: ArrayBuffer, stride: number, perRecord: number, size: { width: number; height: number }): Uint8Array {
  const src = new Uint8Array(bytes);
  const out = new Uint8Array(size.width * size.height * TEXEL_BYTES);
  const step = perRecord * TEXEL_BYTES;
  if (step === stride) {
    out.set(src);
    return out;
  }
  const records = Math.floor(src.byteLength / stride);
  for (let i = 0; i < records; i++) out.set(src.subarray(i * stride, (i + 1) * stride), i * step);
  return out;
}

const bytesOf = (a: ArrayBufferView): Uint8Array => new Uint8Array(a.buffer, a.byteOffset, a.byteLength);

function concatenate(pages: readonly Uint8Array[]): Uint8Array {
  const out = new Uint8Array(pages.reduce((s, p) => s + p.byteLength, 0));
  let at = 0;
  for (const p of pages) {
    out.set(p, at);
    at += p.byteLength;
  }
  return out;
}

/**
 * Every texture of group 0 for the fragment tracer, checked against the limits before any texel is
 * copied: a scene that does not fit is refused in one line naming the texture, its size and the limit.
 */
export function packSceneTextures(packed: PackedScene, options: SceneTextureOptions = {}): SceneTextures {
  const limit = options.maxTextureDimension2D ?? WEBGL2_MAX_TEXTURE_SIZE;
  const layersLimit = options.maxTextureArrayLayers ?? 256;
  const label = options.label ? ` of scene '${options.label}'` : '';
  const layouts = sceneLayouts();
  const records = RECORD_TEXTURES.map((r) => {
    const stride = layouts[r.layout].stride;
    const bytes = packed[r.name];
    if (bytes.byteLength % stride !== 0) throw new LanternError(`${r.name}${label} holds ${bytes.byteLength} bytes, not a whole number of ${stride}-byte records`);
    const perRecord = texelsPerRecord(stride);
    return { ...r, stride, bytes, perRecord, texels: (bytes.byteLength / stride) * perRecord };
  });
  const rowShift = options.rowShift ?? sceneTextureRowShift(records.map((r) => r.texels), limit);
  if (rowShift === undefined || records.some((r) => Math.ceil(r.texels / 2 ** rowShift) > limit) || 2 ** rowShift > limit) {
    const worst = records.reduce((a, b) => (b.texels > a.texels ? b : a));
    const row = 2 ** (options.rowShift ?? Math.floor(Math.log2(limit)));
    throw new LanternError(`${worst.name}${label} needs ${worst.texels.toLocaleString('en-US')} texels, ${Math.ceil(worst.texels / row).toLocaleString('en-US')} rows of ${row.toLocaleString('en-US')}: more than the ${limit.toLocaleString('en-US')} × ${limit.toLocaleString('en-US')} texels a texture may have here`);
  }

  // The textures uploaded as they are: their sizes first, checked before anything is copied.
  const env = packed.environment;
  const bsdf = bsdfTableTexture();
  const instanceRecords = Math.max(1, Math.ceil(packed.instances.byteLength / (INSTANCE_TEXELS * TEXEL_BYTES)));
  const instanceSize = { width: INSTANCES_PER_ROW * INSTANCE_TEXELS, height: Math.ceil(instanceRecords / INSTANCES_PER_ROW) };
  const attributes = packed.triangleAttributes;
  const sides: [string, number, number][] = [
    ['texture_atlas', packed.atlas.pageSize, packed.atlas.pageSize],
    ['texture_atlas_linear', packed.linearAtlas.pageSize, packed.linearAtlas.pageSize],
    ['environment_map', env.environment_map.width, env.environment_map.height],
    ['environment_cdf', env.environment_cdf.width, env.environment_cdf.height],
    ['bsdf_tables', bsdf.width, bsdf.height],
    ['triangle_attributes', attributes.width, attributes.height],
    ['instance_data', instanceSize.width, instanceSize.height],
  ];
  for (const [name, width, height] of sides) {
    if (width > limit || height > limit) throw new LanternError(`${name}${label} is ${width.toLocaleString('en-US')} × ${height.toLocaleString('en-US')} texels, more than the ${limit.toLocaleString('en-US')} a side a texture may have here`);
  }
  for (const [name, atlas] of [['texture_atlas', packed.atlas], ['texture_atlas_linear', packed.linearAtlas]] as const) {
    if (atlas.pages.length > layersLimit) throw new LanternError(`${name}${label} has ${atlas.pages.length} pages, more than the ${layersLimit} layers an array texture may have here`);
  }

  const textures: SceneTexture[] = records.map((r) => {
    const size = recordTextureSize(r.texels, rowShift);
    return { name: r.name, group: 0, binding: r.binding, format: RECORD_FORMAT, ...size, depthOrLayers: 1, array: false, data: recordTexels(r.bytes, r.stride, r.perRecord, size) };
  });
  const atlasTexture = (name: string, binding: number, format: SceneTextureFormat, atlas: PackedScene['atlas']): SceneTexture => ({
    name,
    group: 0,
    binding,
    format,
    width: atlas.pageSize,
    height: atlas.pageSize,
    depthOrLayers: atlas.pages.length,
    array: true,
    data: concatenate(atlas.pages),
  });
  // RGB to RGBA (alpha 1), as gpu/scene-resources.ts uploads it.
  const map = env.environment_map;
  const rgba = new Float32Array(map.width * map.height * 4);
  for (let p = 0, q = 0; q < rgba.length; p += 3, q += 4) {
    rgba[q] = map.rgb[p]!;
    rgba[q + 1] = map.rgb[p + 1]!;
    rgba[q + 2] = map.rgb[p + 2]!;
    rgba[q + 3] = 1;
  }
  const instances = new Uint8Array(instanceSize.width * instanceSize.height * TEXEL_BYTES);
  instances.set(new Uint8Array(packed.instances));
  const plain = (name: string, binding: number, format: SceneTextureFormat, width: number, height: number, data: Uint8Array): SceneTexture => ({ name, group: 0, binding, format, width, height, depthOrLayers: 1, array: false, data });
  textures.push(
    atlasTexture('texture_atlas', 7, 'rgba8unorm-srgb', packed.atlas),
    plain('environment_map', 9, ENVIRONMENT_MAP_FORMAT as SceneTextureFormat, map.width, map.height, bytesOf(rgba)),
    plain('environment_cdf', 10, ENVIRONMENT_CDF_FORMAT as SceneTextureFormat, env.environment_cdf.width, env.environment_cdf.height, bytesOf(env.environment_cdf.data)),
    plain('bsdf_tables', 12, BSDF_TABLE_TEXTURE_FORMAT as SceneTextureFormat, bsdf.width, bsdf.height, bytesOf(bsdf.data)),
    atlasTexture('texture_atlas_linear', 13, 'rgba8unorm', packed.linearAtlas),
    plain('triangle_attributes', 15, 'rgba32uint', attributes.width, attributes.height, bytesOf(attributes.data)),
    plain('instance_data', 16, 'rgba32uint', instanceSize.width, instanceSize.height, instances),
  );
  const texelsPerRecordByName = Object.fromEntries(records.map((r) => [r.name, r.perRecord])) as Record<RecordTextureName, number>;
  return { textures, rowShift, texelsPerRecord: texelsPerRecordByName, byteSize: textures.reduce((s, t) => s + t.data.byteLength, 0) };
}

/** Bytes per texel of a scene texture's format. */
export const formatBytes = (format: SceneTextureFormat): number => (format === 'rgba32uint' ? 16 : 4);
