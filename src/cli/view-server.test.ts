import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { startViewServer } from './view-server.ts';

const dir = mkdtempSync(join(tmpdir(), 'lantern-view-server-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('the view server', () => {
  it("serves a scene file's declared siblings beside it, and nothing else from its folder", async () => {
    const app = join(dir, 'app');
    const scene = join(dir, 'helmet');
    mkdirSync(app);
    mkdirSync(join(scene, 'textures'), { recursive: true });
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    writeFileSync(join(scene, 'helmet.gltf'), '{}');
    writeFileSync(join(scene, 'helmet.bin'), 'bin');
    writeFileSync(join(scene, 'textures', 'base color.png'), 'png');
    writeFileSync(join(scene, 'secret.txt'), 'secret');
    const server = await startViewServer({ appDir: app, files: [{ path: join(scene, 'helmet.gltf'), siblings: ['helmet.bin', './textures/base color.png'] }] });
    try {
      expect(server.fileUrls).toEqual(['files/0/helmet.gltf']);
      const get = async (path: string) => {
        const r = await fetch(new URL(path, server.url));
        return `${r.status} ${r.ok ? await r.text() : ''}`.trim();
      };
      expect(await get('files/0/helmet.gltf')).toBe('200 {}');
      expect(await get('files/0/helmet.bin')).toBe('200 bin');
      // What the page asks for: the sibling's path resolved against the main file's address.
      expect(await get(new URL('textures/base%20color.png', new URL('files/0/helmet.gltf', server.url)).href)).toBe('200 png');
      expect(await get('files/0/secret.txt')).toBe('404');
      expect(await get('files/0/../0/secret.txt')).toBe('404');
    } finally {
      await server.close();
    }
  });

  it('refuses siblings outside the scene file\'s folder before serving anything', async () => {
    const app = join(dir, 'app2');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    for (const sibling of ['../elsewhere.bin', '/etc/passwd', 'a//b.png', 'textures/../../up.png']) {
      await expect(startViewServer({ appDir: app, files: [{ path: join(dir, 'x.gltf'), siblings: [sibling] }] })).rejects.toThrow(/outside its folder/);
    }
  });
});
