/**
 * Every compute entry point of src/shaders binds at most 10 storage buffers: browsers give a compute
 * stage no more (Chromium's SwiftShader adapter offers exactly 10, and GPUs in browsers often only
 * 8–10), while Dawn in Node offers more, so a kernel over the limit passes every Node test and fails
 * in the page. The ReSTIR merge made path_trace_frame bind 11; the browser tests caught it, this
 * catches it without a browser.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { describe, expect, it } from 'vitest';
import { entryPointBindings, reflectModule } from './reflect.ts';

const BROWSER_STORAGE_BUFFERS_PER_STAGE = 10;
const SHADERS = join(import.meta.dirname, '../../shaders');
/** GPUShaderStage.COMPUTE (the global is not there without a WebGPU implementation). */
const COMPUTE = 4;

function wgslFiles(dir: string): string[] {
  return readdirSync(dir, { withFileTypes: true }).flatMap((d) => (d.isDirectory() ? wgslFiles(join(dir, d.name)) : d.name.endsWith('.wgsl') ? [join(dir, d.name)] : []));
}

/** Module name (as reflectModule takes it) and its compute entry points, for every module that has one. */
const kernels = wgslFiles(SHADERS).flatMap((file) => {
  const source = readFileSync(file, 'utf8');
  const entries = [...source.matchAll(/@compute\s+@workgroup_size\([^)]*\)\s*fn\s+(\w+)/g)].map((m) => m[1]!);
  return entries.length > 0 ? [{ module: relative(SHADERS, file).replace(/\\/g, '/').replace(/\.wgsl$/, ''), entries }] : [];
});

describe('storage buffers per compute stage', () => {
  it('finds the kernels', () => {
    expect(kernels.map((k) => k.module)).toEqual(expect.arrayContaining(['passes/path-trace-frame', 'restir/restir', 'passes/denoise-atrous']));
  });
  for (const { module, entries } of kernels) {
    it(`${module}: ${entries.join(', ')} bind at most ${BROWSER_STORAGE_BUFFERS_PER_STAGE}`, () => {
      const shader = reflectModule(module);
      for (const entry of entries) {
        const storage = entryPointBindings(shader, [entry], COMPUTE).flat().filter((s) => s.entry.buffer?.type === 'storage' || s.entry.buffer?.type === 'read-only-storage');
        expect(storage.length, `${module}:${entry} binds ${storage.map((s) => s.name).join(', ')}`).toBeLessThanOrEqual(BROWSER_STORAGE_BUFFERS_PER_STAGE);
      }
    });
  }
});
