/**
 * A pass's `params` uniform, laid out by reflection of its WGSL module. `write` copies new values to
 * the GPU with queue.writeBuffer, which takes effect at the next submit: a pass that writes its
 * parameters this way must be submitted before it is encoded again.
 */
import { makeStructuredView, type StructuredView } from 'webgpu-utils';
import { reflectModule } from '../gpu/wgsl/reflect.ts';

/** Values by WGSL field name; nested structs as nested objects. */
export type UniformValues = { [field: string]: number | readonly number[] | UniformValues };

export class UniformParams<T extends UniformValues> {
  readonly buffer: GPUBuffer;
  private readonly view: StructuredView;

  constructor(private readonly device: GPUDevice, module: string, variable = 'params') {
    const def = reflectModule(module).defs.uniforms[variable];
    if (!def) throw new Error(`WGSL module '${module}' has no uniform '${variable}'`);
    this.view = makeStructuredView(def);
    this.buffer = device.createBuffer({ label: `${module} ${variable}`, size: this.view.arrayBuffer.byteLength, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  write(values: T): void {
    this.view.set(values);
    this.device.queue.writeBuffer(this.buffer, 0, this.view.arrayBuffer);
  }

  destroy(): void {
    this.buffer.destroy();
  }
}
