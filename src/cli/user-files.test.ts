import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { withLimits } from '../budgets.ts';
import { expectLanternError } from '../expect-lantern-error.ts';
import { checkUserFile, isMissing, readJsonFile, readUserFile } from './user-files.ts';

const dir = mkdtempSync(join(tmpdir(), 'lantern-user-files-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('reading a user file', () => {
  const file = join(dir, 'mesh.ply');
  writeFileSync(file, 'ply\n');
  symlinkSync(file, join(dir, 'link.ply'));
  symlinkSync('/dev/zero', join(dir, 'zero.ply'));
  symlinkSync(join(dir, 'nowhere'), join(dir, 'dangling.ply'));
  mkdirSync(join(dir, 'folder.ply'));
  execFileSync('mkfifo', [join(dir, 'pipe.ply')]);

  it('reads a regular file, or one reached through a link, whole', () => {
    expect(new TextDecoder().decode(readUserFile(file))).toBe('ply\n');
    expect(new TextDecoder().decode(readUserFile(join(dir, 'link.ply')))).toBe('ply\n');
  });

  it('refuses a device, a pipe (without blocking on it) and a folder, naming what it is and where a link led', () => {
    expectLanternError(() => readUserFile('/dev/zero'), /^cannot read '\/dev\/zero': it is a device, not a regular file$/);
    expectLanternError(() => readUserFile(join(dir, 'zero.ply'), { what: '--env' }), /^--env: cannot read '.*zero\.ply' \(\/dev\/zero\): it is a device, not a regular file$/);
    expectLanternError(() => readUserFile(join(dir, 'pipe.ply')), /pipe\.ply': it is a pipe, not a regular file$/);
    expectLanternError(() => readUserFile(join(dir, 'folder.ply')), /folder\.ply': it is a directory, not a regular file$/);
    expectLanternError(() => checkUserFile('/dev/zero'), /it is a device/);
    expectLanternError(() => readJsonFile('/dev/zero', '--path'), /^--path: cannot read '\/dev\/zero': it is a device/);
  });

  it('says a file is missing, and tells missing from unreadable', () => {
    const missing = expectLanternError(() => readUserFile(join(dir, 'dangling.ply')), /dangling\.ply': no such file$/);
    expect(isMissing(missing)).toBe(true);
    expect(isMissing(expectLanternError(() => readUserFile('/dev/zero')))).toBe(false);
    expectLanternError(() => readUserFile(join(file, 'below')), /a part of the path is not a folder$/);
  });

  it('checks the size before reading: over fileBytes is refused with the limit named, over maxBytes in one line', () => {
    const big = join(dir, 'big.bin');
    writeFileSync(big, new Uint8Array(5000));
    expect(readUserFile(big)).toHaveLength(5000);
    const refusal = withLimits({ fileBytes: 4096 }, () => expectLanternError(() => readUserFile(big)));
    expect(refusal.userMessage).toMatch(/big\.bin: file size in bytes: 5,000 is over the limit fileBytes=4,096\. If the file is what you mean to open, raise it with --limits fileBytes=5k/);
    withLimits({ fileBytes: 4096 }, () => expectLanternError(() => checkUserFile(big), /over the limit fileBytes/));
    expectLanternError(() => readUserFile(big, { maxBytes: 100, what: '--path' }), /^--path: '.*big\.bin' holds 5,000 bytes; --path is read up to 100$/);
  });
});
