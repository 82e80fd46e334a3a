import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { chunkRenderArgs, jobChunks, parseJob } from './job.ts';

const sampleJob = {
  name: 'cornell-still',
  scene: 'cornell',
  render: { width: 16, height: 12, bounces: 3, seed: 5, torch: 'off' },
  parameterSpace: { taskParameterDefinitions: [{ name: 'Sample', type: 'CHUNK[INT]', range: '0-9', chunks: { defaultTaskCount: 4, rangeConstraint: 'CONTIGUOUS' } }] },
  output: { folder: 'out/cornell', png: 'cornell.png' },
};

describe('farm jobs', () => {
  it('cut a Sample range into contiguous chunks, each one render of its samples into a shard', () => {
    const job = parseJob(sampleJob);
    const chunks = jobChunks(job);
    expect(chunks.map((c) => [c.id, c.values[0], c.values[c.values.length - 1]])).toEqual([['chunk-0000', 0, 3], ['chunk-0001', 4, 7], ['chunk-0002', 8, 9]]);
    expect(chunkRenderArgs(job, chunks[1]!, { shard: 's.shard' })).toEqual(['cornell', '--width', '16', '--height', '12', '--bounces', '3', '--seed', '5', '--torch', 'off', '--samples', '4-7', '--shard', 's.shard']);
  });
  it('give Frame chunks of frames, one a chunk for INT', () => {
    const job = parseJob({ ...sampleJob, render: { temporal: true, spp: 2 }, parameterSpace: { taskParameterDefinitions: [{ name: 'Frame', type: 'INT', range: '1-3,47' }] }, output: { folder: 'f' } });
    expect(job.output.png).toBe('frames');
    const chunks = jobChunks(job);
    expect(chunks.map((c) => c.values)).toEqual([[1], [2], [3], [47]]);
    expect(chunkRenderArgs(job, chunks[3]!, { pngFolder: 'f/frames' })).toEqual(['cornell', '--temporal', '--spp', '2', '--frames', '47-47', '--out', 'f/frames']);
  });
  it('are the same chunks every time (deterministic)', () => {
    expect(JSON.stringify(jobChunks(parseJob(sampleJob)))).toBe(JSON.stringify(jobChunks(parseJob(structuredClone(sampleJob)))));
  });
  it('refuse mistakes in one line naming the field', () => {
    const def = sampleJob.parameterSpace.taskParameterDefinitions[0]!;
    const cases: [unknown, RegExp][] = [
      [[], /JSON object/],
      [{ ...sampleJob, name: 'a b' }, /"name"/],
      [{ ...sampleJob, extra: 1 }, /unknown field 'extra'/],
      [{ ...sampleJob, render: { out: 'x.png' } }, /render.out" is decided by the job/],
      [{ ...sampleJob, render: { spp: 4 } }, /render.spp/],
      [{ ...sampleJob, parameterSpace: { taskParameterDefinitions: [{ ...def, name: 'Tile' }] } }, /"Frame" or "Sample"/],
      [{ ...sampleJob, parameterSpace: { taskParameterDefinitions: [{ ...def, type: 'FLOAT' }] } }, /type must be/],
      [{ ...sampleJob, parameterSpace: { taskParameterDefinitions: [{ ...def, range: '0-3,8' }] } }, /one run of consecutive samples/],
      [{ ...sampleJob, parameterSpace: { taskParameterDefinitions: [{ ...def, chunks: { defaultTaskCount: 0 } }] } }, /defaultTaskCount/],
      [{ ...sampleJob, output: { folder: 'x' } }, /needs "output.png" or "output.exr"/],
      [{ ...sampleJob, output: { folder: 'x', png: '../up.png' } }, /file name inside the folder/],
    ];
    for (const [data, pattern] of cases) expectLanternError(() => parseJob(data), pattern);
  });
});
