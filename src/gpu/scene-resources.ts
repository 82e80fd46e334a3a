/**
 * The GPU buffers of one scene (bind group 0), made from a PackedScene. Owns them: destroy() frees
 * them all, so switching scenes never leaks GPU memory.
 */
import { LanternError } from '../errors.ts';
import { BSDF_TABLE_TEXTURE_FORMAT, bsdfTableTexture } from './pack/bsdf-tables.ts';
import { ENVIRONMENT_CDF_FORMAT, ENVIRONMENT_MAP_FORMAT, type PackedEnvironment } from './pack/environment-pack.ts';
import type { PackedScene } from './pack/scene-pack.ts';
import { createBufferWithData } from './readback.ts';
import { withErrorScope } from './device.ts';
import { checkSceneFits, instanceTextureSize } from './scene-limits.ts';

const STORAGE_NAMES = ['bvh_nodes', 'triangles_hot', 'triangles_shading', 'materials', 'light_slots', 'texture_refs'] as const;
const UNIFORM_NAMES = ['scene_info', 'punctual_lights'] as const;
type TextureName = 'texture_atlas' | 'texture_atlas_linear' | 'environment_map' | 'environment_cdf' | 'bsdf_tables' | 'triangle_attributes' | 'instance_data';

type BufferName = (typeof UNIFORM_NAMES)[number] | (typeof STORAGE_NAMES)[number];

export class SceneResources {
  /** Every group-0 resource keyed by its WGSL variable name in shaders/scene/bindings.wgsl. */
  readonly bindings: Readonly<Record<BufferName | 'environment_info' | TextureName, GPUBuffer | GPUTextureView>>;

  private constructor(
    readonly buffers: Readonly<Record<BufferName, GPUBuffer>>,
    readonly atlas: GPUTexture,
    readonly linearAtlas: GPUTexture,
    private readonly environment: UploadedEnvironment,
    private readonly bsdfTables: GPUTexture,
    /** Per-vertex tangents and second uvs (group 0 binding 15); rewritten in place when instances move. */
    readonly triangleAttributes: GPUTexture,
    /** The Instance records (group 0 binding 16), rewritten whenever an instance moves. */
    readonly instanceData: GPUTexture,
    readonly counts: PackedScene['counts'],
    readonly features: PackedScene['features'],
    readonly byteSize: number,
  ) {
    this.bindings = {
      ...buffers,
      texture_atlas: atlas.createView({ label: 'texture atlas', dimension: '2d-array' }),
      texture_atlas_linear: linearAtlas.createView({ label: 'linear texture atlas', dimension: '2d-array' }),
      ...environment.bindings,
      bsdf_tables: bsdfTables.createView({ label: 'BSDF tables' }),
      triangle_attributes: triangleAttributes.createView({ label: 'triangle attributes' }),
      instance_data: instanceData.createView({ label: 'instance records' }),
    };
  }

