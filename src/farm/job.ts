/**
 * A farm job: one `render` of a scene split into chunks, described in JSON shaped like Open Job
 * Description's parameter spaces, so that it maps onto other farms later:
 *
 *   { "name": "cornell-still", "scene": "cornell",
 *     "render": { "width": 16, "height": 12, "bounces": 3, "seed": 5 },
 *     "parameterSpace": { "taskParameterDefinitions": [
 *       { "name": "Sample", "type": "CHUNK[INT]", "range": "0-63",
 *         "chunks": { "defaultTaskCount": 8, "rangeConstraint": "CONTIGUOUS" } } ] },
 *     "output": { "folder": "out/cornell", "png": "cornell.png", "exr": "cornell.exr" } }
 *
 * A Sample job's output.png / output.exr name the merged image's files in the folder; a Frame job's
 * name subfolders that receive frame-0000.png / .exr, ... (png defaults to "frames").
 *
 * `render` holds `lantern render`'s options by their long names (`true` for a switch). One task
 * parameter: `Sample` (a still's samples, chunks of defaultTaskCount contiguous samples, each
 * rendered as one dispatch into a shard, merged exactly) or `Frame` (frames of a camera path or of
 * the world's clock; `INT`: a frame a chunk, `CHUNK[INT]`: defaultTaskCount frames a chunk).
 * Everything here is pure: the same job gives the same chunks, names and command lines.
 */
import { LanternError } from '../errors.ts';
import { formatIntRange, parseIntRange } from './frames.ts';

export type JobKind = 'samples' | 'frames';

export interface FarmJob {
  readonly name: string;
  readonly scene: string;
  /** `render`'s options by long name (no leading dashes). */
  readonly render: Readonly<Record<string, string | number | boolean>>;
  readonly kind: JobKind;
  /** Frames (kind 'frames') or sample numbers (kind 'samples'; contiguous), sorted. */
  readonly values: readonly number[];
  /** Values a chunk. */
  readonly chunkSize: number;
  readonly output: { readonly folder: string; readonly png?: string; readonly exr?: string };
}

export interface Chunk {
  /** 0, 1, ...: the chunk's place in the job. */
  readonly index: number;
  /** `chunk-0003`: its name in files and queues. */
  readonly id: string;
  /** Frames or sample numbers, sorted (samples contiguous). */
  readonly values: readonly number[];
}

/** Options the job itself decides (where outputs go, which frames or samples): not allowed in `render`. */
const JOB_OWNED = new Set(['out', 'o', 'exr', 'json', 'frames', 'shard', 'samples', 'chunk', 'timings', 'help']);

const fail = (what: string, hint?: string): never => {
  throw new LanternError(`job: ${what}`, hint);
};

