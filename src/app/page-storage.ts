/**
 * What the page remembers between visits, in localStorage where the browser lets it: whether the
 * controls were shown once, the first frame's wait and the pipeline compile times measured on this
 * adapter (first-frame-estimate.ts: the next visit's estimate). Nothing runs at import.
 */
import type { CompileProgress } from '../gpu/pipeline-compiles.ts';
import { adapterKey, withMeasuredCompiles, type CompileTimesRecord, type FirstFrameRecord } from './first-frame-estimate.ts';
import type { PageState } from './page-state.ts';

/** localStorage keys: whether the controls were shown once; first frames measured per adapter. */
export const HELP_SEEN_KEY = 'lantern.helpSeen';
export const FIRST_FRAME_KEY = 'lantern.firstFrame';
/** Pipeline compile times per adapter (first-frame-estimate.ts CompileTimesRecord): the next visit's estimate of each compile. */
const COMPILE_TIMES_KEY = 'lantern.compileTimes';

/** localStorage, or undefined where the browser refuses it (private modes, file: pages). */
export function storage(): Storage | undefined {
  try {
    return window.localStorage;
  } catch {
    return undefined;
  }
}

/** Keeps a value in localStorage where the browser lets it (a full or refused store only loses the memory). */
export function remember(key: string, value: string): void {
  try {
    storage()?.setItem(key, value);
  } catch {
    // Nothing to do: the page works the same without it.
  }
}

/** The first frame measured on an earlier visit (its adapter, wait and pixels), if the store holds a valid one. */
export function firstFrameRecord(): FirstFrameRecord | undefined {
  try {
    const raw = storage()?.getItem(FIRST_FRAME_KEY);
    const r = raw ? (JSON.parse(raw) as Partial<FirstFrameRecord>) : undefined;
    return r && typeof r.adapter === 'string' && typeof r.ms === 'number' && typeof r.pixels === 'number' ? { adapter: r.adapter, ms: r.ms, pixels: r.pixels } : undefined;
  } catch {
    return undefined;
  }
}

/** The compile times measured on this computer for the page's adapter (none before its facts are known), read from the store once per adapter. */
export function knownCompileTimes(page: PageState): Readonly<Record<string, number>> {
  if (!page.adapterFacts) return {};
  const adapter = adapterKey(page.adapterFacts);
  if (page.compileTimes?.adapter !== adapter) {
    let stored: Partial<CompileTimesRecord> | undefined;
    try {
      stored = JSON.parse(storage()?.getItem(COMPILE_TIMES_KEY) ?? 'null') ?? undefined;
    } catch {
      stored = undefined;
    }
    const ms = stored?.adapter === adapter && stored.ms && typeof stored.ms === 'object' ? Object.fromEntries(Object.entries(stored.ms).filter(([, v]) => typeof v === 'number' && v >= 0)) : {};
    page.compileTimes = { adapter, ms };
  }
  return page.compileTimes.ms;
}

/** Merges the times of the compiles done into the page's record and keeps it for the next visit. */
export function noteCompiles(page: PageState, c: CompileProgress | undefined): void {
  if (!c || !page.adapterFacts) return;
  const known = knownCompileTimes(page);
  const next = withMeasuredCompiles(known, c.compiles);
  if (next === known) return;
  page.compileTimes = { adapter: page.compileTimes!.adapter, ms: next };
  remember(COMPILE_TIMES_KEY, JSON.stringify(page.compileTimes));
}
