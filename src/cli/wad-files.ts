/** Reading the WAD files a Doom URI names (`iwad.wad+pwad.wad#MAP01`) into a WadStack, for `lantern textures`. */
import { basename } from 'node:path';
import { readUserFile } from './user-files.ts';
import { parseDoomUri } from '../loaders/doom/uri.ts';
import { readWad, WadStack } from '../loaders/doom/wad.ts';

export function openWads(uri: string): { stack: WadStack; map?: string } {
  const { files, map } = parseDoomUri(uri);
  const stack = new WadStack(files.map((f) => readWad(readUserFile(f), basename(f))));
  return { stack, ...(map ? { map } : {}) };
}
