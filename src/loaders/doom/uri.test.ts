import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { isDoomUri, parseDoomUri } from './uri.ts';

describe('Doom URIs', () => {
  it('parses one WAD with a map', () => {
    expect(parseDoomUri('path/to/iwad.wad#E1M1')).toEqual({ files: ['path/to/iwad.wad'], map: 'E1M1' });
  });

  it('parses stacked WADs, keeping relative paths and upper-casing the map', () => {
    expect(parseDoomUri('../doom2.WAD+mods/pwad.wad#map01')).toEqual({ files: ['../doom2.WAD', 'mods/pwad.wad'], map: 'MAP01' });
  });

  it('leaves the map undefined without a fragment', () => {
    expect(parseDoomUri('freedoom2.wad')).toEqual({ files: ['freedoom2.wad'] });
    expect(parseDoomUri('freedoom2.wad#')).toEqual({ files: ['freedoom2.wad'] });
  });

  it('treats a # inside a path ending in .wad as part of the path', () => {
    expect(parseDoomUri('wads#1/doom.wad')).toEqual({ files: ['wads#1/doom.wad'] });
  });

  it('recognises .wad paths, case-insensitively, with or without a map', () => {
    expect(isDoomUri('a/b/DOOM.WAD')).toBe(true);
    expect(isDoomUri('doom.wad#E1M1')).toBe(true);
    expect(isDoomUri('doom2.wad+pwad.wad#MAP07')).toBe(true);
    expect(isDoomUri('bunny.ply')).toBe(false);
    expect(isDoomUri('doom.wad.gz')).toBe(false);
    expect(isDoomUri('cornell')).toBe(false);
  });

  it('refuses parts that are not WADs ("+" inside a path) and bad map names', () => {
    expect(() => parseDoomUri('c++/doom.wad')).toThrow(LanternError);
    expect(() => parseDoomUri('doom.wad+#E1M1')).toThrow(/'' is not a .wad file/);
    expect(() => parseDoomUri('doom.wad#TOOLONGNAME')).toThrow(/not a map name/);
    expect(() => parseDoomUri('doom.wad#E1 M1')).toThrow(/not a map name/);
  });
});
