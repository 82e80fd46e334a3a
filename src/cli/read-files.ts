/** Reading files the user named, with errors that say which file and why in one line. */
import { readFileSync } from 'node:fs';
import { LanternError } from '../errors.ts';

export function readFileOrExplain(path: string): Uint8Array {
  try {
    return readFileSync(path);
  } catch (e) {
    const code = (e as NodeJS.ErrnoException).code;
    const why = code === 'ENOENT' ? 'no such file' : code === 'EACCES' ? 'permission denied' : code === 'EISDIR' ? 'it is a directory' : code === 'ENAMETOOLONG' ? 'the path is too long' : (e as Error).message;
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
