/** Reading files the user named, with errors that say which file and why in one line. */
import { accessSync, constants, readFileSync, statSync } from 'node:fs';
import { LanternError } from '../errors.ts';

function explain(path: string, e: unknown): LanternError {
  const code = (e as NodeJS.ErrnoException).code;
  const why = code === 'ENOENT' ? 'no such file' : code === 'EACCES' ? 'permission denied' : code === 'EISDIR' ? 'it is a directory' : code === 'ENAMETOOLONG' ? 'the path is too long' : (e as Error).message;
  return new LanternError(`cannot read '${path}': ${why}`);
}

export function readFileOrExplain(path: string): Uint8Array {
  try {
    return readFileSync(path);
  } catch (e) {
    throw explain(path, e);
  }
}

/** Checks, without reading it, that a file exists and may be read: a command checks its inputs before slow work starts. */
export function checkReadableFile(path: string): void {
  try {
    if (statSync(path).isDirectory()) throw Object.assign(new Error('EISDIR'), { code: 'EISDIR' });
    accessSync(path, constants.R_OK);
  } catch (e) {
    throw explain(path, e);
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
