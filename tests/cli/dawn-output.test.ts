/**
 * Dawn's own lines (the Vulkan loader's "Found no drivers!" on a machine without a GPU) stay out of
 * the built CLI's output, where they read like a failure before Lantern's own note; --verbose shows them.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runLantern } from './run-lantern.ts';

let dir: string;

beforeAll(() => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-dawn-output-'));
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

/** Lines of stderr that are not Lantern's own ("lantern: ..."). */
const foreignLines = (stderr: string) => stderr.split('\n').filter((l) => l !== '' && !l.startsWith('lantern: '));

describe("Dawn's own output", () => {
  it('stays out of a render on the machine as it is (no driver chosen), and --verbose shows it', () => {
    const asItIs = { VK_ICD_FILENAMES: undefined, VK_DRIVER_FILES: undefined };
    const args = ['render', 'cornell', '-W', '8', '-H', '8', '--spp', '1', '--out', join(dir, 'c.png')];
    const quiet = runLantern(args, asItIs);
    expect(quiet.code, quiet.stderr).toBe(0);
    expect(foreignLines(quiet.stderr)).toEqual([]);
    // A machine with a GPU: Dawn found it without a word, and there is nothing to show.
    if (!/SwiftShader/.test(quiet.stderr)) return;
    expect(quiet.stderr).toMatch(/^lantern: no GPU adapter found; rendering on the CPU with SwiftShader \(slow\)$/m);
    const verbose = runLantern(['--verbose', ...args], asItIs);
    expect(verbose.code, verbose.stderr).toBe(0);
    expect(verbose.stderr).toMatch(/vkCreateInstance/);
    expect(verbose.stderr).toMatch(/^lantern: no GPU adapter found; rendering on the CPU with SwiftShader \(slow\)$/m);
  });
});

