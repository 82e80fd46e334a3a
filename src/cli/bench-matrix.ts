/**
 * The benchmark matrix (`lantern bench-matrix`, `npm run bench:matrix`) as data: which runs of
 * `lantern bench` and `lantern render` it makes, the figures it reads from each, how a run is
 * compared with a recorded one (every figure more than 3 % worse is named) and the markdown table
 * docs/perf.md keeps. Pure: commands/bench-matrix.ts runs the processes and samples the clocks.
 * Why a matrix: issue #27 found the progressive kernel 10–25 % slower than docs/perf.md said, lost
 * over several merges that each timed only what they changed.
 */
import { LanternError } from '../errors.ts';

/** Which way a figure improves. */
export type Better = 'higher' | 'lower';

export interface Figure {
  /** Entry id and metric: 'progressive/cornell/samples'. */
  readonly key: string;
  readonly value: number;
  readonly unit: string;
  readonly better: Better;
}

/** What an entry needs beyond the bundle: a Doom IWAD (E1M1) or the Stanford Dragon's PLY. */
export type EntryNeed = 'doom' | 'dragon';

/** The groups, in the order they run: `--only` takes these or entry ids. */
export const MATRIX_GROUPS = ['progressive', 'progressive-random', 'spectral', 'protocol', 'real-time', 'startup'] as const;
export type MatrixGroup = (typeof MATRIX_GROUPS)[number];

export interface MatrixEntry {
  /** 'progressive/cornell': group and scene (or protocol, or start-up case). */
  readonly id: string;
  readonly group: MatrixGroup;
  readonly needs?: EntryNeed;
  /** 'bench': `lantern bench … --json`, figures from its report; 'startup': `lantern render` timed by the wall clock. */
  readonly kind: 'bench' | 'startup';
  /** Arguments after the command name; SCENE_DOOM / SCENE_DRAGON stand for the files found. */
  readonly args: readonly string[];
  /** Start-up entries: how many times the render runs (the first is reported apart: caches cold). */
  readonly runs?: number;
}

export const SCENE_DOOM = '<doom>';
export const SCENE_DRAGON = '<dragon>';

/** Built-in scenes of the progressive rows (prism is cheap and the only dispersive one; furnace the analytic check). */
const PROGRESSIVE_SCENES = ['cornell', 'furnace', 'materials', 'rtiow', 'dungeon', 'prism'] as const;

export interface MatrixSize {
  readonly width: number;
  readonly height: number;
  /** Timed launches (bench --repeats). */
  readonly repeats: number;
}

/** The default matrix: 1080p, as docs/perf.md has measured since issue #2. */
export const DEFAULT_SIZE: MatrixSize = { width: 1920, height: 1080, repeats: 20 };

