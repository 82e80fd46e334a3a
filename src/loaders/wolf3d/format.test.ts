import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { formatOfFolder, identify, parseSceneReference, sortFiles } from '../registry.ts';
import type { NamedBytes, ResolveSibling } from '../format.ts';
import { parseWolfReference, WOLF3D_FORMAT, wolfFilesInFolder, wolfRole } from './format.ts';
import { testGameFiles } from './test-files.ts';

const head = (f: NamedBytes) => ({ name: f.name, head: f.bytes.subarray(0, 1024) });
const resolveFrom = (files: readonly NamedBytes[]): ResolveSibling => (path) => Promise.resolve(files.find((f) => f.name === path)?.bytes);

describe('recognising the files', () => {
  it('knows GAMEMAPS by its signature and the others by their extension', () => {
    const { maphead, gamemaps, vswap } = testGameFiles();
    expect(WOLF3D_FORMAT.sniff(gamemaps.bytes)).toBe(true);
    expect(WOLF3D_FORMAT.sniff(maphead.bytes)).toBe(false);
    // A GAMEMAPS by any name is still one.
    expect(identify({ name: 'maps.bin', head: gamemaps.bytes })?.id).toBe('wolf3d');
    for (const f of [maphead, vswap]) expect(identify(head(f))?.id).toBe('wolf3d');
    expect(['MAPHEAD.WL1', 'gamemaps.wl6', 'dir/VSWAP.WL6', 'MAPTEMP.WL6', 'AUDIOT.WL1', 'VSWAP.SOD'].map(wolfRole)).toEqual(['maphead', 'gamemaps', 'vswap', 'gamemaps', undefined, undefined]);
  });

  it('parses file lists and map names; folders are for the CLI to see', () => {
    expect(parseWolfReference('a/MAPHEAD.WL1+a/GAMEMAPS.WL1+a/VSWAP.WL1#e1l2')).toEqual({ paths: ['a/MAPHEAD.WL1', 'a/GAMEMAPS.WL1', 'a/VSWAP.WL1'], part: 'E1L2' });
    expect(parseWolfReference('w/vswap.wl6#3')).toEqual({ paths: ['w/vswap.wl6'], part: 'E1L3' });
    expect(parseWolfReference('w/MAPHEAD.WL1')).toEqual({ paths: ['w/MAPHEAD.WL1'] });
    expect(parseWolfReference('w/odd#name/MAPHEAD.WL1')).toEqual({ paths: ['w/odd#name/MAPHEAD.WL1'] });
    expect(parseWolfReference('wolf3d#E1L1')).toBeUndefined();
    expect(parseWolfReference('doom.wad#E1M1')).toBeUndefined();
    expect(() => parseWolfReference('MAPHEAD.WL1#E1M1')).toThrow(/'E1M1' is not a map/);
    expect(parseSceneReference('x/MAPHEAD.WL1#E1L9').format?.id).toBe('wolf3d');
    expect(WOLF3D_FORMAT.part?.normalize?.('10')).toBe('E1L10');
  });

  it('finds the set in a folder, the registered game before the shareware', () => {
    expect(wolfFilesInFolder(['README.md', 'vswap.wl1', 'AUDIOT.WL1', 'MAPHEAD.WL1', 'GAMEMAPS.WL1'])).toEqual(['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'vswap.wl1']);
    expect(wolfFilesInFolder(['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1', 'MAPHEAD.WL6', 'GAMEMAPS.WL6', 'VSWAP.WL6'])).toEqual(['MAPHEAD.WL6', 'GAMEMAPS.WL6', 'VSWAP.WL6']);
    expect(wolfFilesInFolder(['MAPHEAD.WL1', 'GAMEMAPS.WL6', 'VSWAP.WL1'])).toBeUndefined();
    expect(formatOfFolder(['a.wad', 'b.txt'])).toBeUndefined();
    expect(formatOfFolder(['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1'])?.format.id).toBe('wolf3d');
  });

  it('sorts a dropped folder into the set (other game files ignored) and its siblings', () => {
    const { maphead, gamemaps, vswap } = testGameFiles();
    const dropped = [head(vswap), { name: 'AUDIOT.WL1', head: new Uint8Array(10) }, { name: 'README.md', head: new Uint8Array(3) }, head(gamemaps), head(maphead)];
    const sorted = sortFiles(dropped);
    expect(sorted.format.id).toBe('wolf3d');
    expect(sorted.main.map((f) => f.name)).toEqual(['MAPHEAD.WL1', 'GAMEMAPS.WL1', 'VSWAP.WL1', 'AUDIOT.WL1']);
    expect(sorted.siblings.map((f) => f.name)).toEqual(['README.md']);
  });
});

describe('opening a set', () => {
  it('opens the three files named together, lists the maps and builds a scene', async () => {
    const { maphead, gamemaps, vswap } = testGameFiles({ maps: 2 });
    const opened = await WOLF3D_FORMAT.open({ files: [maphead, gamemaps, vswap, { name: 'AUDIOT.WL1', bytes: new Uint8Array(4) }], resolve: resolveFrom([]) });
    expect(opened.description).toBe('MAPHEAD.WL1 + GAMEMAPS.WL1 + VSWAP.WL1');
    expect(opened.parts).toEqual([{ name: 'E1L1', loadable: true }, { name: 'E1L2', loadable: true }]);
    expect(['2', 'e1l1', 'E1L3', 'x'].map((n) => opened.partNamed?.(n))).toEqual(['E1L2', 'E1L1', undefined, undefined]);
    const scene = await opened.scene('E1L2');
    expect(scene.name).toBe('E1L2 Test Map2');
    // The player start of the test map: tile (10, 30), facing north (−z).
    expect(scene.camera.position).toEqual([10.5 * 64, 32, 30.5 * 64]);
    expect(scene.camera.forward).toEqual([0, 0, -1]);
    const inventory = opened.inventory!();
    expect(inventory.lines[0]).toBe('Wolfenstein 3D (.WL1): 2 maps, 16 wall pages, 50 sprites');
    expect(inventory.json).toMatchObject({ extension: 'WL1', maps: [{ id: 'E1L1', title: 'Test Map1', width: 64, height: 64, doors: 2, statics: 5 }, { id: 'E1L2' }] });
  });

  it('finds the other two beside any one of them, in its case', async () => {
    const { maphead, gamemaps, vswap } = testGameFiles({ extension: 'wl6' });
    const lower = [maphead, gamemaps, vswap].map((f) => ({ name: f.name.toLowerCase(), bytes: f.bytes }));
    for (const main of lower) {
      const opened = await WOLF3D_FORMAT.open({ files: [main], resolve: resolveFrom(lower) });
      expect(opened.parts.map((p) => p.name)).toEqual(['E1L1', 'E1L2']);
    }
    expect(WOLF3D_FORMAT.siblings?.(lower[0]!)).toEqual(['gamemaps.wl6', 'vswap.wl6']);
    expect(WOLF3D_FORMAT.siblings?.(gamemaps)).toEqual(['MAPHEAD.wl6', 'VSWAP.wl6']);
    // Upper-case siblings of a lower-case name are found too.
    const upper = [gamemaps, vswap].map((f) => ({ name: f.name.toUpperCase(), bytes: f.bytes }));
    const opened = await WOLF3D_FORMAT.open({ files: [lower[0]!], resolve: resolveFrom(upper) });
    expect(opened.description).toBe('maphead.wl6 + GAMEMAPS.WL6 + VSWAP.WL6');
  });

  it('says which file is missing or doubled', async () => {
    const { maphead, gamemaps, vswap } = testGameFiles();
    await expect(WOLF3D_FORMAT.open({ files: [maphead], resolve: resolveFrom([gamemaps]) })).rejects.toThrow(/MAPHEAD\.WL1: VSWAP\.WL1 is missing beside it/);
    await expect(WOLF3D_FORMAT.open({ files: [maphead, maphead], resolve: resolveFrom([]) })).rejects.toThrow(/both are MAPHEAD files/);
    // Two whole games dropped together: the registered one.
    const registered = testGameFiles({ extension: 'WL6', maps: 3 });
    const both = await WOLF3D_FORMAT.open({ files: [maphead, gamemaps, vswap, registered.maphead, registered.gamemaps, registered.vswap], resolve: resolveFrom([]) });
    expect([both.description, both.parts.length]).toEqual(['MAPHEAD.WL6 + GAMEMAPS.WL6 + VSWAP.WL6', 3]);
    await expect(WOLF3D_FORMAT.open({ files: [{ name: 'AUDIOT.WL1', bytes: new Uint8Array(2) }], resolve: resolveFrom([]) })).rejects.toThrow(LanternError);
    const cut = { ...vswap, bytes: vswap.bytes.subarray(0, 100) };
    await expect(WOLF3D_FORMAT.open({ files: [maphead, gamemaps, cut], resolve: resolveFrom([]) })).rejects.toThrow(/^VSWAP\.WL1: /);
  });
});
