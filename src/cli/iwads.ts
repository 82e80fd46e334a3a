/**
 * Bare Doom map names as scenes: `lantern render E1M1` opens E1M1 of an installed IWAD, as a Doom
 * port would, so that commands from the issues and the docs run without a path. Searched in order:
 * $DOOMWADDIR, each folder of $DOOMWADPATH, then where Debian's packages put them
 * (/usr/share/games/doom: `apt-get install freedoom`), /usr/local/share/games/doom and /usr/share/doom.
 * Episode maps (ExMy) come from The Ultimate Doom, Doom or Freedoom Phase 1 (or the shareware Doom),
 * MAPxx from Doom II or Freedoom Phase 2, the commercial games first.
 */
import { statSync } from 'node:fs';
import { join } from 'node:path';
import { LanternError } from '../errors.ts';

const EPISODE_MAP = /^E[1-9]M[1-9]$/i;
const LEVEL_MAP = /^MAP[0-9][0-9]$/i;

const EPISODE_IWADS = ['doomu.wad', 'doom.wad', 'freedoom1.wad', 'doom1.wad'];
const LEVEL_IWADS = ['doom2.wad', 'freedoom2.wad', 'plutonia.wad', 'tnt.wad'];

/** Whether an argument is a bare map name (E1M1, MAP01), which names a map of an installed IWAD. */
export function isBareMapName(arg: string): boolean {
  return EPISODE_MAP.test(arg) || LEVEL_MAP.test(arg);
}

/** The folders searched for IWADs, in order (environment first). */
export function iwadFolders(env: NodeJS.ProcessEnv = process.env): string[] {
  const folders: string[] = [];
  if (env.DOOMWADDIR) folders.push(env.DOOMWADDIR);
  if (env.DOOMWADPATH) folders.push(...env.DOOMWADPATH.split(':').filter((f) => f.length > 0));
  folders.push('/usr/share/games/doom', '/usr/local/share/games/doom', '/usr/share/doom');
  return folders;
}

function isFile(path: string): boolean {
  try {
    return statSync(path).isFile();
  } catch {
    return false;
  }
}

/**
 * The installed IWAD that holds a bare map name's kind of map, or a LanternError saying where it
 * looked and how to get one. The map itself is looked up in the WAD later (a missing one is named).
 */
export function iwadForMap(map: string, folders: readonly string[] = iwadFolders()): string {
  const names = EPISODE_MAP.test(map) ? EPISODE_IWADS : LEVEL_IWADS;
  for (const name of names) {
    for (const folder of folders) {
      const path = join(folder, name);
      if (isFile(path)) return path;
    }
  }
  throw new LanternError(
    `no Doom IWAD found for '${map}' (looked for ${names.join(', ')} in ${folders.join(', ')})`,
    `Install Freedoom (Debian: apt-get install freedoom), set DOOMWADDIR to the folder of your IWAD, or name the file: ${names[0] === 'doomu.wad' ? 'freedoom1.wad' : 'freedoom2.wad'}#${map.toUpperCase()}`,
  );
}