/** Every entry, in running order, for images of `size` (start-up entries keep their own sizes unless tiny). */
export function matrixEntries(size: MatrixSize = DEFAULT_SIZE): MatrixEntry[] {
  const image = ['-W', String(size.width), '-H', String(size.height), '-r', String(size.repeats)];
  const scenes: { name: string; arg: string; needs?: EntryNeed }[] = [
    ...PROGRESSIVE_SCENES.map((name) => ({ name, arg: name })),
    { name: 'E1M1', arg: SCENE_DOOM, needs: 'doom' },
    { name: 'dragon', arg: SCENE_DRAGON, needs: 'dragon' },
  ];
  const entry = (id: string, group: MatrixGroup, args: string[], needs?: EntryNeed): MatrixEntry => ({ id, group, kind: 'bench', args, ...(needs ? { needs } : {}) });
  const entries: MatrixEntry[] = [];
  for (const s of scenes) entries.push(entry(`progressive/${s.name}`, 'progressive', [s.arg, ...image], s.needs));
  // The analytic furnace says nothing new about the PCG stream: every other scene runs both.
  for (const s of scenes.filter((x) => x.name !== 'furnace')) entries.push(entry(`progressive-random/${s.name}`, 'progressive-random', [s.arg, ...image, '--sampler', 'random'], s.needs));
  entries.push(entry('spectral/prism', 'spectral', ['prism', ...image, '--spectral']));
  // tinybvh's workload is defined at 16:9; a tiny matrix keeps the aspect.
  for (const p of ['tinybvh-closeup', 'tinybvh-framing']) entries.push(entry(`protocol/${p}`, 'protocol', [SCENE_DRAGON, '--protocol', p, ...image], 'dragon'));
  const frames = ['-W', String(size.width), '-H', String(size.height), '-r', String(Math.max(size.repeats, 3) * 3), '--real-time'];
  entries.push(entry('real-time/cornell', 'real-time', ['cornell', ...frames, '--temporal', '--denoise']));
  entries.push(entry('real-time/E1M1', 'real-time', [SCENE_DOOM, ...frames, '--temporal', '--denoise'], 'doom'));
  entries.push(entry('real-time-wavefront/E1M1', 'real-time', [SCENE_DOOM, ...frames, '--temporal', '--denoise', '--integrator', 'wavefront'], 'doom'));
  entries.push(entry('real-time-hybrid/E1M1', 'real-time', [SCENE_DOOM, ...frames, '--mode', 'hybrid'], 'doom'));
  const tiny = size.width < DEFAULT_SIZE.width / 4;
  // The start-up figures: E1M1 at 512² (64 spp) to a PNG, and Ray Tracing in One Weekend's final image.
  const e1m1 = tiny ? ['-W', String(size.width), '-H', String(size.height), '-s', '1'] : ['-W', '512', '-H', '512'];
  const rtiow = tiny ? ['-W', String(size.width), '-H', String(size.height), '-s', '1', '--bounces', '6'] : ['-W', '1200', '-H', '1200', '-s', '500', '--bounces', '6'];
  entries.push({ id: 'startup/E1M1-512', group: 'startup', kind: 'startup', args: [SCENE_DOOM, ...e1m1], needs: 'doom', runs: 3 });
  entries.push({ id: 'startup/rtiow-1200-500spp', group: 'startup', kind: 'startup', args: ['rtiow', ...rtiow], runs: 2 });
  return entries;
}

/** The entries `--only` keeps: a comma-separated list of groups and entry ids (undefined: all). */
export function selectEntries(entries: readonly MatrixEntry[], only: string | undefined): MatrixEntry[] {
  if (only === undefined) return [...entries];
  const wanted = only.split(',').map((s) => s.trim()).filter((s) => s.length > 0);
  for (const w of wanted) {
    if (!(MATRIX_GROUPS as readonly string[]).includes(w) && !entries.some((e) => e.id === w)) {
      throw new LanternError(`--only: no group or entry '${w}'`, `Groups: ${MATRIX_GROUPS.join(', ')}; entries look like ${entries[0]?.id ?? 'progressive/cornell'}`);
    }
  }
  return entries.filter((e) => wanted.includes(e.group) || wanted.includes(e.id));
}

const num = (x: unknown): number | undefined => (typeof x === 'number' && Number.isFinite(x) ? x : undefined);
const obj = (x: unknown): Record<string, unknown> => (x !== null && typeof x === 'object' ? (x as Record<string, unknown>) : {});

/** The figures of one `bench --json` report (progressive, protocol or --real-time), under the entry's id. */
export function benchFigures(id: string, report: unknown): Figure[] {
  const r = obj(report);
  const out: Figure[] = [];
  const add = (metric: string, value: number | undefined, unit: string, better: Better) => {
    if (value !== undefined) out.push({ key: `${id}/${metric}`, value, unit, better });
  };
  const path = obj(r.pathTracing);
  const samples = num(path.samplesPerSecond);
  add('samples', samples === undefined ? undefined : samples / 1e6, 'M samples/s', 'higher');
  add('primary', num(obj(r.primary).mraysPerSecond), 'M rays/s', 'higher');
  // A scene whose primary rays all miss has no diffuse rays: 0 is no figure.
  const diffuse = num(obj(r.diffuse).mraysPerSecond);
  add('diffuse', diffuse === 0 ? undefined : diffuse, 'M rays/s', 'higher');
  add('frame', num(r.frameMs), 'ms', 'lower');
  add('chain', num(r.chainMs), 'ms', 'lower');
  const passes = obj(r.passMs);
  add('path', num(passes['path trace (frame)']) ?? num(passes['path trace (wavefront)']), 'ms', 'lower');
  return out;
}

/** The figures of a start-up entry from its wall-clock seconds per run (the first run, then the best of the others). */
export function startupFigures(id: string, seconds: readonly number[]): Figure[] {
  if (seconds.length === 0) return [];
  const out: Figure[] = [{ key: `${id}/first`, value: seconds[0]!, unit: 's', better: 'lower' }];
  if (seconds.length > 1) out.push({ key: `${id}/warm`, value: Math.min(...seconds.slice(1)), unit: 's', better: 'lower' });
  return out;
}

