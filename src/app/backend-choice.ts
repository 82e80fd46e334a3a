/**
 * Which backend the page renders with (issue #30): WebGPU where the browser has it and gives an
 * adapter, else WebGL2's fragment path tracer (src/webgl2/), and WebGL2 whatever the browser has when
 * the link says `backend=webgl2`. The reason is kept for the page to say. The WebGPU rungs (core,
 * compatibility mode) are device acquisition's (gpu/device.ts); this is only the last rung.
 */

export type BackendKind = 'webgpu' | 'webgl2';

export interface BackendChoice {
  readonly kind: BackendKind;
  /** Why WebGL2 (undefined for WebGPU). */
  readonly reason?: string;
}

/** The link parameter that forces a backend. */
export const BACKEND_PARAM = 'backend';

/** What WebGPU answers before the choice: navigator.gpu (undefined without WebGPU). */
export interface GpuProbe {
  requestAdapter(): Promise<unknown>;
}

/** The backend for a page with `search` (its location.search) in a browser whose navigator.gpu is `gpu`. */
export async function chooseBackend(search: string, gpu: GpuProbe | undefined): Promise<BackendChoice> {
  if (new URLSearchParams(search).get(BACKEND_PARAM) === 'webgl2') return { kind: 'webgl2', reason: `forced by ${BACKEND_PARAM}=webgl2` };
  if (!gpu) return { kind: 'webgl2', reason: 'WebGPU not available' };
  let adapter: unknown = null;
  try {
    adapter = await gpu.requestAdapter();
  } catch {
    adapter = null;
  }
  if (!adapter) return { kind: 'webgl2', reason: 'WebGPU not available (no adapter)' };
  return { kind: 'webgpu' };
}

/** The page's words for the choice: "WebGL2 (fragment path tracer): WebGPU not available", "WebGPU". */
export function describeBackend(choice: BackendChoice): string {
  return choice.kind === 'webgl2' ? `WebGL2 (fragment path tracer): ${choice.reason ?? 'chosen'}` : 'WebGPU';
}
