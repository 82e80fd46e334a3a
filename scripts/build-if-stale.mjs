#!/usr/bin/env node
/**
 * `node scripts/build-if-stale.mjs cli [app]`: builds each named bundle (npm run build:cli, build:app)
 * only when its inputs changed since it was last built here, so that `npm run lantern -- …` starts in
 * a moment instead of rebuilding (about 6 s) on every call. Plain JavaScript: it runs before anything
 * is built, on Node alone.
 *
 * The fingerprint is a SHA-256 over every input file's path and contents (src/ whole, the Vite config,
 * the lock file, tsconfig.json): an edit, a file added or deleted, or a branch switched (whatever the
 * files' times say) changes it. It is written to .stamp-<bundle> after a successful build, with the
 * size and time of the bundle's main output as that build left them; a build from elsewhere (an
 * `npm run build:cli` on another branch), a deleted output or another fingerprint means a rebuild.
 * The fingerprint is taken before the build, so an edit made while it runs is built next time.
 */
import { spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

/** What each bundle is built from, the file its build writes last-known, and the npm script that builds it. */
const BUNDLES = {
  cli: { inputs: ['src', 'vite.cli.config.ts', 'scripts/node-bundle.ts', 'scripts/shader-reflection.ts', 'package-lock.json', 'tsconfig.json'], output: 'dist/cli/lantern.mjs', script: 'build:cli' },
  app: { inputs: ['src', 'index.html', 'vite.config.ts', 'scripts/shader-reflection.ts', 'package-lock.json', 'tsconfig.json'], output: 'dist/app/index.html', script: 'build:app' },
};

/** Every file under `path` (or `path` itself), relative to the root, sorted; a missing input is none. */
function inputFiles(path) {
  if (!existsSync(path)) return [];
  if (!statSync(path).isDirectory()) return [path];
  return readdirSync(path, { recursive: true })
    .map((name) => join(path, name))
    .filter((p) => statSync(p).isFile())
    .sort();
}

function fingerprint(inputs) {
  const hash = createHash('sha256');
  for (const input of inputs) {
    hash.update(`input ${input}\0`);
    for (const file of inputFiles(input)) hash.update(`${file}\0`).update(readFileSync(file)).update('\0');
  }
  return hash.digest('hex');
}

/** The bundle's main output as a build left it: size and modification time, or undefined when there is none. */
function outputState(output) {
  if (!existsSync(output)) return undefined;
  const { size, mtimeMs } = statSync(output);
  return `${size} ${mtimeMs}`;
}

function stampOf(name) {
  try {
    return JSON.parse(readFileSync(`.stamp-${name}`, 'utf8'));
  } catch {
    return undefined;
  }
}

const names = process.argv.slice(2);
const unknown = names.filter((n) => !(n in BUNDLES));
if (names.length === 0 || unknown.length > 0) {
  process.stderr.write(`usage: node scripts/build-if-stale.mjs ${Object.keys(BUNDLES).join('|')} …${unknown.length ? ` (not ${unknown.join(', ')})` : ''}\n`);
  process.exit(2);
}
for (const name of names) {
  const bundle = BUNDLES[name];
  const sources = fingerprint(bundle.inputs);
  const stamp = stampOf(name);
  const output = outputState(bundle.output);
  if (stamp && output && stamp.sources === sources && stamp.output === output) continue;
  const npm = process.env.npm_execpath ? [process.execPath, [process.env.npm_execpath]] : ['npm', []];
  const built = spawnSync(npm[0], [...npm[1], 'run', '-s', bundle.script], { stdio: 'inherit' });
  if (built.status !== 0) process.exit(built.status ?? 1);
  writeFileSync(`.stamp-${name}`, `${JSON.stringify({ sources, output: outputState(bundle.output) })}\n`);
}
