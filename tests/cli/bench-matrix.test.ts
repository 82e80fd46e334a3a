/**
 * `lantern bench-matrix` as a user runs it, on SwiftShader with a one-entry matrix: the JSON it writes
 * (commit, GPU, clocks, figures) and the comparison with a recorded run, which names the figures more
 * than 3 % worse.
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';

let dir: string;
let cli: string;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-matrix-'));
  // Absolute: the runs below start in the temporary folder (no docs/perf/matrix-latest.json there).
  cli = resolve(inject('lanternCli'));
});

afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
});

function lantern(args: string[]) {
  const r = spawnSync(process.execPath, [cli, ...args], {
    encoding: 'utf8',
    cwd: dir,
    env: { ...process.env, VK_ICD_FILENAMES: '/usr/lib/chromium/vk_swiftshader_icd.json' },
    timeout: 300_000,
  });
  return { code: r.status, stdout: r.stdout, stderr: r.stderr.split('\n').filter((l) => l.startsWith('lantern')).join('\n') };
}

describe('lantern bench-matrix', () => {
  it('times its entries in processes of the bundle, writes the run as JSON and names what got worse against a recorded run', () => {
    const out = join(dir, 'run.json');
    const r = lantern(['bench-matrix', '--only', 'progressive/cornell', '--size', '16x16', '-r', '1', '--no-warmup', '--no-compare', '--out', out, '--commit', 'test-commit']);
    expect(r.code, r.stderr).toBe(0);
    const run = JSON.parse(readFileSync(out, 'utf8'));
    expect(run).toMatchObject({ schema: 1, commit: 'test-commit', size: { width: 16, height: 16, repeats: 1 } });
    expect(run.gpu.adapter).toMatch(/swiftshader/i);
    expect(run.gpu.info.vendor).toBeTypeOf('string');
    // No nvidia-smi here: the clocks are unknown, and said to be.
    if (spawnSync('nvidia-smi', ['-L']).status !== 0) expect(run.clocks).toBe('unknown');
    expect(run.entries.map((e: { id: string }) => e.id)).toEqual(['progressive/cornell']);
    const figures = Object.fromEntries(run.entries[0].figures.map((f: { key: string; value: number }) => [f.key, f.value]));
    expect(Object.keys(figures).sort()).toEqual(['progressive/cornell/diffuse', 'progressive/cornell/primary', 'progressive/cornell/samples']);
    for (const v of Object.values(figures)) expect(v).toBeGreaterThan(0);
    expect(r.stdout).toMatch(/\| progressive\/cornell \| [\d,.]+ \| [\d,.]+ \| [\d,.]+ \|/);

    // A recorded run where path tracing was 1.5× faster and primary rays 1 % slower: only path tracing is named.
    const old = structuredClone(run);
    for (const f of old.entries[0].figures) f.value = f.key.endsWith('/samples') ? f.value * 1.5 : f.key.endsWith('/primary') ? f.value / 1.01 : f.value;
    writeFileSync(join(dir, 'old.json'), JSON.stringify(old));
    const c = lantern(['bench-matrix', '--from', out, '--compare', join(dir, 'old.json')]);
    expect(c.code, c.stderr).toBe(0);
    expect(c.stdout).toMatch(/progressive\/cornell\/samples: [\d,.]+ → [\d,.]+ M samples\/s, 33\.3 % worse/);
    expect(c.stdout).not.toMatch(/primary: .* worse/);
    expect(c.stdout).toMatch(/\*\*[\d,.]+ \(−33\.3 %\)\*\*/);
  });

  it('says in one line what is wrong with its input', () => {
    const missing = lantern(['bench-matrix', '--from', join(dir, 'none.json')]);
    expect(missing.code).toBe(1);
    expect(missing.stderr).toMatch(/^lantern: error: cannot read .*none\.json \(ENOENT\)$/);
    writeFileSync(join(dir, 'bad.json'), '{"schema": 2}');
    const bad = lantern(['bench-matrix', '--from', join(dir, 'bad.json'), '--no-compare']);
    expect(bad.stderr).toMatch(/^lantern: error: .*bad\.json is not a bench-matrix run/);
    const only = lantern(['bench-matrix', '--only', 'progressive/nowhere', '--no-compare']);
    expect(only.code).toBe(1);
    expect(only.stderr).toMatch(/--only: no group or entry 'progressive\/nowhere'/);
  });
});
