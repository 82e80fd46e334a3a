import { describe, expect, it } from 'vitest';
import { chooseBackend, describeBackend } from './backend-choice.ts';

const withAdapter = { requestAdapter: () => Promise.resolve({}) };
const noAdapter = { requestAdapter: () => Promise.resolve(null) };
const failing = { requestAdapter: () => Promise.reject(new Error('GPU process crashed')) };

describe('the backend choice: WebGPU, else WebGL2', () => {
  it('takes WebGPU when it gives an adapter', async () => {
    expect(await chooseBackend('', withAdapter)).toEqual({ kind: 'webgpu' });
    expect(await chooseBackend('?scene=cornell&backend=webgpu', withAdapter)).toEqual({ kind: 'webgpu' });
  });

  it('falls back to WebGL2 without navigator.gpu, without an adapter, or when asking fails', async () => {
    expect(await chooseBackend('', undefined)).toEqual({ kind: 'webgl2', reason: 'WebGPU not available' });
    expect(await chooseBackend('', noAdapter)).toEqual({ kind: 'webgl2', reason: 'WebGPU not available (no adapter)' });
    expect(await chooseBackend('', failing)).toEqual({ kind: 'webgl2', reason: 'WebGPU not available (no adapter)' });
  });

  it('takes WebGL2 when the link forces it, whatever the browser has', async () => {
    expect(await chooseBackend('?backend=webgl2', withAdapter)).toEqual({ kind: 'webgl2', reason: 'forced by backend=webgl2' });
    expect(describeBackend(await chooseBackend('?backend=webgl2', withAdapter))).toBe('WebGL2 (fragment path tracer): forced by backend=webgl2');
    expect(describeBackend(await chooseBackend('', undefined))).toBe('WebGL2 (fragment path tracer): WebGPU not available');
    expect(describeBackend({ kind: 'webgpu' })).toBe('WebGPU');
  });
});
