import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { jobChunks } from '../../farm/job.ts';
import { chunkFiles, chunkOutputs, readJobFile } from './job-file.ts';

const dir = mkdtempSync(join(tmpdir(), 'lantern-job-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

const write = (name: string, data: unknown) => {
  writeFileSync(join(dir, name), JSON.stringify(data));
  return join(dir, name);
};
const space = { taskParameterDefinitions: [{ name: 'Frame', type: 'CHUNK[INT]', range: '0-4', chunks: { defaultTaskCount: 2 } }] };

describe('job files', () => {
  it('resolve paths against the job file and name each chunk\'s outputs', () => {
    writeFileSync(join(dir, 'walk.json'), '{}');
    const job = readJobFile(write('frames.json', { name: 'walk', scene: 'cornell', render: { path: 'walk.json', width: 8 }, parameterSpace: space, output: { folder: 'out', png: 'frames', exr: 'exr' } }));
    expect(job.render.path).toBe(join(dir, 'walk.json'));
    expect(job.output.folder).toBe(join(dir, 'out'));
    const chunks = jobChunks(job);
    expect(chunks.map((c) => c.values)).toEqual([[0, 1], [2, 3], [4]]);
    expect(chunkFiles(job, chunks[0]!)).toEqual({ pngFolder: join(dir, 'out', 'frames'), exrFolder: join(dir, 'out', 'exr') });
    expect(chunkOutputs(job, chunks[2]!)).toEqual([join(dir, 'out', 'frames', 'frame-0004.png'), join(dir, 'out', 'exr', 'frame-0004.exr')]);
  });
  it('check render options with render\'s own parser, in one line', () => {
    expectLanternError(() => readJobFile(write('bad.json', { name: 'b', scene: 'cornell', render: { bounces: 'many' }, parameterSpace: space, output: { folder: 'o' } })), /job: its render options do not parse: .*--bounces/);
    expectLanternError(() => readJobFile(write('bad2.json', { name: 'b', scene: 'cornell', render: { colour: 'red' }, parameterSpace: space, output: { folder: 'o' } })), /unknown option '--colour'/);
    expectLanternError(() => readJobFile(join(dir, 'missing.json')), /missing.json/);
  });
});
