import { describe, expect, it } from 'vitest';
import { Timeline } from './timeline.ts';

/** A clock the test moves by hand. */
function manualClock() {
  let t = 0;
  return { now: () => t, set: (v: number) => (t = v) };
}

describe('Timeline', () => {
  it('records synchronous and asynchronous steps as spans, by start time, with the total to the last end', async () => {
    const clock = manualClock();
    const timeline = new Timeline(clock.now);
    clock.set(10);
    const value = timeline.timeSync('parse', () => {
      clock.set(25);
      return 7;
    });
    expect(value).toBe(7);
    timeline.add({ stage: 'node start', startMs: 0, endMs: 5 });
    const pending = timeline.time('compile', async () => {
      clock.set(40);
      await Promise.resolve();
      clock.set(90);
      return 'done';
    });
    expect(await pending).toBe('done');
    timeline.end('since 60', 60, 'overlaps compile');
    expect(timeline.spans.map((s) => [s.stage, s.startMs, s.endMs])).toEqual([
      ['node start', 0, 5],
      ['parse', 10, 25],
      ['compile', 25, 90],
      ['since 60', 60, 90],
    ]);
    expect(timeline.totalMs).toBe(90);
    expect(timeline.find('compile')).toMatchObject({ startMs: 25, endMs: 90 });
    expect(timeline.toJSON().spans[3]).toEqual({ stage: 'since 60', startMs: 60, endMs: 90, detail: 'overlaps compile' });
  });

  it('records a step that fails, and passes the failure on', async () => {
    const clock = manualClock();
    const timeline = new Timeline(clock.now);
    await expect(timeline.time('upload', () => Promise.reject(new Error('out of memory')))).rejects.toThrow('out of memory');
    expect(() => timeline.timeSync('read', () => { throw new Error('missing file'); })).toThrow('missing file');
    expect(timeline.spans.map((s) => s.stage)).toEqual(['upload', 'read']);
  });

  it('formats one line per span with start, end and duration', () => {
    const timeline = new Timeline(() => 0);
    timeline.add({ stage: 'bundle', startMs: 0, endMs: 50 });
    timeline.add({ stage: 'device', startMs: 50, endMs: 100, detail: 'adapter X' });
    const lines = timeline.format(10).split('\n');
    expect(lines).toHaveLength(3);
    expect(lines[0]).toContain('100.0 ms in all');
    expect(lines[2]).toMatch(/^device\s+50\.0\s+100\.0\s+50\.0\s+\|\s{5}#{5}\| adapter X$/);
  });
});
