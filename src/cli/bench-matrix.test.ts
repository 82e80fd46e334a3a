import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import {
  benchFigures, compareRuns, describeWorse, markdownTable, matrixEntries, parseClockLine, parseRun, selectEntries, startupFigures,
  type EntryResult, type Figure, type MatrixRun,
} from './bench-matrix.ts';

const figure = (key: string, value: number, better: Figure['better'] = 'higher', unit = 'M samples/s'): Figure => ({ key, value, unit, better });
const entry = (id: string, figures: Figure[]): EntryResult => ({ id, command: [], seconds: 1, ok: true, figures });
const run = (entries: EntryResult[]): MatrixRun => ({ schema: 1, date: '2026-12-01T00:00:00Z', commit: 'abc', gpu: { adapter: 'test' }, clocks: 'unknown', size: { width: 1920, height: 1080, repeats: 20 }, entries });

describe('bench-matrix comparison', () => {
  const before = run([
    entry('progressive/cornell', [figure('progressive/cornell/samples', 1461), figure('progressive/cornell/primary', 13000, 'higher', 'M rays/s')]),
    entry('real-time/E1M1', [figure('real-time/E1M1/frame', 10.9, 'lower', 'ms')]),
    entry('startup/E1M1-512', [figure('startup/E1M1-512/warm', 1.1, 'lower', 's')]),
    entry('progressive/dragon', [figure('progressive/dragon/samples', 765)]),
  ]);

  it('names every figure more than 3 % worse, in either direction of better, worst first', () => {
    const after = run([
      // 19.6 % fewer samples per second: worse.
      entry('progressive/cornell', [figure('progressive/cornell/samples', 1174.6), figure('progressive/cornell/primary', 12700, 'higher', 'M rays/s')]),
      // 4 % more milliseconds a frame: worse; the start-up 2.9 % slower: within the threshold.
      entry('real-time/E1M1', [figure('real-time/E1M1/frame', 11.336, 'lower', 'ms')]),
      entry('startup/E1M1-512', [figure('startup/E1M1-512/warm', 1.1319, 'lower', 's')]),
    ]);
    const c = compareRuns(before, after);
    expect(c.worse.map((w) => w.key)).toEqual(['progressive/cornell/samples', 'real-time/E1M1/frame']);
    expect(c.worse[0]!.worse).toBeCloseTo((1461 - 1174.6) / 1461, 12);
    expect(c.worse[1]!.worse).toBeCloseTo(0.04, 12);
    // 12,700 against 13,000 is 2.3 % worse: a change, not named.
    expect(c.changes.find((x) => x.key === 'progressive/cornell/primary')!.worse).toBeCloseTo(300 / 13000, 12);
    expect(c.missing).toEqual(['progressive/dragon/samples']);
    expect(describeWorse(c)).toEqual([
      'progressive/cornell/samples: 1,461.0 → 1,174.6 M samples/s, 19.6 % worse',
      'real-time/E1M1/frame: 10.90 → 11.34 ms, 4.0 % worse',
    ]);
  });

  it('does not name figures that got better, however much', () => {
    const after = run([entry('progressive/cornell', [figure('progressive/cornell/samples', 3000)]), entry('real-time/E1M1', [figure('real-time/E1M1/frame', 1, 'lower', 'ms')])]);
    const c = compareRuns(before, after);
    expect(c.worse).toEqual([]);
    expect(c.changes.map((x) => Math.sign(x.worse))).toEqual([-1, -1]);
    expect(describeWorse(c)).toEqual(['no figure more than 3 % worse']);
  });

  it('marks worse cells in the markdown table and shows each change with its sign', () => {
    const after = run([entry('progressive/cornell', [figure('progressive/cornell/samples', 1174.6)]), entry('real-time/E1M1', [figure('real-time/E1M1/frame', 10.0, 'lower', 'ms')])]);
    const table = markdownTable(after, before).split('\n');
    expect(table[0]).toBe('| entry | path tracing (M samples/s) | frame (ms) |');
    expect(table[2]).toBe('| progressive/cornell | **1,174.6 (−19.6 %)** |  |');
    expect(table[3]).toBe('| real-time/E1M1 |  | 10.00 (−8.3 %) |');
  });
});

