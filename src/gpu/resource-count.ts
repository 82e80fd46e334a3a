/**
 * Counts the GPU buffers and textures a device holds: created minus destroyed. The viewer shows the
 * numbers and the page tests check that loading and unloading scenes gives every buffer back (a
 * buffer that is merely dropped lives on until garbage collection, which may never come while the
 * page is busy, so Lantern destroys what it creates and this count proves it).
 *
 * It works by wrapping `createBuffer` / `createTexture` of one device object, so it needs no
 * cooperation from the code that allocates.
 */

export interface ResourceCount {
  /** Buffers created and not yet destroyed. */
  readonly buffers: number;
  /** Textures created and not yet destroyed (canvas textures are not counted: the canvas owns them). */
  readonly textures: number;
  /** Bytes of the live buffers and textures (texture bytes assume 4 bytes per texel and no mips). */
  readonly bytes: number;
}

export class ResourceCounter {
  private liveBuffers = 0;
  private liveTextures = 0;
  private liveBytes = 0;

  /** Wraps `device`'s allocation methods; call once per device, before anything is allocated. */
  constructor(device: GPUDevice) {
    const createBuffer = device.createBuffer.bind(device);
    const createTexture = device.createTexture.bind(device);
    device.createBuffer = (descriptor: GPUBufferDescriptor): GPUBuffer => {
      const buffer = createBuffer(descriptor);
      this.track(buffer, descriptor.size, 'buffer');
      return buffer;
    };
    device.createTexture = (descriptor: GPUTextureDescriptor): GPUTexture => {
      const texture = createTexture(descriptor);
      this.track(texture, texture.width * texture.height * texture.depthOrArrayLayers * 4, 'texture');
      return texture;
    };
  }

  get count(): ResourceCount {
    return { buffers: this.liveBuffers, textures: this.liveTextures, bytes: this.liveBytes };
  }

  private track(resource: GPUBuffer | GPUTexture, bytes: number, kind: 'buffer' | 'texture'): void {
    this.add(kind, 1, bytes);
    const destroy = resource.destroy.bind(resource);
    let destroyed = false;
    // destroy() may be called more than once (WebGPU allows it); count the first.
    resource.destroy = () => {
      if (!destroyed) {
        destroyed = true;
        this.add(kind, -1, -bytes);
      }
      destroy();
    };
  }

  private add(kind: 'buffer' | 'texture', n: number, bytes: number): void {
    if (kind === 'buffer') this.liveBuffers += n;
    else this.liveTextures += n;
    this.liveBytes += bytes;
  }
}
