import { describe, expect, it } from 'vitest';
import { normalizeRelativePath, pathRelativeTo, walkEntries, type WalkEntry } from './dropped-files.ts';

/** A fake file entry whose "file" is its own name. */
const file = (name: string): WalkEntry<string> => ({ isFile: true, isDirectory: false, name, file: (ok) => setTimeout(() => ok(`<${name}>`), 0) });

/** A fake directory whose reader hands out `batch` entries per call, then an empty batch, as Chromium's does. */
function dir(name: string, children: WalkEntry<string>[], batch = 2): WalkEntry<string> {
  return {
    isFile: false,
    isDirectory: true,
    name,
    createReader: () => {
      let at = 0;
      return {
        readEntries: (ok) => {
          const next = children.slice(at, at + batch);
          at += next.length;
          setTimeout(() => ok(next), 0);
        },
      };
    },
  };
}

describe('walkEntries', () => {
  it('finds every file of a dropped folder tree with its path, reading each folder until its reader is empty', async () => {
    const tree = dir('Lantern', [dir('glTF', [file('Lantern.gltf'), file('Lantern.bin'), dir('textures', [file('a.png'), file('b.png'), file('c.png')])]), file('README.md')]);
    const found = await walkEntries([tree, file('loose.glb')]);
    expect(found.map((f) => f.path)).toEqual(['Lantern/glTF/Lantern.gltf', 'Lantern/glTF/Lantern.bin', 'Lantern/glTF/textures/a.png', 'Lantern/glTF/textures/b.png', 'Lantern/glTF/textures/c.png', 'Lantern/README.md', 'loose.glb']);
    expect(found[2]!.file).toBe('<a.png>');
  });

  it('passes on a failed read instead of hanging', async () => {
    const broken: WalkEntry<string> = { isFile: true, isDirectory: false, name: 'gone.bin', file: (_ok, fail) => fail?.(new Error('NotFoundError')) };
    await expect(walkEntries([broken])).rejects.toThrow(/NotFoundError/);
  });
});

describe('pathRelativeTo', () => {
  it('names siblings from the main file folder', () => {
    expect(pathRelativeTo('Lantern/glTF/Lantern.gltf', 'Lantern/glTF/textures/a.png')).toBe('textures/a.png');
    expect(pathRelativeTo('Lantern/glTF/Lantern.gltf', 'Lantern/glTF/Lantern.bin')).toBe('Lantern.bin');
    expect(pathRelativeTo('Lantern/glTF/Lantern.gltf', 'Lantern/shared/a.png')).toBe('../shared/a.png');
    expect(pathRelativeTo('scene.gltf', 'tex/a.png')).toBe('tex/a.png');
    expect(pathRelativeTo('a/scene.gltf', 'a.png')).toBe('../a.png');
  });
});

describe('normalizeRelativePath', () => {
  it('decodes escapes, drops ./ and folds ../ the way a URI reference resolves', () => {
    expect(normalizeRelativePath('./textures/my%20wood.png')).toBe('textures/my wood.png');
    expect(normalizeRelativePath('textures/../a.bin')).toBe('a.bin');
    expect(normalizeRelativePath('../shared/a.png')).toBe('../shared/a.png');
    expect(normalizeRelativePath('tex\\a.png')).toBe('tex/a.png');
    expect(normalizeRelativePath('100%.png')).toBe('100%.png');
  });
});
