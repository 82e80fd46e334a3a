/**
 * The check of a scene's files that runs before anything slow (the GPU, the scene thread): each main
 * file's format checks what its size and a few byte ranges tell (SceneFormat.checkFile: a truncated
 * GLB), so that a damaged file is one clean line at once, before Dawn has started or said anything.
 * Whatever cannot be checked here (an unreadable file, a device, a pipe) is left to the load, which
 * reports it.
 */
import { closeSync, openSync, readSync, statSync } from 'node:fs';
import { basename } from 'node:path';
import { formatOfSet, SNIFF_BYTES } from '../loaders/registry.ts';
import { parseSceneArgument } from './scene-source.ts';

interface OpenFile {
  readonly name: string;
  readonly size: number;
  readonly fd: number;
  readonly head: Uint8Array;
}

/** `length` bytes from `offset`, never past the file's end. */
function readRange(file: Pick<OpenFile, 'fd' | 'size'>, offset: number, length: number): Uint8Array {
  const bytes = new Uint8Array(Math.max(0, Math.min(length, file.size - offset)));
  for (let at = 0; at < bytes.length; ) {
    const n = readSync(file.fd, bytes, at, bytes.length - at, offset + at);
    if (n === 0) return bytes.subarray(0, at);
    at += n;
  }
  return bytes;
}

function openRegularFile(path: string, name: string): OpenFile | undefined {
  try {
    const stat = statSync(path);
    if (!stat.isFile()) return undefined;
    const fd = openSync(path, 'r');
    const file = { name, size: stat.size, fd };
    return { ...file, head: readRange(file, 0, SNIFF_BYTES) };
  } catch {
    return undefined;
  }
}

export function checkSceneFiles(sceneArg: string): void {
  const argument = parseSceneArgument(sceneArg);
  if (argument.kind !== 'files') return;
  const files = argument.paths.map((path) => openRegularFile(path, argument.displayName ?? basename(path)));
  try {
    const readable = files.filter((f) => f !== undefined);
    if (readable.length !== files.length || readable.length === 0) return;
    const { format } = formatOfSet(readable);
    for (const file of readable) format.checkFile?.(file.name, file.size, (offset, length) => readRange(file, offset, length));
  } finally {
    for (const f of files) if (f) closeSync(f.fd);
  }
}
