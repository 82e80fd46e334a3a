import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { decodeExrRgb } from '../image/exr.ts';
import { checkOutputPath, encodeExrNative, nativeExrDeflate, outputPathProblem, writeFile } from './output-files.ts';
import { encodeExr } from '../image/exr.ts';

const dir = mkdtempSync(join(tmpdir(), 'lantern-output-files-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('output paths, checked before the work', () => {
  it('accepts new files and folders below a writable folder, and existing ones of the right kind', () => {
    writeFileSync(join(dir, 'old.png'), 'x');
    mkdirSync(join(dir, 'frames'));
    expect(outputPathProblem(join(dir, 'new.png'), 'file')).toBeUndefined();
    expect(outputPathProblem(join(dir, 'a', 'b', 'new.png'), 'file')).toBeUndefined();
    expect(outputPathProblem(join(dir, 'old.png'), 'file')).toBeUndefined();
    expect(outputPathProblem(join(dir, 'frames'), 'folder')).toBeUndefined();
    expect(outputPathProblem(join(dir, 'x', 'y'), 'folder')).toBeUndefined();
  });

  it('refuses a folder for a file, a file for a folder, a path through a file, and an empty name', () => {
    expect(outputPathProblem(dir, 'file')).toBe('it is a folder');
    expect(outputPathProblem(join(dir, 'old.png'), 'folder')).toBe('it is a file, not a folder');
    expect(outputPathProblem(join(dir, 'old.png', 'inside.png'), 'file')).toBe(`${join(dir, 'old.png')} is a file, not a folder`);
    expect(outputPathProblem('', 'file')).toBe('the name is empty');
    expectLanternError(() => checkOutputPath('--exr', dir, 'file'), /^--exr: cannot write '.*': it is a folder$/);
  });

  it("refuses the kernel's folders at once (a recursive mkdir under /proc never returns)", () => {
    for (const path of ['/proc/lantern/out.png', '/proc/self/x.png', '/sys/x.png', '/dev/lantern/x.png']) {
      expect(outputPathProblem(path, 'file'), path).toMatch(/is a system folder/);
    }
    expect(outputPathProblem('/proc/lantern-textures', 'folder')).toMatch(/^\/proc is a system folder/);
    expectLanternError(() => writeFile('/proc/lantern/deeper/x.png', new Uint8Array(1)), /cannot write '\/proc\/lantern\/deeper\/x.png': \/proc is a system folder/);
  });
});

describe('EXR through Node\'s zlib', () => {
  // 3840 wide: a 4K image's rows, 5 chunks of 16 lines and one of 4.
  const [width, height] = [3840, 84];
  const rgb = new Float32Array(width * height * 3);
  let seed = 7;
  for (let i = 0; i < rgb.length; i++) {
    seed = (seed * 1664525 + 1013904223) >>> 0;
    // Smooth in the upper rows (compressible), noise below (stored raw where zlib cannot shrink it).
    rgb[i] = i < rgb.length / 2 ? 0.25 + 0.1 * Math.sin(i / 5000) : seed / 2 ** 32;
  }

  it('decodes to the same floats as the portable encoder\'s file, from the thread pool and the threads\' sync deflate alike', async () => {
    const pooled = await encodeExrNative(width, height, rgb);
    const sync = encodeExr(width, height, rgb, {}, nativeExrDeflate);
    expect(Buffer.from(pooled).equals(Buffer.from(sync))).toBe(true);
    const expected = decodeExrRgb(encodeExr(width, height, rgb)).rgb;
    expect(Buffer.from(decodeExrRgb(pooled).rgb.buffer).equals(Buffer.from(expected.buffer))).toBe(true);
  });
});
