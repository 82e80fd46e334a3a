/**
 * Where a device's set-up time goes: code that compiles pipelines or uploads a scene reports each
 * step here, and a start-up timeline (the CLI's `render --timings`, the page's first-frame figure)
 * listens. Times are performance.now() milliseconds. Without a listener, reporting costs a lookup.
 */

/** One timed step: a pipeline compiled, a shader module, a scene upload. */
export interface StageSpan {
  readonly stage: string;
  readonly startMs: number;
  readonly endMs: number;
  /** e.g. the override constants a pipeline variant was compiled with. */
  readonly detail?: string;
}

export type StageListener = (span: StageSpan) => void;

const listeners = new WeakMap<GPUDevice, StageListener>();

/** Tells `listener` of every step reported for `device` from now on (undefined stops). */
export function observeStages(device: GPUDevice, listener: StageListener | undefined): void {
  if (listener) listeners.set(device, listener);
  else listeners.delete(device);
}

export function reportStage(device: GPUDevice, span: StageSpan): void {
  listeners.get(device)?.(span);
}

/** Runs `step` and reports how long it took (also when it fails). */
export async function timedStage<T>(device: GPUDevice, stage: string, step: () => Promise<T>, detail?: string): Promise<T> {
  if (!listeners.has(device)) return step();
  const startMs = performance.now();
  try {
    return await step();
  } finally {
    reportStage(device, { stage, startMs, endMs: performance.now(), ...(detail ? { detail } : {}) });
  }
}
