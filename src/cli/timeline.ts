/**
 * A start-up timeline: where one command's time went, from process start to its last output, as
 * spans in performance.now() milliseconds (0 is when Node started the process). Steps that run
 * concurrently (the GPU starting while the scene loads, pipelines compiling side by side) overlap,
 * so the timeline is a list of spans, not a sum. `lantern render --timings` prints it and adds it
 * to --json.
 */
import type { StageSpan } from '../gpu/stage-log.ts';

export type TimelineSpan = StageSpan;

export class Timeline {
  private readonly list: TimelineSpan[] = [];

  constructor(private readonly now: () => number = () => performance.now()) {}

  add(span: TimelineSpan): void {
    this.list.push(span);
  }

  /** A span from `startMs` until now. */
  end(stage: string, startMs: number, detail?: string): void {
    this.add({ stage, startMs, endMs: this.now(), ...(detail ? { detail } : {}) });
  }

  /** Runs a synchronous step and records it. */
  timeSync<T>(stage: string, step: () => T): T {
    const startMs = this.now();
    try {
      return step();
    } finally {
      this.end(stage, startMs);
    }
  }

  /** Awaits an asynchronous step and records it (also when it fails). */
  async time<T>(stage: string, step: () => Promise<T>): Promise<T> {
    const startMs = this.now();
    try {
      return await step();
    } finally {
      this.end(stage, startMs);
    }
  }

  /** The spans by start time (ties: the shorter first). */
  get spans(): readonly TimelineSpan[] {
    return [...this.list].sort((a, b) => a.startMs - b.startMs || a.endMs - b.endMs);
  }

  /** The first span of a stage, if any. */
  find(stage: string): TimelineSpan | undefined {
    return this.list.find((s) => s.stage === stage);
  }

  /** Milliseconds from process start to the end of the last span. */
  get totalMs(): number {
    return this.list.reduce((m, s) => Math.max(m, s.endMs), 0);
  }

  toJSON(): { totalMs: number; spans: TimelineSpan[] } {
    const round = (v: number) => Math.round(v * 100) / 100;
    return { totalMs: round(this.totalMs), spans: this.spans.map((s) => ({ ...s, startMs: round(s.startMs), endMs: round(s.endMs) })) };
  }

  /** A table for a terminal: start, end and duration of each span, and a bar on a time axis. */
  format(width = 40): string {
    const total = this.totalMs || 1;
    const spans = this.spans;
    const name = Math.max(5, ...spans.map((s) => s.stage.length));
    const ms = (v: number) => v.toFixed(1).padStart(8);
    const lines = [`${'stage'.padEnd(name)}    start      end     took  (ms since process start, ${total.toFixed(1)} ms in all)`];
    for (const s of spans) {
      const a = Math.floor((s.startMs / total) * width), b = Math.max(a + 1, Math.ceil((s.endMs / total) * width));
      const bar = ' '.repeat(a) + '#'.repeat(b - a);
      lines.push(`${s.stage.padEnd(name)} ${ms(s.startMs)} ${ms(s.endMs)} ${ms(s.endMs - s.startMs)}  |${bar.padEnd(width)}|${s.detail ? ` ${s.detail}` : ''}`);
    }
    return lines.join('\n');
  }
}
