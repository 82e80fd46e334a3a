import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { iwadFolders, iwadForMap, isBareMapName } from './iwads.ts';

describe('bare Doom map names', () => {
  it('recognises ExMy and MAPxx, nothing else', () => {
    for (const name of ['E1M1', 'e4m9', 'MAP01', 'map32']) expect(isBareMapName(name)).toBe(true);
    for (const name of ['E1M10', 'E0M1', 'MAP1', 'cornell', 'E1M1.wad', 'x#E1M1']) expect(isBareMapName(name)).toBe(false);
  });

  it('finds the IWAD of the map kind, commercial games before Freedoom, earlier folders first', () => {
    const a = mkdtempSync(join(tmpdir(), 'iwads-a-'));
    const b = mkdtempSync(join(tmpdir(), 'iwads-b-'));
    writeFileSync(join(a, 'freedoom1.wad'), 'x');
    writeFileSync(join(b, 'doom.wad'), 'x');
    writeFileSync(join(b, 'freedoom2.wad'), 'x');
    expect(iwadForMap('E1M1', [a, b])).toBe(join(b, 'doom.wad'));
    expect(iwadForMap('MAP07', [a, b])).toBe(join(b, 'freedoom2.wad'));
    expect(iwadFolders({ DOOMWADDIR: '/w', DOOMWADPATH: '/p:/q' }).slice(0, 3)).toEqual(['/w', '/p', '/q']);
  });

  it('says where it looked and how to get one when none is installed', () => {
    const empty = mkdtempSync(join(tmpdir(), 'iwads-none-'));
    const error = expectLanternError(() => iwadForMap('MAP01', [empty]));
    expect(error.message).toContain(empty);
    expect(error.userMessage).toMatch(/apt-get install freedoom.*freedoom2\.wad#MAP01/s);
  });
});