export interface ClockRange {
  readonly min: number;
  readonly median: number;
  readonly max: number;
}

/** What nvidia-smi read while an entry ran (MHz), or 'unknown' without nvidia-smi. */
export type Clocks = { readonly sm: ClockRange; readonly mem: ClockRange; readonly samples: number } | 'unknown';

export interface EntryResult {
  readonly id: string;
  readonly command: readonly string[];
  readonly seconds: number;
  readonly ok: boolean;
  /** The command's one-line failure (its last stderr line), when it failed. */
  readonly error?: string;
  /** Why it was not run (no Doom IWAD, no Dragon). */
  readonly skipped?: string;
  readonly clocks?: Clocks;
  readonly figures: readonly Figure[];
  /** The bench report as printed (bench entries). */
  readonly report?: unknown;
}

/** The JSON a matrix run writes (docs/perf/matrix-latest.json is one). */
export interface MatrixRun {
  readonly schema: 1;
  readonly date: string;
  readonly commit: string;
  readonly gpu: { readonly adapter: string; readonly info?: unknown; readonly nvidiaSmi?: string };
  readonly clocks: Clocks;
  readonly size: MatrixSize;
  readonly entries: readonly EntryResult[];
}

/** The clock range of a list of MHz samples. */
export function clockRange(samples: readonly number[]): ClockRange {
  const sorted = [...samples].sort((a, b) => a - b);
  return { min: sorted[0] ?? 0, median: sorted[Math.floor((sorted.length - 1) / 2)] ?? 0, max: sorted[sorted.length - 1] ?? 0 };
}

/** nvidia-smi's `--query-gpu=clocks.sm,clocks.mem --format=csv,noheader,nounits` line ("1980, 3201"), or undefined for anything else. */
export function parseClockLine(line: string): { sm: number; mem: number } | undefined {
  const m = /^\s*(\d+(?:\.\d+)?)\s*(?:MHz)?\s*,\s*(\d+(?:\.\d+)?)\s*(?:MHz)?\s*$/.exec(line);
  return m ? { sm: Number(m[1]), mem: Number(m[2]) } : undefined;
}

/** Every figure of a run, by key. */
export function runFigures(run: Pick<MatrixRun, 'entries'>): Map<string, Figure> {
  const map = new Map<string, Figure>();
  for (const e of run.entries) for (const f of e.figures) map.set(f.key, f);
  return map;
}

export interface FigureChange {
  readonly key: string;
  readonly unit: string;
  readonly before: number;
  readonly after: number;
  /** Signed so that positive is worse: (before − after) / before for higher-is-better figures, (after − before) / before for lower. */
  readonly worse: number;
}

export interface Comparison {
  /** Every figure more than the threshold worse, worst first. */
  readonly worse: readonly FigureChange[];
  /** Every figure both runs have, in the new run's order. */
  readonly changes: readonly FigureChange[];
  /** Figures the old run has and the new one lacks (an entry failed or was skipped). */
  readonly missing: readonly string[];
}

/** The threshold beyond which a figure counts as worse: run-to-run spread on the H200 is ≤ 1 %. */
export const WORSE_THRESHOLD = 0.03;

/** Compares a run with an older one, figure by figure. */
export function compareRuns(before: Pick<MatrixRun, 'entries'>, after: Pick<MatrixRun, 'entries'>, threshold = WORSE_THRESHOLD): Comparison {
  const old = runFigures(before), now = runFigures(after);
  const changes: FigureChange[] = [];
  for (const f of now.values()) {
    const o = old.get(f.key);
    if (!o || o.value === 0) continue;
    const worse = f.better === 'higher' ? (o.value - f.value) / o.value : (f.value - o.value) / o.value;
    changes.push({ key: f.key, unit: f.unit, before: o.value, after: f.value, worse });
  }
  return {
    changes,
    worse: changes.filter((c) => c.worse > threshold).sort((a, b) => b.worse - a.worse),
    missing: [...old.keys()].filter((k) => !now.has(k)),
  };
}

/** A figure as docs/perf.md writes them: thousands separated, 1–4 significant decimals by size. */
export function formatFigure(value: number): string {
  const digits = value >= 100 ? 1 : value >= 10 ? 2 : 3;
  return value.toLocaleString('en-US', { minimumFractionDigits: digits, maximumFractionDigits: digits });
}

