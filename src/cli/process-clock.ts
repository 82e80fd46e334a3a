/**
 * The first module of the CLI bundle to run (main.ts imports it before anything else): when the
 * bundle began to execute, in performance.now() milliseconds, which Node counts from the moment the
 * process started (performance.timeOrigin). Before that: Node's own start and parsing the bundle.
 */
import type { StageSpan } from '../gpu/stage-log.ts';

export const BUNDLE_START_MS = performance.now();

let evaluatedMs: number | undefined;

/** main.ts calls this first thing in its body: every module of the bundle has run by then. */
export function bundleEvaluated(): void {
  evaluatedMs ??= performance.now();
}

/** Node's start (to the first module of the bundle) and the bundle's own top-level code, as spans. */
export function processSpans(): StageSpan[] {
  return [
    { stage: 'node start + bundle parse', startMs: 0, endMs: BUNDLE_START_MS },
    { stage: 'bundle evaluated', startMs: BUNDLE_START_MS, endMs: evaluatedMs ?? BUNDLE_START_MS },
  ];
}
