/**
 * The farm on one machine (issue #31): a local redis-server started here, three `farm worker`
 * processes on SwiftShader, one killed (with its render child) in the middle of a chunk. The job
 * still completes (the dead worker's chunk goes back to the queue when its lock runs out), and its
 * merged PNG and EXR equal a one-process render of the same samples in dispatches of the chunk
 * size, byte for byte. A second worker on one GPU is refused (the lease in Redis, gpu-lease.ts). A
 * Frame job's chunks rendered one after another in one chunk server equal a one-process render. Also
 * the job file's one-line refusals.
 */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { runLantern, SWIFTSHADER } from './run-lantern.ts';

const redisServer = spawnSync('sh', ['-c', 'command -v redis-server'], { encoding: 'utf8' }).stdout.trim();
if (!redisServer) console.warn('tests/cli/farm.test.ts: redis-server is not installed (apt-get install redis-server; scripts/setup.sh does it): the BullMQ fault test is skipped');

let dir: string;
let redis: ChildProcess | undefined;
let url = '';
const workers: ChildProcess[] = [];

const RENDER = { width: 16, height: 12, bounces: 3, seed: 5 };
const job = (name: string, folder: string) => ({
  name,
  scene: 'cornell',
  render: RENDER,
  parameterSpace: { taskParameterDefinitions: [{ name: 'Sample', type: 'CHUNK[INT]', range: '0-7', chunks: { defaultTaskCount: 2, rangeConstraint: 'CONTIGUOUS' } }] },
  output: { folder, png: 'merged.png', exr: 'merged.exr' },
});

function freePort(): Promise<number> {
  return new Promise((resolve, reject) => {
    const server = createServer();
    server.listen(0, '127.0.0.1', () => {
      const port = (server.address() as { port: number }).port;
      server.close(() => resolve(port));
    });
    server.on('error', reject);
  });
}

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-farm-'));
  // The reference: one process, the same 8 samples in dispatches of the chunk size.
  const ref = runLantern(['render', 'cornell', '--width', '16', '--height', '12', '--bounces', '3', '--seed', '5', '--spp', '8', '--chunk', '2', '--out', join(dir, 'ref.png'), '--exr', join(dir, 'ref.exr')]);
  expect(ref.code, ref.stderr).toBe(0);
});

afterAll(async () => {
  for (const w of workers) {
    try {
      if (w.exitCode === null && w.signalCode === null) process.kill(-w.pid!, 'SIGKILL');
    } catch {
      // Gone already.
    }
  }
  redis?.kill('SIGTERM');
  rmSync(dir, { recursive: true, force: true });
});

