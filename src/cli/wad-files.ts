/** Reading the WAD files a Doom URI names (`iwad.wad+pwad.wad#MAP01`) into a WadStack. */
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { LanternError } from '../errors.ts';
import { parseDoomUri } from '../loaders/doom/uri.ts';
import { readWad, WadStack } from '../loaders/doom/wad.ts';

export function readFileOrExplain(path: string): Uint8Array {
  try {
    return readFileSync(path);
  } catch (e) {
    const code = (e as NodeJS.ErrnoException).code;
    const why = code === 'ENOENT' ? 'no such file' : code === 'EACCES' ? 'permission denied' : code === 'EISDIR' ? 'it is a directory' : (e as Error).message;
    throw new LanternError(`cannot read '${path}': ${why}`);
  }
}

/** A JSON file's parsed contents; unreadable or malformed files are LanternErrors naming the path. */
export function readJsonFile(path: string): unknown {
  const text = new TextDecoder().decode(readFileOrExplain(path));
  try {
    return JSON.parse(text);
  } catch (e) {
    throw new LanternError(`${path} is not valid JSON: ${(e as Error).message}`);
  }
}

export function openWads(uri: string): { stack: WadStack; map?: string } {
  const { files, map } = parseDoomUri(uri);
  const stack = new WadStack(files.map((f) => readWad(readFileOrExplain(f), basename(f))));
  return { stack, ...(map ? { map } : {}) };
}