  static async upload(device: GPUDevice, packed: PackedScene, label: string): Promise<SceneResources> {
    // Before anything is allocated: a scene that cannot fit leaves nothing half made.
    checkSceneFits(packed, device.limits, label);
    const buffers = await withErrorScope(device, `the GPU buffers of scene '${label}'`, () => {
      const b: Record<string, GPUBuffer> = {};
      for (const name of UNIFORM_NAMES) {
        b[name] = createBufferWithData(device, `${label} ${name}`, packed[name], GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST);
      }
      for (const name of STORAGE_NAMES) {
        b[name] = createBufferWithData(device, `${label} ${name}`, packed[name], GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST);
      }
      return b as SceneResources['buffers'];
    });
    const atlas = await uploadAtlas(device, packed.atlas, 'rgba8unorm-srgb', `${label} texture atlas`);
    const linearAtlas = await uploadAtlas(device, packed.linearAtlas, 'rgba8unorm', `${label} linear texture atlas`);
    const environment = await uploadEnvironment(device, packed.environment, label);
    const bsdfTables = await uploadBsdfTables(device);
    const attributes = packed.triangleAttributes;
    const triangleAttributes = await withErrorScope(device, `the tangents of scene '${label}'`, () => {
      const texture = device.createTexture({ label: `${label} triangle attributes`, size: [attributes.width, attributes.height], format: 'rgba32uint', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
      writeTriangleAttributes(device, texture, attributes);
      return texture;
    });
    const instanceData = await withErrorScope(device, `the instances of scene '${label}'`, () => createInstanceTexture(device, packed.instances, label));
    const atlasBytes = (a: PackedScene['atlas']) => a.pages.length * a.pageSize * a.pageSize * 4;
    const byteSize = Object.values(buffers).reduce((s, b) => s + b.size, 0) + atlasBytes(packed.atlas) + atlasBytes(packed.linearAtlas) + environment.byteSize;
    return new SceneResources(buffers, atlas, linearAtlas, environment, bsdfTables, triangleAttributes, instanceData, packed.counts, packed.features, byteSize + bsdfTables.width * bsdfTables.height * 4 + attributes.data.byteLength + instanceData.width * instanceData.height * 16);
  }

  /**
   * Writes new contents into one of the group-0 buffers (materials, the light table after an edit).
   * Where they no longer fit, that buffer alone is made anew (the old one destroyed) and a new
   * SceneResources sharing everything else is returned, so bind groups cached per SceneResources are
   * made again; otherwise `this`.
   */
  rewriteBuffer(device: GPUDevice, name: BufferName, data: ArrayBuffer): SceneResources {
    const old = this.buffers[name];
    if (data.byteLength <= old.size) {
      device.queue.writeBuffer(old, 0, data);
      return this;
    }
    if ((STORAGE_NAMES as readonly string[]).includes(name) && data.byteLength > device.limits.maxStorageBufferBindingSize) {
      throw new LanternError(`${name} needs ${(data.byteLength / 2 ** 20).toFixed(1)} MiB, more than one storage buffer may hold on this GPU`);
    }
    const buffer = createBufferWithData(device, old.label, data, old.usage);
    old.destroy();
    return new SceneResources(
      { ...this.buffers, [name]: buffer },
      this.atlas,
      this.linearAtlas,
      this.environment,
      this.bsdfTables,
      this.triangleAttributes,
      this.instanceData,
      this.counts,
      this.features,
      this.byteSize - old.size + buffer.size,
    );
  }

  /**
   * Writes the Instance records (PackedScene.instances) into instance_data; where they need more rows
   * than it has, the texture alone is made anew and a new SceneResources returned (as rewriteBuffer).
   */
  rewriteInstances(device: GPUDevice, records: ArrayBuffer): SceneResources {
    const { height } = instanceTextureSize(records.byteLength);
    if (height <= this.instanceData.height) {
      writeInstanceTexture(device, this.instanceData, records);
      return this;
    }
    const texture = createInstanceTexture(device, records, this.instanceData.label);
    const oldBytes = this.instanceData.width * this.instanceData.height * 16;
    this.instanceData.destroy();
    return new SceneResources(this.buffers, this.atlas, this.linearAtlas, this.environment, this.bsdfTables, this.triangleAttributes, texture, this.counts, this.features, this.byteSize - oldBytes + texture.width * texture.height * 16);
  }

  destroy(): void {
    for (const b of Object.values(this.buffers)) b.destroy();
    this.atlas.destroy();
    this.linearAtlas.destroy();
    this.environment.destroy();
    this.bsdfTables.destroy();
    this.triangleAttributes.destroy();
    this.instanceData.destroy();
  }
}

function createInstanceTexture(device: GPUDevice, records: ArrayBuffer, label: string): GPUTexture {
  const { width, height } = instanceTextureSize(records.byteLength);
  const texture = device.createTexture({ label: `${label} instance records`, size: [width, height], format: 'rgba32uint', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
  writeInstanceTexture(device, texture, records);
  return texture;
}

/** The records' bytes are the texels in order: whole rows, the last padded with zeros. */
function writeInstanceTexture(device: GPUDevice, texture: GPUTexture, records: ArrayBuffer): void {
  const { width, height } = instanceTextureSize(records.byteLength);
  const data = new Uint8Array(width * height * 16);
  data.set(new Uint8Array(records));
  device.queue.writeTexture({ texture }, data, { bytesPerRow: width * 16, rowsPerImage: height }, [width, height]);
}

/** Writes triangle_attributes' texels (f32 bits into rgba32uint). */
export function writeTriangleAttributes(device: GPUDevice, texture: GPUTexture, a: PackedScene['triangleAttributes']): void {
  device.queue.writeTexture({ texture }, a.data, { bytesPerRow: a.width * 16, rowsPerImage: a.height }, [a.width, a.height]);
}

/** The BSDF energy tables (group 0 binding 12): the same for every scene, 41 KB. */
export function uploadBsdfTables(device: GPUDevice): Promise<GPUTexture> {
  const t = bsdfTableTexture();
  return withErrorScope(device, 'the BSDF tables', () => {
    const texture = device.createTexture({ label: 'BSDF tables', size: [t.width, t.height], format: BSDF_TABLE_TEXTURE_FORMAT, usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    device.queue.writeTexture({ texture }, t.data, { bytesPerRow: t.width * 4, rowsPerImage: t.height }, [t.width, t.height]);
    return texture;
  });
}

export interface UploadedEnvironment {
  /** environment_info, environment_map and environment_cdf, by their WGSL names. */
  readonly bindings: Readonly<Record<'environment_info' | 'environment_map' | 'environment_cdf', GPUBuffer | GPUTextureView>>;
  readonly byteSize: number;
  destroy(): void;
}

/**
 * Bytes one writeTexture of a large texture stages at a time: the queue copies what it is given
 * into memory of its own until the GPU has taken it, so an 8K environment map (512 MB) written at
 * once was held once more, besides the RGBA copy it was written from.
 */
const UPLOAD_BAND_BYTES = 8 << 20;

/**
 * The usage of a texture written in bands. RENDER_ATTACHMENT lets Dawn zero a texture that no single
 * write covers (it does before the first band lands) with a render pass; without it, Dawn copied a
 * zero-filled buffer of the texture's whole size (512 MB more at once for an 8K map, measured on
 * SwiftShader: the upload peaked at 1.93 GB, and at 1.64 GB with it).
 */
const bandedTextureUsage = (): GPUTextureUsageFlags => GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.RENDER_ATTACHMENT;

/**
 * Writes a 2D texture of `floatsPerTexel` f32 per texel a band of rows at a time, each taken by the
 * GPU before the next is staged; `fill(y, rows, band)` writes rows y.. into `band` (reused: the
 * queue copies it at once).
 */
async function writeTextureInBands(device: GPUDevice, texture: GPUTexture, floatsPerTexel: number, fill: (y: number, rows: number, band: Float32Array) => void, what: string): Promise<void> {
  const { width, height } = texture;
  const bytesPerRow = width * floatsPerTexel * 4;
  const rows = Math.max(1, Math.min(height, Math.floor(UPLOAD_BAND_BYTES / bytesPerRow)));
  const band = new Float32Array(rows * width * floatsPerTexel);
  for (let y = 0; y < height; y += rows) {
    const n = Math.min(rows, height - y);
    const data = band.subarray(0, n * width * floatsPerTexel);
    fill(y, n, data);
    await withErrorScope(device, what, () => device.queue.writeTexture({ texture, origin: [0, y] }, data, { bytesPerRow, rowsPerImage: n }, [width, n]));
    if (y + n < height) await device.queue.onSubmittedWorkDone();
  }
}

/** The environment's resources of group 0 (bindings 8–10, see shaders/scene/bindings.wgsl). */
export async function uploadEnvironment(device: GPUDevice, packed: PackedEnvironment, label: string): Promise<UploadedEnvironment> {
  const map = packed.environment_map;
  const cdf = packed.environment_cdf;
  const uploaded = await withErrorScope(device, `the environment of scene '${label}'`, () => {
    const info = createBufferWithData(device, `${label} environment_info`, packed.environment_info, GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST);
    const mapTexture = device.createTexture({ label: `${label} environment map`, size: [map.width, map.height], format: ENVIRONMENT_MAP_FORMAT, usage: bandedTextureUsage() });
    const cdfTexture = device.createTexture({ label: `${label} environment CDFs`, size: [cdf.width, cdf.height], format: ENVIRONMENT_CDF_FORMAT, usage: bandedTextureUsage() });
    return {
      bindings: { environment_info: info, environment_map: mapTexture.createView(), environment_cdf: cdfTexture.createView() },
      byteSize: info.size + map.width * map.height * 16 + cdf.width * cdf.height * 4,
      destroy: () => {
        info.destroy();
        mapTexture.destroy();
        cdfTexture.destroy();
      },
      mapTexture,
      cdfTexture,
    };
  });
  // RGB to the texture's RGBA (alpha 1), a band at a time.
  await writeTextureInBands(device, uploaded.mapTexture, 4, (y, _rows, band) => {
    for (let p = y * map.width * 3, q = 0; q < band.length; p += 3, q += 4) {
      band[q] = map.rgb[p]!;
      band[q + 1] = map.rgb[p + 1]!;
      band[q + 2] = map.rgb[p + 2]!;
      band[q + 3] = 1;
    }
  }, `the environment map of scene '${label}' (${map.width}×${map.height})`);
  await writeTextureInBands(device, uploaded.cdfTexture, 1, (y, rows, band) => band.set(cdf.data.subarray(y * cdf.width, (y + rows) * cdf.width)), `the environment's sampling table of scene '${label}'`);
  return uploaded;
}

function uploadAtlas(device: GPUDevice, atlas: PackedScene['atlas'], format: GPUTextureFormat, label: string): Promise<GPUTexture> {
  const { pageSize, pages } = atlas;
  return withErrorScope(device, `${label} (${pages.length} × ${pageSize}² texels)`, () => {
    const texture = device.createTexture({
      label,
      size: [pageSize, pageSize, pages.length],
      format,
      usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
    });
    pages.forEach((page, layer) => {
      device.queue.writeTexture({ texture, origin: [0, 0, layer] }, page, { bytesPerRow: pageSize * 4 }, [pageSize, pageSize, 1]);
    });
    return texture;
  });
}
