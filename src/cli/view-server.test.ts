import { mkdirSync, mkdtempSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { request, type IncomingMessage } from 'node:http';
import { connect, createServer as createTcpServer, type AddressInfo } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { CONTENT_SECURITY_POLICY, hostAllowed, startViewServer } from './view-server.ts';

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

  it('follows links before it serves a sibling: a file or a folder linked from outside is refused, a link that stays inside is served', async () => {
    const app = join(dir, 'app-links');
    const scene = join(dir, 'linked');
    const outside = join(dir, 'outside');
    mkdirSync(app);
    mkdirSync(join(scene, 'inner'), { recursive: true });
    mkdirSync(join(outside, 'etc'), { recursive: true });
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    writeFileSync(join(scene, 'model.gltf'), '{}');
    writeFileSync(join(scene, 'inner', 'real.bin'), 'inside');
    writeFileSync(join(outside, 'secret.bin'), 'secret');
    writeFileSync(join(outside, 'etc', 'hostname'), 'host');
    symlinkSync(join(outside, 'secret.bin'), join(scene, 'file-out.bin'));
    symlinkSync(join(outside, 'etc'), join(scene, 'folder-out'));
    symlinkSync(join('inner', 'real.bin'), join(scene, 'file-in.bin'));
    symlinkSync(join(scene, 'inner'), join(scene, 'folder-in'));
    // A link to the folder above, reached through a sibling's path.
    symlinkSync('..', join(scene, 'up'));
    const siblings = ['file-out.bin', 'folder-out/hostname', 'file-in.bin', 'folder-in/real.bin', 'up/outside/secret.bin'];
    const server = await startViewServer({ appDir: app, files: [{ path: join(scene, 'model.gltf'), siblings }] });
    try {
      const get = async (path: string) => {
        const r = await fetch(new URL(`files/0/${path}`, server.url));
        return `${r.status} ${r.ok ? await r.text() : ''}`.trim();
      };
      expect(await get('file-out.bin')).toBe('404');
      expect(await get('folder-out/hostname')).toBe('404');
      expect(await get('up/outside/secret.bin')).toBe('404');
      expect(await get('file-in.bin')).toBe('200 inside');
      expect(await get('folder-in/real.bin')).toBe('200 inside');
    } finally {
      await server.close();
    }
  });

  it('serves regular files only: a FIFO or a device named as a scene file is not served (nor does it hold the request)', async () => {
    const app = join(dir, 'app-special');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    const fifo = join(dir, 'pipe.ply');
    execFileSync('mkfifo', [fifo]);
    const server = await startViewServer({ appDir: app, files: [fifo, '/dev/zero'] });
    try {
      for (const url of server.fileUrls) expect((await fetch(new URL(url, server.url))).status).toBe(404);
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

  it('closes the file of every download a client aborts, and answers on (no descriptor leak)', async () => {
    const app = join(dir, 'app3');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    // Larger than the stream buffers, so that no download has read the whole file when it is aborted.
    const big = join(dir, 'big.wad');
    writeFileSync(big, new Uint8Array(8 << 20));
    const server = await startViewServer({ appDir: app, files: [big] });
    const descriptors = () => readdirSync('/proc/self/fd').length;
    try {
      const url = new URL(server.fileUrls[0]!, server.url);
      const abortOne = () =>
        new Promise<void>((resolve, reject) => {
          const r = request(url, (response) => {
            response.once('data', () => {
              r.destroy();
              resolve();
            });
          });
          r.on('error', () => undefined);
          r.on('close', () => resolve());
          r.once('error', reject);
          r.end();
        });
      await abortOne();
      await settle();
      const before = descriptors();
      for (let i = 0; i < 60; i++) await abortOne();
      await settle();
      // pipe() left one file open per abort (60 here); what remains is the test's own sockets closing.
      expect(descriptors() - before).toBeLessThan(10);
      const r = await fetch(server.url);
      expect(r.status).toBe(200);
    } finally {
      await server.close();
    }
  });

  it('answers only to the names of this machine (DNS rebinding), with nosniff and a Content-Security-Policy', async () => {
    const app = join(dir, 'app4');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    const server = await startViewServer({ appDir: app });
    try {
      const { port } = new URL(server.url);
      for (const [host, status] of [
        [`127.0.0.1:${port}`, 200],
        [`localhost:${port}`, 200],
        [`LOCALHOST.:${port}`, 200],
        [`app.localhost:${port}`, 200],
        [`evil.example:${port}`, 421],
        [`127.0.0.1.evil.example:${port}`, 421],
        ['', 421],
      ] as const) {
        const response = await get(server.url, { host });
        expect(`${host} ${response.statusCode}`).toBe(`${host} ${status}`);
        expect(response.headers['x-content-type-options']).toBe('nosniff');
        expect(response.headers['content-security-policy']).toBe(CONTENT_SECURITY_POLICY);
      }
      expect((await get(new URL('nothing-here', server.url).href, { host: `localhost:${port}` })).headers['x-content-type-options']).toBe('nosniff');
    } finally {
      await server.close();
    }
  });

  it('checks a Host header by its name, with or without a port, IPv6 in brackets', () => {
    const names = new Set(['localhost', '127.0.0.1', '::1', '192.168.1.7']);
    for (const ok of ['localhost', 'localhost:8080', '127.0.0.1:1', '127.1.2.3', '[::1]:8080', '[::1]', '192.168.1.7:80', 'x.localhost']) expect(hostAllowed(ok, names), ok).toBe(true);
    for (const bad of [undefined, '', 'example.com', 'localhost.example.com:80', '192.168.1.8', '::1', '[::2]:80', 'localhost:80:80', '[evil]:80', '127.0.0.1@evil.example']) expect(hostAllowed(bad, names), String(bad)).toBe(false);
  });

  it('says in one line when it cannot listen: a port in use, an address not of this machine', async () => {
    const app = join(dir, 'app5');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    const taken = createTcpServer();
    await new Promise<void>((resolve) => taken.listen(0, '127.0.0.1', resolve));
    try {
      const { port } = taken.address() as AddressInfo;
      await expect(startViewServer({ appDir: app, port })).rejects.toThrow(`port ${port} is already in use`);
      // 192.0.2.0/24 is reserved for documentation: never an address of this machine.
      await expect(startViewServer({ appDir: app, host: '192.0.2.1' })).rejects.toThrow('cannot listen on 192.0.2.1: it is not an address of this machine');
    } finally {
      taken.close();
    }
    const local = await startViewServer({ appDir: app });
    expect(local.loopbackOnly).toBe(true);
    await local.close();
    const everywhere = await startViewServer({ appDir: app, host: '0.0.0.0' });
    expect(everywhere.loopbackOnly).toBe(false);
    await everywhere.close();
  });

  it('closes connections past the cap and those that never finish their request', async () => {
    const app = join(dir, 'app6');
    mkdirSync(app);
    writeFileSync(join(app, 'index.html'), '<!doctype html>');
    const server = await startViewServer({ appDir: app, limits: { maxConnections: 2, headersTimeoutMs: 300, requestTimeoutMs: 300, checkIntervalMs: 50 } });
    try {
      const { port } = new URL(server.url);
      // Two connections that start a request and never end its headers; the server closes both.
      const open = () => {
        const socket = connect(Number(port), '127.0.0.1');
        socket.write(`GET / HTTP/1.1\r\nHost: localhost:${port}\r\n`);
        const closed = new Promise<string>((resolve) => {
          let text = '';
          socket.on('data', (d) => (text += d.toString()));
          socket.on('close', () => resolve(text));
          socket.on('error', () => undefined);
        });
        return { socket, closed };
      };
      const slow = [open(), open()];
      await settle();
      // The third, past the cap, is closed at once without an answer.
      const third = open();
      expect(await third.closed).toBe('');
      const answers = await Promise.all(slow.map((s) => s.closed));
      for (const text of answers) expect(text === '' || text.startsWith('HTTP/1.1 408')).toBe(true);
      // The slow ones gone, the server answers again.
      expect((await get(server.url, { host: `localhost:${port}` })).statusCode).toBe(200);
    } finally {
      await server.close();
    }
  });
});

/** Lets sockets and streams finish closing. */
const settle = () => new Promise((resolve) => setTimeout(resolve, 100));

/** A GET with exactly these headers (fetch() will not send a Host of our choosing); the body is read and dropped. */
function get(url: string, headers: Record<string, string>): Promise<IncomingMessage> {
  return new Promise((resolve, reject) => {
    const r = request(url, { headers, setHost: false }, (response) => {
      response.resume();
      response.on('end', () => resolve(response));
    });
    r.on('error', reject);
    r.end();
  });
}