describe('lantern farm', () => {
  it('refuses a bad job file in one line', () => {
    writeFileSync(join(dir, 'bad.json'), JSON.stringify({ ...job('bad', 'out'), render: { ...RENDER, bounce: 3 } }));
    const r = runLantern(['farm', 'run', join(dir, 'bad.json'), '--local', '1']);
    expect(r.code).toBe(1);
    expect(r.stderr).toMatch(/lantern: error: job: its render options do not parse: unknown option '--bounce'/);
    writeFileSync(join(dir, 'bad2.json'), JSON.stringify({ ...job('bad', 'out'), render: { spp: 4 } }));
    expect(runLantern(['farm', 'run', join(dir, 'bad2.json'), '--local', '1']).stderr).toMatch(/"render.spp" is the Sample range's length/);
  });

  it.skipIf(!redisServer)('completes a job through BullMQ with a worker killed mid-chunk, merged byte for byte as one process renders it', async () => {
    const port = await freePort();
    url = `redis://127.0.0.1:${port}`;
    redis = spawn(redisServer, ['--port', String(port), '--bind', '127.0.0.1', '--save', '', '--appendonly', 'no'], { stdio: 'ignore' });
    for (let i = 0; i < 50 && spawnSync('redis-cli', ['-p', String(port), 'ping'], { encoding: 'utf8' }).stdout.trim() !== 'PONG'; i++) await new Promise((r) => setTimeout(r, 100));
    const folder = join(dir, 'queued');
    writeFileSync(join(dir, 'job.json'), JSON.stringify(job('fault', folder)));
    const submitted = runLantern(['farm', 'submit', join(dir, 'job.json'), '--redis', url]);
    expect(submitted.code, submitted.stderr).toBe(0);
    expect(submitted.stdout).toMatch(/submitted fault-[0-9a-f]{12}: 4 chunks and a merge/);

    const logs: string[] = ['', '', ''];
    let killed = false;
    const cli = inject('lanternCli');
    for (let k = 0; k < 3; k++) {
      // Its own process group, so that killing it kills its render child too, as a machine going down would.
      // Three workers on one adapter (SwiftShader's CPU) on purpose: --share-gpu.
      const w = spawn(process.execPath, [cli, 'farm', 'worker', '--redis', url, '--name', `w${k}`, '--lock-seconds', '3', '--share-gpu'], { env: { ...process.env, ...SWIFTSHADER }, detached: true, stdio: ['ignore', 'ignore', 'pipe'] });
      w.stderr!.on('data', (d: Buffer) => {
        logs[k] += d.toString();
        // Worker 0 dies a second into its first chunk: after the lock was taken, before the shard.
        if (k === 0 && !killed && /attempt 1/.test(logs[0]!)) {
          killed = true;
          setTimeout(() => process.kill(-w.pid!, 'SIGKILL'), 1000);
        }
      });
      workers.push(w);
    }
    let merged = false;
    for (const until = Date.now() + 240_000; Date.now() < until && !merged; ) {
      await new Promise((r) => setTimeout(r, 1000));
      merged = /merged in/.test(logs.join(''));
    }
    const state = runLantern(['farm', 'status', '--redis', url, '--json'], {});
    expect(merged, `${logs.join('\n')}\n${state.stdout}`).toBe(true);
    expect(killed).toBe(true);
    const status = JSON.parse(state.stdout) as { done: number; chunks: number; merge: string }[];
    expect(status[0]).toMatchObject({ chunks: 4, done: 4, merge: 'completed' });
    // The killed worker's chunk was done by another.
    const killedChunk = /(chunk-\d{4}) \(\d+-\d+\), attempt 1/.exec(logs[0]!)![1]!;
    expect(logs[1]! + logs[2]!).toMatch(new RegExp(`${killedChunk} done in`));
    expect(readFileSync(join(folder, 'merged.png')).equals(readFileSync(join(dir, 'ref.png')))).toBe(true);
    expect(readFileSync(join(folder, 'merged.exr')).equals(readFileSync(join(dir, 'ref.exr')))).toBe(true);

    // One worker a GPU: sharers keep out a worker that would be alone on it, and one alone keeps out the next.
    const alone = runLantern(['farm', 'worker', '--redis', url, '--name', 'w3'], SWIFTSHADER);
    expect(alone.code).toBe(1);
    expect(alone.stderr).toMatch(/^lantern: error: worker w[012] already renders on this GPU \(.*SwiftShader.*\)/m);
    for (const w of workers.slice(1)) process.kill(-w.pid!, 'SIGTERM');
    await Promise.all(workers.slice(1).map((w) => new Promise((r) => (w.exitCode !== null || w.signalCode !== null ? r(undefined) : w.once('exit', r)))));
    const first = spawn(process.execPath, [cli, 'farm', 'worker', '--redis', url, '--name', 'w4'], { env: { ...process.env, ...SWIFTSHADER }, detached: true, stdio: ['ignore', 'ignore', 'pipe'] });
    workers.push(first);
    let firstLog = '';
    first.stderr!.on('data', (d: Buffer) => (firstLog += d.toString()));
    for (const until = Date.now() + 60_000; Date.now() < until && !/waiting for chunks/.test(firstLog); ) await new Promise((r) => setTimeout(r, 200));
    expect(firstLog).toMatch(/w4: adapter .*, GPU known as /);
    const second = runLantern(['farm', 'worker', '--redis', url, '--name', 'w5'], SWIFTSHADER);
    expect(second.code).toBe(1);
    expect(second.stderr).toMatch(/^lantern: error: worker w4 already renders on this GPU/m);
  });

  it('renders a Frame job\'s chunks one after another in one chunk server, each frame the one-process render\'s byte for byte', () => {
    // --temporal: the second chunk renders frames 0-1 again for their history, in the process that rendered them first.
    const folder = join(dir, 'frames');
    writeFileSync(join(dir, 'frames.json'), JSON.stringify({
      name: 'frames',
      scene: 'cornell',
      render: { ...RENDER, temporal: true },
      parameterSpace: { taskParameterDefinitions: [{ name: 'Frame', type: 'CHUNK[INT]', range: '0-3', chunks: { defaultTaskCount: 2, rangeConstraint: 'CONTIGUOUS' } }] },
      output: { folder, png: 'png', exr: 'exr' },
    }));
    const farm = runLantern(['farm', 'run', join(dir, 'frames.json'), '--local', '1']);
    expect(farm.code, farm.stderr).toBe(0);
    expect(farm.stderr).toMatch(/worker 0: chunk-0001 \(2-3\) in/);
    const ref = runLantern(['render', 'cornell', '--width', '16', '--height', '12', '--bounces', '3', '--seed', '5', '--temporal', '--frames', '4', '--out', join(dir, 'fref-png'), '--exr', join(dir, 'fref-exr')]);
    expect(ref.code, ref.stderr).toBe(0);
    for (let f = 0; f < 4; f++) {
      const name = `frame-${String(f).padStart(4, '0')}`;
      expect(readFileSync(join(folder, 'png', `${name}.png`)).equals(readFileSync(join(dir, 'fref-png', `${name}.png`))), name).toBe(true);
      expect(readFileSync(join(folder, 'exr', `${name}.exr`)).equals(readFileSync(join(dir, 'fref-exr', `${name}.exr`))), name).toBe(true);
    }
  });
});
