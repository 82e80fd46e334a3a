/**
 * Wolfenstein 3D files on the page: the three dropped together (or a dropped folder of the game)
 * form one set whose maps the picker lists, and a link naming one file fetches the other two
 * beside it.
 */
import { describe, expect, it } from 'vitest';
import { sortFiles } from '../loaders/registry.ts';
import { testGameFiles } from '../loaders/wolf3d/test-files.ts';
import { SceneRequests } from './scene-request.ts';

describe('Wolfenstein 3D on the page', () => {
  it('a dropped folder of the game opens as one set, other files aside', async () => {
    const { maphead, gamemaps, vswap } = testGameFiles({ maps: 2 });
    const dropped = [
      { ...vswap, head: vswap.bytes },
      { name: 'README.md', bytes: new TextEncoder().encode('# Wolf'), head: new TextEncoder().encode('# Wolf') },
      { name: 'AUDIOT.WL1', bytes: new Uint8Array(16), head: new Uint8Array(16) },
      { ...maphead, head: maphead.bytes },
      { ...gamemaps, head: gamemaps.bytes },
    ];
    const { format, main, siblings } = sortFiles(dropped);
    expect(format.id).toBe('wolf3d');
    const requests = new SceneRequests();
    const summary = await requests.openFiles({ format: format.id, files: main, siblings });
    expect(summary).toEqual({ format: 'wolf3d', description: 'MAPHEAD.WL1 + GAMEMAPS.WL1 + VSWAP.WL1', parts: [{ name: 'E1L1', loadable: true }, { name: 'E1L2', loadable: true }] });
    const loaded = await requests.load({ kind: 'part', part: 'E1L2' });
    expect(loaded.prepared.scene.name).toBe('E1L2 Test Map2');
    expect(loaded.prepared.triangles.count).toBeGreaterThan(0);
  });

  it('a link naming MAPHEAD fetches GAMEMAPS and VSWAP beside it', async () => {
    const { maphead, gamemaps, vswap } = testGameFiles();
    const served: Record<string, Uint8Array> = { 'http://h/files/0/GAMEMAPS.WL1': gamemaps.bytes, 'http://h/files/0/VSWAP.WL1': vswap.bytes };
    const fetched: string[] = [];
    const requests = new SceneRequests((url) => {
      fetched.push(url);
      return Promise.resolve(served[url]);
    });
    const summary = await requests.openFiles({ format: 'wolf3d', files: [maphead], siblings: [], baseUrl: 'http://h/files/0/MAPHEAD.WL1' });
    expect(summary.parts.map((p) => p.name)).toEqual(['E1L1', 'E1L2']);
    expect(fetched).toEqual(['http://h/files/0/GAMEMAPS.WL1', 'http://h/files/0/VSWAP.WL1']);
  });
});
