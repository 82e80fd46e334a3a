/** Helpers for GPU tests that run a kernel of their own, linked against the real WGSL modules. */
import { ComputeKernel } from '../../src/gpu/kernel.ts';
import { readBuffer, createBufferWithData } from '../../src/gpu/readback.ts';
import { linkWgsl } from '../../src/gpu/wgsl/linker.ts';
import { reflectLinked } from '../../src/gpu/wgsl/reflect.ts';
import { SHADER_MODULES } from '../../src/shaders/index.ts';

/** A test kernel: `code` may `#import` any module of src/shaders. */
export async function testKernel(device: GPUDevice, name: string, code: string, entryPoint: string, constants?: Record<string, number>): Promise<ComputeKernel> {
  const sources = new Map(SHADER_MODULES);
  sources.set(name, code);
  return ComputeKernel.create(device, { module: reflectLinked(linkWgsl(name, sources)), entryPoint, ...(constants ? { constants } : {}) });
}

export function storageBuffer(device: GPUDevice, label: string, data: ArrayBuffer | ArrayBufferView): GPUBuffer {
  return createBufferWithData(device, label, data, GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST);
}

export function uniformBuffer(device: GPUDevice, label: string, data: ArrayBuffer | ArrayBufferView): GPUBuffer {
  return createBufferWithData(device, label, data, GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST);
}

export function outputBuffer(device: GPUDevice, label: string, bytes: number): GPUBuffer {
  return device.createBuffer({ label, size: bytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
}

/** Dispatches once and reads `output` back. */
export async function runOnce(device: GPUDevice, kernel: ComputeKernel, groups: Record<number, GPUBindGroup>, workgroups: [number, number?, number?], output: GPUBuffer): Promise<ArrayBuffer> {
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginComputePass();
  kernel.dispatch(pass, groups, ...workgroups);
  pass.end();
  device.queue.submit([encoder.finish()]);
  return readBuffer(device, output);
}
