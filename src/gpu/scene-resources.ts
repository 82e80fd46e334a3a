/**
 * The GPU buffers of one scene (bind group 0), made from a PackedScene. Owns them: destroy() frees
 * them all, so switching scenes never leaks GPU memory.
 */
import { LanternError } from '../errors.ts';
import type { PackedScene } from './pack/scene-pack.ts';
import { createBufferWithData } from './readback.ts';
import { withErrorScope } from './device.ts';

const STORAGE_NAMES = ['bvh_nodes', 'triangles_hot', 'triangles_shading', 'materials', 'light_slots', 'texture_refs'] as const;
const UNIFORM_NAMES = ['scene_info', 'punctual_lights'] as const;

type BufferName = (typeof UNIFORM_NAMES)[number] | (typeof STORAGE_NAMES)[number];

export class SceneResources {
  /** Every group-0 resource keyed by its WGSL variable name in shaders/scene/bindings.wgsl. */
  readonly bindings: Readonly<Record<BufferName | 'texture_atlas' | 'texture_atlas_linear', GPUBuffer | GPUTextureView>>;

  private constructor(
    readonly buffers: Readonly<Record<BufferName, GPUBuffer>>,
    readonly atlas: GPUTexture,
    readonly linearAtlas: GPUTexture,
    readonly counts: PackedScene['counts'],
    readonly features: PackedScene['features'],
    readonly byteSize: number,
  ) {
    this.bindings = {
      ...buffers,
      texture_atlas: atlas.createView({ label: 'texture atlas', dimension: '2d-array' }),
      texture_atlas_linear: linearAtlas.createView({ label: 'linear texture atlas', dimension: '2d-array' }),
    };
  }

  static async upload(device: GPUDevice, packed: PackedScene, label: string): Promise<SceneResources> {
    const limit = device.limits.maxStorageBufferBindingSize;
    for (const name of STORAGE_NAMES) {
      const size = packed[name].byteLength;
      if (size > limit) {
        throw new LanternError(
          `scene '${label}' is too large for this GPU: ${name} needs ${(size / 2 ** 20).toFixed(1)} MiB but one storage buffer may hold ${(limit / 2 ** 20).toFixed(1)} MiB`,
          'Use a smaller scene or a GPU with larger storage buffers',
        );
      }
    }
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
    const atlasBytes = (a: PackedScene['atlas']) => a.pages.length * a.pageSize * a.pageSize * 4;
    const byteSize = Object.values(buffers).reduce((s, b) => s + b.size, 0) + atlasBytes(packed.atlas) + atlasBytes(packed.linearAtlas);
    return new SceneResources(buffers, atlas, linearAtlas, packed.counts, packed.features, byteSize);
  }

  destroy(): void {
    for (const b of Object.values(this.buffers)) b.destroy();
    this.atlas.destroy();
    this.linearAtlas.destroy();
  }
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
