/**
 * Wolfenstein 3D from the built `lantern` command: a folder lists its maps, one map opens by
 * `folder#E1L1`, by a file list or by one file, and broken files give one line naming the file.
 * Test-written files always; the real shareware files where present.
 */
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, inject, it } from 'vitest';
import { testGameFiles } from '../../src/loaders/wolf3d/test-files.ts';

let dir: string;
let cli: string;

beforeAll(async () => {
  dir = mkdtempSync(join(tmpdir(), 'lantern-wolf3d-'));
  // Built once for the e2e project (tests/e2e/global-setup.ts).
  cli = inject('lanternCli');
  const game = testGameFiles({ maps: 3 });
  mkdirSync(join(dir, 'game'));
  for (const f of [game.maphead, game.gamemaps, game.vswap]) writeFileSync(join(dir, 'game', f.name), f.bytes);
  writeFileSync(join(dir, 'game', 'AUDIOT.WL1'), new Uint8Array(8));
  mkdirSync(join(dir, 'broken'));
  writeFileSync(join(dir, 'broken', 'MAPHEAD.WL1'), game.maphead.bytes);
  writeFileSync(join(dir, 'broken', 'GAMEMAPS.WL1'), game.gamemaps.bytes.subarray(0, 4000));
  writeFileSync(join(dir, 'broken', 'VSWAP.WL1'), game.vswap.bytes);
});

afterAll(() => {
  rmSync(dir, { recursive: true, force: true });
});

function lantern(args: string[]) {
  const r = spawnSync(process.execPath, [cli, ...args], { encoding: 'utf8', env: { ...process.env, VK_ICD_FILENAMES: '/usr/lib/chromium/vk_swiftshader_icd.json' }, timeout: 120_000 });
  const stderr = r.stderr.split('\n').filter((l) => l.startsWith('lantern') || l.startsWith('error:')).join('\n');
  return { code: r.status, stdout: r.stdout, stderr, rawStderr: r.stderr };
}

describe('lantern info on Wolfenstein 3D files', () => {
  it('a folder lists its maps; folder#map, a file list and one file open a map', () => {
    const game = join(dir, 'game');
    const listing = lantern(['info', game]);
    expect(listing.code, listing.rawStderr).toBe(0);
    expect(listing.stdout).toContain('Wolfenstein 3D (.WL1): 3 maps, 16 wall pages, 50 sprites');
    expect(listing.stdout).toMatch(/E1L3\s+Test Map3\s+64×64/);
    const json = JSON.parse(lantern(['info', game, '--json']).stdout);
    expect(json.maps.map((m: { id: string }) => m.id)).toEqual(['E1L1', 'E1L2', 'E1L3']);
    for (const arg of [`${game}#e1l2`, `${game}#2`, `${game}/MAPHEAD.WL1+${game}/GAMEMAPS.WL1+${game}/VSWAP.WL1#E1L2`, `${game}/VSWAP.WL1#E1L2`]) {
      const r = lantern(['info', arg, '--json']);
      expect(r.code, `${arg}: ${r.rawStderr}`).toBe(0);
      expect(JSON.parse(r.stdout).scene).toBe('E1L2 Test Map2');
    }
  });

  it('bad input: one line naming the file or the map', () => {
    const broken = lantern(['info', join(dir, 'broken')]);
    expect(broken.code).not.toBe(0);
    expect(broken.stderr).toMatch(/^lantern: error: GAMEMAPS\.WL1: map \d \(E1L\d\)/);
    expect(broken.stderr.split('\n')).toHaveLength(1);
    const noMap = lantern(['info', `${join(dir, 'game')}#E2L1`]);
    expect(noMap.stderr).toMatch(/has no map 'E2L1'\. Its maps are: E1L1, E1L2, E1L3/);
    const empty = mkdtempSync(join(dir, 'empty-'));
    expect(lantern(['info', `${empty}#E1L1`]).stderr).toMatch(/is a folder with no scene Lantern reads in it/);
    const missing = mkdtempSync(join(dir, 'lonely-'));
    writeFileSync(join(missing, 'MAPHEAD.WL1'), testGameFiles().maphead.bytes);
    expect(lantern(['info', join(missing, 'MAPHEAD.WL1')]).stderr).toMatch(/MAPHEAD\.WL1: GAMEMAPS\.WL1 is missing beside it/);
  });
});

const SHAREWARE = ['../shared/assets/wolf3d-shareware', '/work/shared/assets/wolf3d-shareware'].find((d) => existsSync(join(d, 'VSWAP.WL1')));
if (!SHAREWARE) console.warn('Wolfenstein 3D shareware files not found: skipping the CLI test on them');

describe.skipIf(!SHAREWARE)('lantern info on the shareware folder', () => {
  it('lists E1L1 to E1L10 with their titles and counts', () => {
    const r = lantern(['info', SHAREWARE!]);
    expect(r.code, r.rawStderr).toBe(0);
    expect(r.stdout).toContain('Wolfenstein 3D (.WL1): 10 maps, 106 wall pages, 436 sprites');
    expect(r.stdout).toMatch(/E1L1\s+Wolf1 Map1\s+64×64\s+3057\s+22\s+121/);
    expect(r.stdout).toMatch(/E1L10\s+Wolf1 Secret\s+64×64/);
  });
});
