/**
 * Files the user drops or picks, with their path inside a dropped or picked folder, so that a
 * glTF's `textures/foo.png` finds `textures/foo.png` and not some other `foo.png`. The folder walk
 * is written against the few members of the File and Directory Entries API it uses (structural
 * types, not the DOM's), so that a unit test can walk a fake tree; the page passes real entries.
 */

/** A file and its path inside what was dropped ("Lantern/glTF/textures/a.png"), or its bare name. */
export interface PathedFile<F = File> {
  readonly file: F;
  readonly path: string;
}

/** The members of FileSystemFileEntry / FileSystemDirectoryEntry the walk needs. */
export interface WalkEntry<F = File> {
  readonly isFile: boolean;
  readonly isDirectory: boolean;
  readonly name: string;
  file?(success: (file: F) => void, failure?: (error: unknown) => void): void;
  createReader?(): { readEntries(success: (entries: WalkEntry<F>[]) => void, failure?: (error: unknown) => void): void };
}

/**
 * Every file under the given entries, depth first, with paths relative to the drop. A directory
 * reader hands out its entries in batches (Chromium: 100 at a time) and an empty batch at the end,
 * so it is read until empty.
 */
export async function walkEntries<F>(entries: readonly WalkEntry<F>[], prefix = ''): Promise<PathedFile<F>[]> {
  const out: PathedFile<F>[] = [];
  for (const entry of entries) {
    const path = prefix + entry.name;
    if (entry.isFile && entry.file) {
      const file = await new Promise<F>((resolve, reject) => entry.file!(resolve, reject));
      out.push({ file, path });
    } else if (entry.isDirectory && entry.createReader) {
      const reader = entry.createReader();
      const children: WalkEntry<F>[] = [];
      for (;;) {
        const batch = await new Promise<WalkEntry<F>[]>((resolve, reject) => reader.readEntries(resolve, reject));
        if (batch.length === 0) break;
        children.push(...batch);
      }
      out.push(...(await walkEntries(children, `${path}/`)));
    }
  }
  return out;
}

/**
 * A file's path as the scene loader should know it: relative to the folder of the scene's main
 * file (so a glTF's relative URIs match it exactly); a file outside that folder keeps a `../` path.
 */
export function pathRelativeTo(mainPath: string, path: string): string {
  const from = mainPath.split('/').slice(0, -1);
  const to = path.split('/');
  let common = 0;
  while (common < from.length && common < to.length - 1 && from[common] === to[common]) common++;
  return [...from.slice(common).map(() => '..'), ...to.slice(common)].join('/');
}

/**
 * A relative reference as a plain path: percent-escapes decoded (a glTF URI may write a space as
 * %20), `./` dropped and `a/../` folded, backslashes (written by some Windows exporters) as slashes.
 */
export function normalizeRelativePath(reference: string): string {
  let decoded = reference;
  try {
    decoded = decodeURIComponent(reference);
  } catch {
    // A lone '%' is a literal character in a file name.
  }
  const out: string[] = [];
  for (const part of decoded.replace(/\\/g, '/').split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else out.push(part);
  }
  return out.join('/');
}
