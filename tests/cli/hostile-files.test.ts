/**
 * Issue 27's hostile inputs through the built `lantern` command: each ends at once with exit 0 or
 * one line naming the problem. The same inputs are tested at the loaders in tests/fuzz/regressions.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { constantExr, wolfWarningFloodFiles } from '../fuzz/crafted.ts';

let dir: string;
let cli: string;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-hostile-'));
  // Built once for the e2e project (tests/e2e/global-setup.ts).
  cli = inject('lanternCli');
});

afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
});

function lantern(args: string[], env: Record<string, string> = {}) {
  const r = spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', env: { ...process.env, VK_ICD_FILENAMES: '/usr/lib/chromium/vk_swiftshader_icd.json', ...env }, timeout: 120_000 });
  const lines = r.stderr.split('\n').filter((l) => l.startsWith('lantern'));
  return { code: r.status, stdout: r.stdout, lines, rawStderr: r.stderr };
}

/** One `lantern: error:` line matching `pattern`, and exit 1. */
function expectOneLineError(r: ReturnType<typeof lantern>, pattern: RegExp): void {
  expect(r.code, r.rawStderr).toBe(1);
  expect(r.lines, r.rawStderr).toHaveLength(1);
  expect(r.lines[0]).toMatch(pattern);
}

describe('device files and pipes are not read', () => {
  it('refuses /dev/zero behind a .ply name, as --env, as --path and as a diff input (each grew the process to gigabytes)', () => {
    const zero = join(dir, 'zero.ply');
    symlinkSync('/dev/zero', zero);
    expectOneLineError(lantern(['info', zero]), /^lantern: error: cannot read '.*zero\.ply' \(\/dev\/zero\): it is a device, not a regular file$/);
    expectOneLineError(lantern(['render', 'cornell', '--env', '/dev/zero', '-W', '8', '-H', '8']), /^lantern: error: --env: cannot read '\/dev\/zero': it is a device/);
    expectOneLineError(lantern(['render', 'cornell', '--path', '/dev/zero', '-W', '8', '-H', '8']), /^lantern: error: --path: cannot read '\/dev\/zero': it is a device/);
    expectOneLineError(lantern(['diff', '/dev/zero', '/dev/zero']), /^lantern: error: cannot read '\/dev\/zero': it is a device/);
    expectOneLineError(lantern(['render', zero, '-W', '8', '-H', '8']), /it is a device, not a regular file$/);
  });

  it('refuses a FIFO without waiting for a writer', () => {
    const fifo = join(dir, 'pipe.mol');
    execFileSync('mkfifo', [fifo]);
    expectOneLineError(lantern(['info', fifo]), /pipe\.mol': it is a pipe, not a regular file$/);
  });

  it('refuses a scene file over the fileBytes limit before reading it, saying how to raise it', () => {
    const big = join(dir, 'big.ply');
    writeFileSync(big, new Uint8Array(3000));
    expectOneLineError(lantern(['info', big, '--limits', 'fileBytes=2k']), /big\.ply: file size in bytes: 3,000 is over the limit fileBytes=2,048\. If the file is what you mean to open, raise it with --limits fileBytes=3k/);
  });
});

describe('warning floods', () => {
  it('a Wolfenstein 3D map whose every tile warns prints a capped list and one closing line per kind (it printed 32,040 lines)', () => {
    const game = join(dir, 'flood');
    mkdirSync(game);
    for (const f of wolfWarningFloodFiles()) writeFileSync(join(game, f.name), f.bytes);
    const r = lantern(['info', `${game}#E1L1`]);
    expect(r.code, r.rawStderr.slice(0, 2000)).toBe(0);
    expect(r.lines.length).toBeLessThan(60);
    expect(r.lines.filter((l) => l.startsWith('lantern: warning: … and '))).toHaveLength(2);
  });
});

describe('images at the imagePixels limit', () => {
  const time = '/usr/bin/time';
  it.skipIf(!existsSync(time))('lantern diff compares two 8192×4096 EXRs, the limit, in well under 2 GB (it passed 2 GB and 60 s)', () => {
    const a = join(dir, 'limit-a.exr'), b = join(dir, 'limit-b.exr');
    writeFileSync(a, constantExr(8192, 4096, 1));
    writeFileSync(b, constantExr(8192, 4096, 1.5));
    // GNU time's %M: the command's peak resident memory in KB, on the last line of stderr.
    const r = spawnSync(time, ['-f', '%M', process.execPath, cli, 'diff', a, b, '--json'], { encoding: 'utf8', timeout: 300_000 });
    expect(r.status, r.stderr).toBe(0);
    const report = JSON.parse(r.stdout);
    expect([report.width, report.height]).toEqual([8192, 4096]);
    expect(report.rmse).toBeCloseTo(0.5, 6);
    const peakKb = Number(r.stderr.trim().split('\n').at(-1));
    expect(peakKb * 1024).toBeLessThan(1.5 * 2 ** 30);
  });
});
