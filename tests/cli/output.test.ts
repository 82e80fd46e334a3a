/**
 * The built CLI's output as a pipe sees it: every byte reaches a slow reader before the process
 * leaves, and control characters quoted from file names never reach the terminal raw.
 */
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { squareRoomWad } from '../../src/loaders/doom/test-wad.ts';

let dir: string;
let cli: string;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-output-'));
  cli = resolve(inject('lanternCli'));
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

/**
 * Runs the CLI in `dir` with one of its streams into a real pipe (a shell's `|`: Node's own child
 * pipes are socket pairs, which Node writes to otherwise) read by a slow reader, which sleeps before
 * it reads; the other stream goes to a file.
 */
function slowlyRead(args: string[], piped: 'stdout' | 'stderr'): Promise<{ code: number; stdout: Buffer; stderr: Buffer }> {
  const files = { OUT: join(dir, 'stdout'), ERR: join(dir, 'stderr'), CODE: join(dir, 'code') };
  // The arguments reach the command as "$@", never through the shell's parser.
  const script =
    piped === 'stdout'
      ? '"$@" 2> "$ERR" | (sleep 1; cat > "$OUT"); echo "${PIPESTATUS[0]}" > "$CODE"'
      : '"$@" 2>&1 > "$OUT" | (sleep 1; cat > "$ERR"); echo "${PIPESTATUS[0]}" > "$CODE"';
  return new Promise((resolve, reject) => {
    const child = spawn('bash', ['-c', script, 'bash', process.execPath, cli, ...args], { cwd: dir, stdio: 'ignore', env: { ...process.env, ...files } });
    child.on('error', reject);
    child.on('close', () => resolve({ code: Number(readFileSync(files.CODE, 'utf8')), stdout: readFileSync(files.OUT), stderr: readFileSync(files.ERR) }));
  });
}

describe('lantern output through a pipe', () => {
  it('gives a slow reader all of a long --json report, then exits 0', async () => {
    // The same WAD named 400 times with a long name: the listing's "wads" makes the report far larger
    // than a pipe's 64 KiB buffer, which is what a process.exit() after writing cut short.
    const name = `${'w'.repeat(200)}.wad`;
    writeFileSync(join(dir, name), squareRoomWad());
    const r = await slowlyRead(['info', Array(400).fill(name).join('+'), '--json'], 'stdout');
    expect(r.code, r.stderr.toString()).toBe(0);
    expect(r.stdout.length).toBeGreaterThan(80_000);
    const report = JSON.parse(r.stdout.toString());
    expect(report.wads).toHaveLength(400);
  });

  it('escapes control characters of a quoted path in a one-line error, and a long one arrives whole', async () => {
    // A name that would set the terminal's title, clear the screen and return the cursor, in a path
    // longer than a pipe holds (and than the system takes).
    const long = Array(400).fill('x'.repeat(200)).join('/');
    const hostile = `\u001B]0;owned\u0007\u001B[2J\r${long}\u009B.ply`;
    const r = await slowlyRead(['info', hostile], 'stderr');
    expect(r.code).toBe(1);
    const stderr = r.stderr.toString();
    // Asserted piecewise: a failure message of 80 kB would bury the point.
    expect(stderr.startsWith("lantern: error: cannot read '\\u001B]0;owned\\u0007\\u001B[2J\\u000Dxxx"), stderr.slice(0, 200)).toBe(true);
    expect(stderr.endsWith("xxx\\u009B.ply': the path is too long\n"), stderr.slice(-200)).toBe(true);
    expect(stderr.includes(long)).toBe(true);
    expect(stderr.split('\n')).toHaveLength(2);
    expect(/[\u0000-\u0009\u000B-\u001F\u007F-\u009F]/.test(stderr)).toBe(false);
  });
});