function isObject(v: unknown): v is Record<string, unknown> {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

/** Checks a parsed job file; one clear line per mistake. Relative paths stay as written (the CLI resolves them). */
export function parseJob(data: unknown): FarmJob {
  if (!isObject(data)) fail('the file must hold a JSON object');
  const d = data as Record<string, unknown>;
  for (const key of Object.keys(d)) if (!['name', 'scene', 'render', 'parameterSpace', 'output', 'specificationVersion'].includes(key)) fail(`unknown field '${key}'`, 'Fields: name, scene, render, parameterSpace, output');
  const name = d.name;
  if (typeof name !== 'string' || !/^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$/.test(name)) fail('"name" must be 1-64 letters, digits, . _ or - (it names queues and files)');
  if (typeof d.scene !== 'string' || d.scene === '') fail('"scene" must name a scene, as `lantern render` takes it');
  const render = d.render ?? {};
  if (!isObject(render)) fail('"render" must be an object of render options, such as { "width": 64, "bounces": 3 }');
  for (const [key, value] of Object.entries(render as Record<string, unknown>)) {
    if (JOB_OWNED.has(key)) fail(`"render.${key}" is decided by the job (its parameter space and output), leave it out`);
    if (!/^[a-z][a-z0-9-]*$/.test(key)) fail(`"render.${key}" is not a render option's long name (such as "bounces" or "light-sampling")`);
    if (!['string', 'number', 'boolean'].includes(typeof value)) fail(`"render.${key}" must be a string, number or boolean`);
    if (typeof value === 'number' && !Number.isFinite(value)) fail(`"render.${key}" must be a finite number`);
  }
  const space = d.parameterSpace;
  if (!isObject(space) || !Array.isArray((space as Record<string, unknown>).taskParameterDefinitions)) fail('"parameterSpace.taskParameterDefinitions" must be a list', 'One definition: { "name": "Frame" | "Sample", "type": "INT" | "CHUNK[INT]", "range": "0-63" }');
  const defs = (space as { taskParameterDefinitions: unknown[] }).taskParameterDefinitions;
  if (defs.length !== 1) fail(`"parameterSpace" must define exactly one task parameter (Frame or Sample), not ${defs.length}`);
  const def = defs[0];
  if (!isObject(def)) fail('a task parameter definition must be an object');
  const p = def as Record<string, unknown>;
  if (p.name !== 'Frame' && p.name !== 'Sample') fail(`task parameter '${String(p.name)}': Lantern splits by "Frame" or "Sample"`);
  if (p.type !== 'INT' && p.type !== 'CHUNK[INT]') fail(`task parameter ${String(p.name)}: type must be "INT" or "CHUNK[INT]", not ${JSON.stringify(p.type)}`);
  if (typeof p.range !== 'string') fail(`task parameter ${String(p.name)}: "range" must be a string such as "0-63" or "1-30,47"`);
  const values = parseIntRange(p.range as string, `job: ${String(p.name)} range`);
  const kind: JobKind = p.name === 'Frame' ? 'frames' : 'samples';
  let chunkSize = 1;
  if (p.type === 'CHUNK[INT]') {
    const chunks = p.chunks;
    if (!isObject(chunks)) fail(`task parameter ${String(p.name)}: CHUNK[INT] needs "chunks": { "defaultTaskCount": N }`);
    const c = chunks as Record<string, unknown>;
    if (!Number.isInteger(c.defaultTaskCount) || (c.defaultTaskCount as number) < 1 || (c.defaultTaskCount as number) > 1_000_000) fail(`task parameter ${String(p.name)}: "chunks.defaultTaskCount" must be a whole number from 1 to 1000000`);
    chunkSize = c.defaultTaskCount as number;
    if (c.rangeConstraint !== undefined && c.rangeConstraint !== 'CONTIGUOUS' && c.rangeConstraint !== 'NONCONTIGUOUS') fail('"chunks.rangeConstraint" must be "CONTIGUOUS" or "NONCONTIGUOUS"');
    if (kind === 'samples' && c.rangeConstraint === 'NONCONTIGUOUS') fail('Sample chunks are contiguous (a chunk is one dispatch of consecutive samples)');
    for (const key of Object.keys(c)) if (!['defaultTaskCount', 'rangeConstraint', 'targetRuntimeSeconds'].includes(key)) fail(`unknown field "chunks.${key}"`);
  } else if (p.chunks !== undefined) fail(`task parameter ${String(p.name)}: "chunks" applies to type CHUNK[INT] only`);
  for (const key of Object.keys(p)) if (!['name', 'type', 'range', 'chunks'].includes(key)) fail(`unknown field "${key}" in task parameter ${String(p.name)}`);
  if (kind === 'samples') {
    if (values[values.length - 1]! - values[0]! + 1 !== values.length) fail('the Sample range must be one run of consecutive samples, such as 0-4095');
    if ((render as Record<string, unknown>).spp !== undefined) fail('"render.spp" is the Sample range\'s length in a Sample job, leave it out');
  }
  const output = d.output;
  if (!isObject(output)) fail('"output" must be an object: { "folder": "...", "png": "name.png", "exr": "name.exr" }');
  const o = output as Record<string, unknown>;
  for (const key of Object.keys(o)) if (!['folder', 'png', 'exr'].includes(key)) fail(`unknown field "output.${key}"`);
  if (typeof o.folder !== 'string' || o.folder === '') fail('"output.folder" must name the shared folder for the job\'s files');
  for (const key of ['png', 'exr'] as const) {
    if (o[key] === undefined) continue;
    if (typeof o[key] !== 'string' || !/^[A-Za-z0-9][A-Za-z0-9._-]*$/.test(o[key] as string)) fail(`"output.${key}" must be a file name inside the folder (letters, digits, . _ -): a file for a Sample job, a subfolder for a Frame job`);
  }
  if (kind === 'samples' && o.png === undefined && o.exr === undefined) fail('a Sample job needs "output.png" or "output.exr" (the merged image)');
  if (kind === 'frames' && o.png === undefined && o.exr === undefined) o.png = 'frames';
  return {
    name: name as string,
    scene: d.scene as string,
    render: render as Record<string, string | number | boolean>,
    kind,
    values,
    chunkSize,
    output: { folder: o.folder as string, ...(typeof o.png === 'string' ? { png: o.png } : {}), ...(typeof o.exr === 'string' ? { exr: o.exr } : {}) },
  };
}

/** The job's chunks: its values cut into runs of chunkSize, in order. */
export function jobChunks(job: FarmJob): Chunk[] {
  const chunks: Chunk[] = [];
  for (let i = 0; i * job.chunkSize < job.values.length; i++) {
    chunks.push({ index: i, id: `chunk-${String(i).padStart(4, '0')}`, values: job.values.slice(i * job.chunkSize, (i + 1) * job.chunkSize) });
  }
  return chunks;
}

/** `render`'s options of the job as arguments, in the job's order: { bounces: 3, temporal: true } -> ['--bounces', '3', '--temporal']. */
export function renderOptionArgs(job: FarmJob): string[] {
  const args: string[] = [];
  for (const [key, value] of Object.entries(job.render)) {
    if (value === false) continue;
    args.push(`--${key}`);
    if (value !== true) args.push(String(value));
  }
  return args;
}

/**
 * The `render` command line (after `render`) of one chunk: a Sample chunk renders its samples in one
 * dispatch into `shard`; a Frame chunk renders its frames into `frames` (a folder), PNG and/or EXR.
 */
export function chunkRenderArgs(job: FarmJob, chunk: Chunk, files: { shard?: string; pngFolder?: string; exrFolder?: string }): string[] {
  const args = [job.scene, ...renderOptionArgs(job)];
  if (job.kind === 'samples') {
    const first = chunk.values[0]!;
    const last = chunk.values[chunk.values.length - 1]!;
    return [...args, '--samples', `${first}-${last}`, '--shard', files.shard!];
  }
  return [...args, '--frames', formatIntRange(chunk.values), ...(files.pngFolder ? ['--out', files.pngFolder] : []), ...(files.exrFolder ? ['--exr', files.exrFolder] : [])];
}