const percent = (x: number) => `${x > 0 ? '+' : x < 0 ? '−' : '±'}${Math.abs(100 * x).toFixed(1)} %`;

/** One line per figure more than the threshold worse ("progressive/cornell/samples: 1,461.0 → 1,174.0 M samples/s, 19.6 % worse"). */
export function describeWorse(c: Comparison, threshold = WORSE_THRESHOLD): string[] {
  if (c.worse.length === 0) return [`no figure more than ${(100 * threshold).toFixed(0)} % worse`];
  return c.worse.map((w) => `${w.key}: ${formatFigure(w.before)} → ${formatFigure(w.after)} ${w.unit}, ${(100 * w.worse).toFixed(1)} % worse`);
}

/**
 * The run as a markdown table (one row per entry, a column per metric), each cell with its change
 * against `before` where given ("1,174.0 (−19.6 %)": the sign is the figure's, not better/worse;
 * cells more than the threshold worse are bold).
 */
export function markdownTable(run: MatrixRun, before?: Pick<MatrixRun, 'entries'>, threshold = WORSE_THRESHOLD): string {
  const metrics: { metric: string; title: string }[] = [
    { metric: 'samples', title: 'path tracing (M samples/s)' },
    { metric: 'primary', title: 'primary (M rays/s)' },
    { metric: 'diffuse', title: 'diffuse (M rays/s)' },
    { metric: 'frame', title: 'frame (ms)' },
    { metric: 'path', title: 'path trace pass (ms)' },
    { metric: 'chain', title: 'denoising chain (ms)' },
    { metric: 'first', title: 'first run (s)' },
    { metric: 'warm', title: 'warm run (s)' },
  ];
  const changes = before ? new Map(compareRuns(before, run, threshold).changes.map((c) => [c.key, c])) : undefined;
  const used = metrics.filter((m) => run.entries.some((e) => e.figures.some((f) => f.key === `${e.id}/${m.metric}`)));
  const header = `| entry | ${used.map((m) => m.title).join(' | ')} |`;
  const rule = `|---|${used.map(() => '---|').join('')}`;
  const rows = run.entries.map((e) => {
    const cells = used.map((m) => {
      const f = e.figures.find((x) => x.key === `${e.id}/${m.metric}`);
      if (!f) return '';
      const c = changes?.get(f.key);
      if (!c) return formatFigure(f.value);
      const cell = `${formatFigure(f.value)} (${percent((c.after - c.before) / c.before)})`;
      return c.worse > threshold ? `**${cell}**` : cell;
    });
    const note = e.skipped ? ` (skipped: ${e.skipped})` : !e.ok ? ` (failed: ${e.error ?? 'no output'})` : '';
    return `| ${e.id}${note} | ${cells.join(' | ')} |`;
  });
  return [header, rule, ...rows].join('\n');
}

/** "1920x1080" → width and height; a LanternError for anything else. */
export function parseSize(text: string): { width: number; height: number } {
  const m = /^(\d{1,5})x(\d{1,5})$/i.exec(text.trim());
  const width = Number(m?.[1]), height = Number(m?.[2]);
  if (!m || width < 1 || height < 1) throw new LanternError(`--size must be WIDTHxHEIGHT (for example 1920x1080), not '${text}'`);
  return { width, height };
}

/** Reads a recorded run (JSON text) or says in one line what is wrong with it. */
export function parseRun(text: string, name: string): MatrixRun {
  let value: unknown;
  try {
    value = JSON.parse(text);
  } catch (e) {
    throw new LanternError(`${name} is not JSON (${(e as Error).message})`);
  }
  const r = obj(value);
  if (r.schema !== 1 || !Array.isArray(r.entries)) throw new LanternError(`${name} is not a bench-matrix run (no schema 1 and entries)`);
  for (const e of r.entries as unknown[]) {
    const entry = obj(e);
    if (typeof entry.id !== 'string' || !Array.isArray(entry.figures)) throw new LanternError(`${name}: an entry without an id or figures`);
    for (const f of entry.figures as unknown[]) {
      const fig = obj(f);
      if (typeof fig.key !== 'string' || num(fig.value) === undefined || (fig.better !== 'higher' && fig.better !== 'lower')) throw new LanternError(`${name}: entry ${entry.id} has a figure without a key, a finite value and a direction`);
    }
  }
  return value as MatrixRun;
}
