/**
 * One SwiftShader device for the test process: the gpu project is not isolated (vitest.config.ts), so
 * every GPU test file shares it, and a pipeline compiled by one file is not compiled again by the next
 * (kernel.ts caches shader modules per device; Dawn returns the pipeline it already made). Tests
 * destroy what they create; resource counts are compared before and after, never as totals.
 * SwiftShader is forced so that results do not depend on the machine running the tests.
 *
 * With LANTERN_PIPELINE_LOG=<file> set, every pipeline the shared device compiles is appended to
 * <file> as one JSON line (test file, test, label, a key for what compiles alike, milliseconds), for
 * finding which files and tests pay for which compiles: `node tests/gpu/pipeline-summary.mjs <file>`.
 * Each compute pipeline's first dispatch is logged as well, and the summary names those compiled
 * and never dispatched.
 */
import { appendFileSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { expect } from 'vitest';
import { acquireNodeGpu } from '../../src/cli/dawn.ts';
import type { GpuContext } from '../../src/gpu/device.ts';

let context: Promise<GpuContext> | undefined;

export function testGpu(): Promise<GpuContext> {
  context ??= acquireNodeGpu({ forceSwiftShader: true }).then((gpu) => {
    const log = process.env.LANTERN_PIPELINE_LOG;
    if (log) logPipelines(gpu.device, log);
    return gpu;
  });
  return context;
}

/** Wraps the device's pipeline and shader-module constructors so that each compile is logged to `file`. */
function logPipelines(device: GPUDevice, file: string): void {
  const codeOf = new WeakMap<GPUShaderModule, string>();
  const createShaderModule = device.createShaderModule.bind(device);
  device.createShaderModule = (descriptor) => {
    const module = createShaderModule(descriptor);
    codeOf.set(module, createHash('sha1').update(descriptor.code).digest('hex').slice(0, 12));
    return module;
  };
  const where = () => {
    const state = expect.getState();
    return { file: (state.testPath ?? '?').replace(/^.*tests\/gpu\//, ''), test: state.currentTestName ?? '(hook)' };
  };
  const stageKey = (stage: GPUProgrammableStage) => {
    const constants = Object.entries(stage.constants ?? {}).map(([k, v]) => `${k}=${v}`).sort().join(',');
    return `${codeOf.get(stage.module) ?? '?'}:${stage.entryPoint ?? ''}${constants ? `[${constants}]` : ''}`;
  };
  const record = (kind: string, label: string | undefined, key: string, t0: number) => {
    appendFileSync(file, `${JSON.stringify({ ...where(), kind, label: label ?? '', key, ms: Math.round(performance.now() - t0) })}\n`);
  };
  // The first dispatch of each compute pipeline is logged too ('used'), so that the summary can name
  // those compiled and never dispatched.
  const keyOf = new WeakMap<GPUComputePipeline, { key: string; label: string; used: boolean }>();
  const createCommandEncoder = device.createCommandEncoder.bind(device);
  device.createCommandEncoder = (descriptor) => {
    const encoder = createCommandEncoder(descriptor);
    const beginComputePass = encoder.beginComputePass.bind(encoder);
    encoder.beginComputePass = (passDescriptor) => {
      const pass = beginComputePass(passDescriptor);
      const setPipeline = pass.setPipeline.bind(pass);
      pass.setPipeline = (pipeline) => {
        const k = keyOf.get(pipeline);
        if (k && !k.used) {
          k.used = true;
          appendFileSync(file, `${JSON.stringify({ ...where(), kind: 'used', label: k.label, key: k.key, ms: 0 })}\n`);
        }
        setPipeline(pipeline);
      };
      return pass;
    };
    return encoder;
  };
  const computeAsync = device.createComputePipelineAsync.bind(device);
  device.createComputePipelineAsync = async (d) => {
    const t0 = performance.now();
    const p = await computeAsync(d);
    record('compute', d.label, stageKey(d.compute), t0);
    keyOf.set(p, { key: stageKey(d.compute), label: d.label ?? '', used: false });
    return p;
  };
  const compute = device.createComputePipeline.bind(device);
  device.createComputePipeline = (d) => {
    const t0 = performance.now();
    const p = compute(d);
    record('compute-sync', d.label, stageKey(d.compute), t0);
    keyOf.set(p, { key: stageKey(d.compute), label: d.label ?? '', used: false });
    return p;
  };
  const renderKey = (d: GPURenderPipelineDescriptor) => `${stageKey(d.vertex)}|${d.fragment ? stageKey(d.fragment) : ''}|${[...(d.fragment?.targets ?? [])].map((t) => t?.format).join(',')}`;
  const renderAsync = device.createRenderPipelineAsync.bind(device);
  device.createRenderPipelineAsync = async (d) => {
    const t0 = performance.now();
    const p = await renderAsync(d);
    record('render', d.label, renderKey(d), t0);
    return p;
  };
  const render = device.createRenderPipeline.bind(device);
  device.createRenderPipeline = (d) => {
    const t0 = performance.now();
    const p = render(d);
    record('render-sync', d.label, renderKey(d), t0);
    return p;
  };
}
