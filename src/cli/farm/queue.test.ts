import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { parseJob } from '../../farm/job.ts';
import { connectionOf, jobKey, progressBar } from './queue.ts';

const job = (seed: number) => parseJob({
  name: 'still',
  scene: 'cornell',
  render: { seed },
  parameterSpace: { taskParameterDefinitions: [{ name: 'Sample', type: 'INT', range: '0-3' }] },
  output: { folder: '/tmp/x', png: 'a.png' },
});

describe('farm queue', () => {
  it('keys a job by its name and content: the same job the same key, another job another', () => {
    expect(jobKey(job(1))).toMatch(/^still-[0-9a-f]{12}$/);
    expect(jobKey(job(1))).toBe(jobKey(job(1)));
    expect(jobKey(job(2))).not.toBe(jobKey(job(1)));
  });
  it('reads Redis URLs, and refuses what is not one in one line', () => {
    expect(connectionOf('redis://127.0.0.1:6399/2')).toMatchObject({ host: '127.0.0.1', port: 6399, db: 2, maxRetriesPerRequest: null });
    expect(connectionOf('rediss://:s%40cret@queue:7000')).toMatchObject({ host: 'queue', port: 7000, password: 's@cret', tls: {} });
    expectLanternError(() => connectionOf('http://queue'), /redis:\/\/ or rediss:\/\//);
    expectLanternError(() => connectionOf('queue:6379'), /redis:\/\/ or rediss:\/\/|must be a URL/);
  });
  it('draws progress bars', () => {
    expect(progressBar(8, 16, 10)).toBe('[#####.....] 8/16');
    expect(progressBar(0, 0, 4)).toBe('[....] 0/0');
  });
});
