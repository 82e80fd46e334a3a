/**
 * The Vite plugin that reflects the WGSL at build time (issue #29): in a bundle,
 * src/gpu/wgsl/precomputed.ts becomes the reflection of every module of src/shaders, made by
 * src/gpu/wgsl/precompute.ts with the reflection code the bundle itself carries, so that a CLI run
 * or a page load reads layouts and bindings instead of parsing WGSL (the path tracer's parses took
 * 1–3 s of a core in every CLI run). Builds only (`apply: 'build'`): the dev server and Vitest load
 * the file as written, undefined, and reflect live. Used by vite.config.ts (the page and its
 * workers) and vite.cli.config.ts.
 *
 * Reflecting every module takes ~8 s, so the result is kept by a fingerprint of everything it is
 * made from (the shaders, src/gpu/wgsl, this file, the two reflectors' versions): in this process
 * (a page and its worker, or the e2e setup's page and CLI builds), and in
 * node_modules/.cache/lantern/shader-reflection.json for the next build whose shaders did not change.
 */
import { createHash } from 'node:crypto';
import { mkdirSync, readdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { runnerImport, type Plugin } from 'vite';
import type { PrecomputeResult } from '../src/gpu/wgsl/precompute.ts';

const TARGET = 'src/gpu/wgsl/precomputed.ts';
const PRECOMPUTE = 'src/gpu/wgsl/precompute.ts';
const SHADERS = 'src/shaders';
/** What the reflection is made from: folders (their .wgsl and non-test .ts files), files, and packages (their versions). */
const INPUT_FOLDERS = [SHADERS, 'src/gpu/wgsl'];
const INPUT_FILES = ['scripts/shader-reflection.ts'];
const INPUT_PACKAGES = ['webgpu-utils', 'wgsl_reflect'];
const CACHE_FILE = 'node_modules/.cache/lantern/shader-reflection.json';

interface Made {
  /** The module that stands in for precomputed.ts. */
  readonly code: string;
  /** What the data leaves out (PrecomputeResult.skipped). */
  readonly skipped: readonly string[];
}

/**
 * Reflections made in this process, by fingerprint. On globalThis because each Vite config bundles
 * its own copy of this file.
 */
const made: Map<string, Promise<Made>> = ((globalThis as { [key: symbol]: unknown })[Symbol.for('lantern:shader-reflection')] ??= new Map()) as never;

export function inputsFingerprint(root: string): string {
  const hash = createHash('sha256');
  const add = (name: string, contents: string | Buffer) => hash.update(`${name}\0`).update(contents).update('\0');
  for (const folder of INPUT_FOLDERS) {
    for (const file of readdirSync(resolve(root, folder), { recursive: true, encoding: 'utf8' }).sort()) {
      if (file.endsWith('.wgsl') || (file.endsWith('.ts') && !file.endsWith('.test.ts'))) add(`${folder}/${file}`, readFileSync(resolve(root, folder, file)));
    }
  }
  for (const file of INPUT_FILES) add(file, readFileSync(resolve(root, file)));
  for (const name of INPUT_PACKAGES) add(name, String((JSON.parse(readFileSync(resolve(root, 'node_modules', name, 'package.json'), 'utf8')) as { version: string }).version));
  return hash.digest('hex');
}

/** The reflection as the module text that stands in for precomputed.ts, made now. */
export async function reflectShaders(root: string): Promise<Made> {
  // The module runner transforms precompute.ts and its imports as Vite does (TypeScript,
  // shaders/index.ts's import.meta.glob), without this config's plugins: the precomputed.ts that
  // reflect.ts imports there is the source's, undefined, so precompute.ts reflects live.
  const { module } = await runnerImport<{ precomputeReflection: () => PrecomputeResult }>(resolve(root, PRECOMPUTE), { root, configFile: false, logLevel: 'error' });
  const { data, skipped } = module.precomputeReflection();
  // JSON text in a string literal: JSON.parse reads it faster than the engine parses an object literal of the same size.
  return { code: `export const PRECOMPUTED_REFLECTION = ${JSON.stringify(JSON.stringify(data))};\n`, skipped };
}

function readCache(root: string, fingerprint: string): Made | undefined {
  try {
    const cached = JSON.parse(readFileSync(resolve(root, CACHE_FILE), 'utf8')) as Made & { fingerprint: string };
    return cached.fingerprint === fingerprint ? { code: cached.code, skipped: cached.skipped } : undefined;
  } catch {
    return undefined;
  }
}

function writeCache(root: string, fingerprint: string, result: Made): void {
  const file = resolve(root, CACHE_FILE);
  try {
    mkdirSync(dirname(file), { recursive: true });
    // Renamed into place: a build reading it at the same time sees the old file or the new one.
    const temporary = `${file}.${process.pid}`;
    writeFileSync(temporary, JSON.stringify({ fingerprint, ...result }));
    renameSync(temporary, file);
  } catch {
    // Only the next build's time depends on it.
  }
}

/** The stand-in for precomputed.ts: from this process, the cache file or made now. */
export function precomputedModule(root: string): Promise<Made> {
  const fingerprint = inputsFingerprint(root);
  const key = `${root}\0${fingerprint}`;
  let result = made.get(key);
  if (!result) {
    const cached = readCache(root, fingerprint);
    result = cached
      ? Promise.resolve(cached)
      : reflectShaders(root).then((r) => {
          writeCache(root, fingerprint, r);
          return r;
        });
    made.set(key, result);
    result.catch(() => made.delete(key));
  }
  return result;
}

export function shaderReflection(): Plugin {
  let root = process.cwd();
  return {
    name: 'lantern:shader-reflection',
    apply: 'build',
    configResolved(config) {
      root = config.root;
    },
    async load(id) {
      if (id.split('?')[0] !== resolve(root, TARGET)) return null;
      // A watching build reflects again when a shader changes.
      for (const file of readdirSync(resolve(root, SHADERS), { recursive: true, encoding: 'utf8' })) {
        if (file.endsWith('.wgsl')) this.addWatchFile(join(root, SHADERS, file));
      }
      const { code, skipped } = await precomputedModule(root);
      for (const s of skipped) this.info(`reflected at run time, not in the bundle: ${s}`);
      return code;
    },
  };
}
