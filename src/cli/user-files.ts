/**
 * Reading the files a user names: every CLI read of a user's path comes here (scene files and the
 * files beside them, --env, --path, --light-table, diff's images, the WADs of `lantern textures`).
 * Only regular files are read, after links are resolved, and only up to a size known before the
 * read: `/dev/zero` behind a `.ply` name, as `--env` or as `--path` once grew the process to 6–7 GB,
 * and a FIFO would block it for ever. Errors say which file and why, in one line.
 */
import { closeSync, constants, fstatSync, openSync, readSync, realpathSync, statSync, type Stats } from 'node:fs';
import { checkLimit } from '../budgets.ts';
import { LanternError } from '../errors.ts';

export interface UserFileOptions {
  /** The most bytes the file may hold. Default: the fileBytes limit (budgets.ts), refused with how to raise it. */
  readonly maxBytes?: number;
  /** What the file is to the command ('--env'): messages start with it. */
  readonly what?: string;
}

/** A regular file's bytes, read whole after its size was checked; anything else is a one-line LanternError. */
export function readUserFile(path: string, options: UserFileOptions = {}): Uint8Array {
  return readUserFilePrefix(path, Infinity, options).bytes;
}

/** readUserFile's checks, but only the file's first `bytes` bytes read (all of a shorter file), with the whole file's size. */
export function readUserFilePrefix(path: string, bytes: number, options: UserFileOptions = {}): { bytes: Uint8Array; fileBytes: number } {
  const { fd, size: fileBytes } = openUserFile(path, options);
  const size = Math.min(bytes, fileBytes);
  try {
    return { bytes: readTo(fd, size), fileBytes };
  } catch (e) {
    throw e instanceof LanternError ? e : explain(path, e, options.what);
  } finally {
    closeSync(fd);
  }
}

function readTo(fd: number, size: number): Uint8Array {
  const bytes = new Uint8Array(size);
  let at = 0;
  // The size was read once: a file that grows meanwhile is read to that size, one that shrinks to its end.
  while (at < size) {
    const n = readSync(fd, bytes, at, size - at, at);
    if (n === 0) break;
    at += n;
  }
  return at === size ? bytes : bytes.subarray(0, at);
}

/** Checks, without reading it, what readUserFile would: a command checks its inputs before slow work starts. */
export function checkUserFile(path: string, options: UserFileOptions = {}): void {
  closeSync(openUserFile(path, options).fd);
}

/** Whether a readUserFile error says there is no such file (a link to nothing included): a missing sibling is the loader's business, a device is not. */
export function isMissing(e: unknown): boolean {
  return e instanceof LanternError && (e.cause as NodeJS.ErrnoException | undefined)?.code === 'ENOENT';
}

/** The largest JSON file of options (--path, --light-table) read: 64 MiB is a million keyframes. */
export const JSON_FILE_BYTES = 1 << 26;

/** A JSON file's parsed contents; unreadable or malformed files are LanternErrors naming the path. */
export function readJsonFile(path: string, what?: string): unknown {
  const text = new TextDecoder().decode(readUserFile(path, { maxBytes: JSON_FILE_BYTES, ...(what ? { what } : {}) }));
  try {
    return JSON.parse(text);
  } catch (e) {
    throw new LanternError(`${path} is not valid JSON: ${(e as Error).message}`);
  }
}

/**
 * The open file and its size, once the path's real target is known to be a regular file within the
 * size allowed. It is opened without blocking (a FIFO put in its place after the check would block
 * the open) and checked again through the descriptor, which is what is then read.
 */
function openUserFile(path: string, options: UserFileOptions): { fd: number; size: number } {
  const prefix = options.what ? `${options.what}: ` : '';
  let real: string;
  let stats: Stats;
  try {
    real = realpathSync(path);
    stats = statSync(real);
  } catch (e) {
    // stat's word on the path as given where it has one: realpath walks the path a part at a time
    // and calls one too long "no such file".
    throw explain(path, statError(path) ?? e, options.what);
  }
  const link = real === path ? '' : ` (${real})`;
  if (!stats.isFile()) throw new LanternError(`${prefix}cannot read '${path}'${link}: ${kindOf(stats)}, not a regular file`);
  let fd: number;
  try {
    fd = openSync(real, constants.O_RDONLY | (constants.O_NONBLOCK ?? 0));
  } catch (e) {
    throw explain(path, e, options.what);
  }
  try {
    const opened = fstatSync(fd);
    if (!opened.isFile()) throw new LanternError(`${prefix}cannot read '${path}'${link}: ${kindOf(opened)}, not a regular file`);
    if (options.maxBytes !== undefined) {
      if (opened.size > options.maxBytes) throw new LanternError(`${prefix}'${path}' holds ${opened.size.toLocaleString('en-US')} bytes; ${options.what ?? 'this file'} is read up to ${options.maxBytes.toLocaleString('en-US')}`);
    } else checkLimit('fileBytes', opened.size, `${prefix}${path}: file size in bytes`);
    return { fd, size: opened.size };
  } catch (e) {
    closeSync(fd);
    throw e;
  }
}

function statError(path: string): unknown {
  try {
    statSync(path);
    return undefined;
  } catch (e) {
    return e;
  }
}

function kindOf(stats: Stats): string {
  if (stats.isDirectory()) return 'it is a directory';
  if (stats.isCharacterDevice() || stats.isBlockDevice()) return 'it is a device';
  if (stats.isFIFO()) return 'it is a pipe';
  if (stats.isSocket()) return 'it is a socket';
  return 'it is a special file';
}

function explain(path: string, e: unknown, what?: string): LanternError {
  const code = (e as NodeJS.ErrnoException).code;
  const why =
    code === 'ENOENT' ? 'no such file'
    : code === 'EACCES' || code === 'EPERM' ? 'permission denied'
    : code === 'EISDIR' ? 'it is a directory'
    : code === 'ENOTDIR' ? 'a part of the path is not a folder'
    : code === 'ELOOP' ? 'too many symbolic links'
    : code === 'ENAMETOOLONG' ? 'the path is too long'
    : (e as Error).message;
  return new LanternError(`${what ? `${what}: ` : ''}cannot read '${path}': ${why}`, undefined, { cause: e });
}