describe('bench-matrix figures', () => {
  it('reads the progressive, protocol and real-time reports of bench --json', () => {
    const progressive = { primary: { mraysPerSecond: 6583 }, diffuse: { mraysPerSecond: 2832 }, pathTracing: { samplesPerSecond: 234.5e6 } };
    expect(benchFigures('progressive/E1M1', progressive)).toEqual([
      figure('progressive/E1M1/samples', 234.5),
      figure('progressive/E1M1/primary', 6583, 'higher', 'M rays/s'),
      figure('progressive/E1M1/diffuse', 2832, 'higher', 'M rays/s'),
    ]);
    // --protocol: rays only; a scene whose primary rays all miss has no diffuse figure.
    expect(benchFigures('protocol/x', { primary: { mraysPerSecond: 3961 }, diffuse: { mraysPerSecond: 0 } }).map((f) => f.key)).toEqual(['protocol/x/primary']);
    const frames = { frameMs: 10.9, chainMs: 1.07, passMs: { 'path trace (frame)': 9.1, temporal: 0.1 } };
    expect(benchFigures('real-time/E1M1', frames)).toEqual([
      figure('real-time/E1M1/frame', 10.9, 'lower', 'ms'),
      figure('real-time/E1M1/chain', 1.07, 'lower', 'ms'),
      figure('real-time/E1M1/path', 9.1, 'lower', 'ms'),
    ]);
    expect(benchFigures('x', { pathTracing: { samplesPerSecond: 'fast' } })).toEqual([]);
  });

  it('reports the first start-up run apart and the best of the others as warm', () => {
    expect(startupFigures('startup/a', [4.4, 1.3, 1.2]).map((f) => [f.key, f.value])).toEqual([['startup/a/first', 4.4], ['startup/a/warm', 1.2]]);
    expect(startupFigures('startup/a', [4.4]).map((f) => f.key)).toEqual(['startup/a/first']);
  });

  it("parses nvidia-smi's clock lines and nothing else", () => {
    expect(parseClockLine('1980, 3201')).toEqual({ sm: 1980, mem: 3201 });
    expect(parseClockLine('345 MHz, 3201 MHz')).toEqual({ sm: 345, mem: 3201 });
    expect(parseClockLine('[N/A], [N/A]')).toBeUndefined();
    expect(parseClockLine('')).toBeUndefined();
  });
});

describe('bench-matrix entries', () => {
  it('holds the scenes, both samplers, the protocol, real-time frames and start-up, ids unique', () => {
    const entries = matrixEntries();
    const ids = entries.map((e) => e.id);
    expect(new Set(ids).size).toBe(ids.length);
    for (const id of ['progressive/cornell', 'progressive/E1M1', 'progressive/dragon', 'progressive-random/cornell', 'progressive-random/dragon', 'protocol/tinybvh-closeup', 'real-time/E1M1', 'real-time-wavefront/E1M1', 'startup/E1M1-512', 'startup/rtiow-1200-500spp']) {
      expect(ids).toContain(id);
    }
    expect(entries.find((e) => e.id === 'progressive-random/rtiow')!.args).toContain('random');
    expect(entries.filter((e) => e.needs === 'dragon').every((e) => e.args[0] === '<dragon>')).toBe(true);
  });

  it('selects by group and by id, and names what it does not know', () => {
    const entries = matrixEntries();
    expect(selectEntries(entries, 'protocol,progressive/cornell').map((e) => e.id)).toEqual(['progressive/cornell', 'protocol/tinybvh-closeup', 'protocol/tinybvh-framing']);
    expectLanternError(() => selectEntries(entries, 'progressive/nowhere'), /--only: no group or entry 'progressive\/nowhere'/);
  });

  it('reads recorded runs back and refuses what is not one', () => {
    const r = run([entry('progressive/cornell', [figure('progressive/cornell/samples', 1)])]);
    expect(parseRun(JSON.stringify(r), 'r.json')).toEqual(r);
    expectLanternError(() => parseRun('{', 'r.json'), /r.json is not JSON/);
    expectLanternError(() => parseRun('{"schema":1}', 'r.json'), /not a bench-matrix run/);
    expectLanternError(() => parseRun(JSON.stringify(run([entry('a', [figure('a/x', Number.NaN)])])).replace('null', '"x"'), 'r.json'), /entry a has a figure without/);
  });
});
