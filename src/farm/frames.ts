/**
 * Frame lists and sample ranges as Open Job Description writes integer ranges: `0-29`, `1-30,47`,
 * `0-238:2` (a step). Frames are numbered from 0, as `render`'s files are (frame-0000.png). A plain
 * number alone (`--frames 30`) is a count, frames 0 to 29: the option's older meaning, kept.
 */
import { LanternError } from '../errors.ts';

/** The largest frame or sample number a range may name. */
export const MAX_RANGE_VALUE = 1e9;

const PART = /^(\d+)(?:-(\d+)(?::(\d+))?)?$/;

/** `1-30,47` -> [1, ..., 30, 47]: sorted, each once. `what` names the option in errors. */
export function parseIntRange(text: string, what: string): number[] {
  const trimmed = text.trim();
  if (trimmed === '') throw new LanternError(`${what} is empty`, 'Give a range such as 0-29 or a list such as 1-30,47');
  const values = new Set<number>();
  for (const part of trimmed.split(',')) {
    const m = PART.exec(part.trim());
    if (!m) throw new LanternError(`${what}: '${part.trim()}' is not a number or a range a-b (a-b:step)`, 'Write frames as 0-29, 1-30,47 or 0-238:2');
    const a = Number(m[1]);
    const b = m[2] !== undefined ? Number(m[2]) : a;
    const step = m[3] !== undefined ? Number(m[3]) : 1;
    if (b < a) throw new LanternError(`${what}: range ${part.trim()} ends before it starts`);
    if (b > MAX_RANGE_VALUE) throw new LanternError(`${what}: ${b} is beyond ${MAX_RANGE_VALUE}`);
    if (step < 1) throw new LanternError(`${what}: the step of ${part.trim()} must be at least 1`);
    if ((b - a) / step + values.size > 1_000_000) throw new LanternError(`${what} names more than 1,000,000 values`);
    for (let v = a; v <= b; v += step) values.add(v);
  }
  return [...values].sort((x, y) => x - y);
}

/**
 * `--frames`: a count (`30`: frames 0-29, the option's first meaning) or a list of frames
 * (`0-29`, `1-30,47`, `5-5` for frame 5 alone).
 */
export function parseFrames(text: string): number[] {
  const t = text.trim();
  if (/^\d+$/.test(t)) {
    const n = Number(t);
    if (n < 1 || n > 100_000) throw new LanternError(`--frames ${t}: a count of frames must be 1 to 100000`, 'Or give frames as a range: 0-29, 1-30,47');
    return Array.from({ length: n }, (_, i) => i);
  }
  return parseIntRange(t, '--frames');
}

/** `a-b`: samples a to b of the one sequence, both included, as the half-open [a, b + 1). */
export function parseSampleRange(text: string, what: string): { start: number; end: number } {
  const m = /^(\d+)-(\d+)$/.exec(text.trim());
  if (!m) throw new LanternError(`${what} must be a range first-last of sample numbers, such as 0-63, not '${text}'`);
  const start = Number(m[1]);
  const last = Number(m[2]);
  if (last < start) throw new LanternError(`${what}: range ${text} ends before it starts`);
  if (last >= MAX_RANGE_VALUE) throw new LanternError(`${what}: ${last} is beyond ${MAX_RANGE_VALUE - 1}`);
  return { start, end: last + 1 };
}

/** A sorted list back in the short form: [0,1,2,3,7] -> '0-3,7'. */
export function formatIntRange(values: readonly number[]): string {
  const parts: string[] = [];
  for (let i = 0; i < values.length; ) {
    let j = i;
    while (j + 1 < values.length && values[j + 1] === values[j]! + 1) j++;
    parts.push(i === j ? `${values[i]}-${values[i]}` : `${values[i]}-${values[j]}`);
    i = j + 1;
  }
  return parts.join(',');
}
