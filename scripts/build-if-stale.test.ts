/**
 * scripts/build-if-stale.mjs in a scratch project whose `build:cli` only counts its runs: a bundle is
 * built when, and only when, its inputs' contents or its output changed since the last build.
 */
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, utimesSync, writeFileSync, existsSync, unlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';

const SCRIPT = join(import.meta.dirname, 'build-if-stale.mjs');
let root: string;

/** The scratch project's build: writes the bundle and counts itself in builds.log; fails while FAIL exists. */
const BUILD = `
import { appendFileSync, existsSync, mkdirSync, writeFileSync } from 'node:fs';
if (existsSync('FAIL')) process.exit(3);
mkdirSync('dist/cli', { recursive: true });
writeFileSync('dist/cli/lantern.mjs', 'built ' + Date.now());
appendFileSync('builds.log', 'x');
`;

beforeAll(() => {
  root = mkdtempSync(join(tmpdir(), 'lantern-stale-'));
  mkdirSync(join(root, 'src/sub'), { recursive: true });
  writeFileSync(join(root, 'package.json'), JSON.stringify({ name: 'scratch', private: true, type: 'module', scripts: { 'build:cli': 'node build.mjs' } }));
  writeFileSync(join(root, 'build.mjs'), BUILD);
  for (const [path, text] of [['src/a.ts', 'export const a = 1;'], ['src/sub/b.wgsl', 'fn b() {}'], ['vite.cli.config.ts', 'export default {};'], ['package-lock.json', '{}'], ['tsconfig.json', '{}']]) writeFileSync(join(root, path!), text!);
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

const file = (path: string) => join(root, path);
const builds = () => (existsSync(file('builds.log')) ? readFileSync(file('builds.log'), 'utf8').length : 0);

/** Runs the script in the scratch project; returns the builds it made and its exit code. */
function run(): { built: number; code: number | null } {
  const before = builds();
  const env = { ...process.env };
  delete env.npm_execpath;
  const r = spawnSync(process.execPath, [SCRIPT, 'cli'], { cwd: root, env, encoding: 'utf8' });
  return { built: builds() - before, code: r.status };
}

describe('build-if-stale', () => {
  // Each run starts npm: seconds apiece on a busy machine.
  it('builds once, then only when an input or the output changed', { timeout: 180_000 }, () => {
    expect(run()).toEqual({ built: 1, code: 0 });
    expect(run()).toEqual({ built: 0, code: 0 });

    writeFileSync(file('src/a.ts'), 'export const a = 2;');
    expect(run().built).toBe(1);
    expect(run().built).toBe(0);
    // A new file, then its deletion.
    writeFileSync(file('src/sub/c.ts'), 'export const c = 3;');
    expect(run().built).toBe(1);
    unlinkSync(file('src/sub/c.ts'));
    expect(run().built).toBe(1);
    // A branch switched back: the old contents with an old time are still a change.
    writeFileSync(file('src/a.ts'), 'export const a = 1;');
    utimesSync(file('src/a.ts'), new Date(2000, 0, 1), new Date(2000, 0, 1));
    expect(run().built).toBe(1);
    // A new time on the same contents is not.
    utimesSync(file('src/sub/b.wgsl'), new Date(), new Date());
    expect(run().built).toBe(0);
    writeFileSync(file('package-lock.json'), '{"lockfileVersion": 3}');
    expect(run().built).toBe(1);
    writeFileSync(file('vite.cli.config.ts'), 'export default { build: {} };');
    expect(run().built).toBe(1);
  });

  it('rebuilds an output that another build replaced or that was deleted', () => {
    run();
    writeFileSync(file('dist/cli/lantern.mjs'), 'built from another branch');
    expect(run().built).toBe(1);
    unlinkSync(file('dist/cli/lantern.mjs'));
    expect(run().built).toBe(1);
    expect(run().built).toBe(0);
  });

  it('a failed build fails the command and is tried again next time', () => {
    writeFileSync(file('src/a.ts'), 'export const a = 4;');
    writeFileSync(file('FAIL'), '');
    expect(run()).toEqual({ built: 0, code: 3 });
    unlinkSync(file('FAIL'));
    expect(run()).toEqual({ built: 1, code: 0 });
  });

  it('is what `npm run lantern` and `npm run view` start with', () => {
    const { scripts } = JSON.parse(readFileSync(join(import.meta.dirname, '../package.json'), 'utf8')) as { scripts: Record<string, string> };
    expect(scripts.lantern).toBe('node scripts/build-if-stale.mjs cli && node dist/cli/lantern.mjs');
    expect(scripts.view).toBe('node scripts/build-if-stale.mjs app cli && node dist/cli/lantern.mjs view');
  });
});
