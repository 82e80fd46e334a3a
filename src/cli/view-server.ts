/**
 * The small local web server behind `lantern view`: the built page (dist/app) and the scene files
 * named on the command line, each at `files/<n>/<name>`, with the siblings its format says it
 * refers to (a glTF's buffers and textures) at `files/<n>/<relative path>`, nothing else. It binds
 * to 127.0.0.1 by default and never serves a path it was not given (no directory listing, no `..`).
 */
import { createReadStream, existsSync, statSync } from 'node:fs';
import { createServer, type IncomingMessage, type ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import { basename, dirname, extname, join, normalize, resolve, sep } from 'node:path';
import { LanternError } from '../errors.ts';

const CONTENT_TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.wasm': 'application/wasm',
  '.map': 'application/json',
};

export interface ViewServerOptions {
  /** The built page: a folder with index.html. */
  readonly appDir: string;
  /** Scene files to offer, in order: a path, or a path with the siblings it refers to. */
  readonly files?: readonly (string | OfferedFile)[];
  readonly host?: string;
  /** 0 picks a free port. */
  readonly port?: number;
}

export interface OfferedFile {
  readonly path: string;
  /** Paths relative to `path`'s folder ('/'-separated); any with '..' or a leading '/' is refused. */
  readonly siblings?: readonly string[];
}

export interface ViewServer {
  /** The page's address, ending in '/'. */
  readonly url: string;
  /** Each offered file's address relative to the page: files/<n>/<name>. */
  readonly fileUrls: readonly string[];
  close(): Promise<void>;
}

export async function startViewServer(options: ViewServerOptions): Promise<ViewServer> {
  const appDir = resolve(options.appDir);
  if (!existsSync(join(appDir, 'index.html'))) {
    throw new LanternError(`the page is not built (${join(appDir, 'index.html')} is missing)`, 'Run `npm run build:app`, or start with `npm run view`, which builds it');
  }
  const files = (options.files ?? []).flatMap((file, i) => {
    const { path, siblings = [] } = typeof file === 'string' ? { path: file } : file;
    const main = { path, url: `files/${i}/${encodeURIComponent(basename(path))}` };
    const beside = siblings.map((relative) => {
      const parts = relative.split('/').filter((p) => p !== '.');
      if (relative.startsWith('/') || parts.some((p) => p === '..' || p === '' || p.includes('\\'))) {
        throw new LanternError(`${basename(path)} refers to '${relative}', outside its folder`, 'lantern view serves only files in or below the scene file\'s folder');
      }
      return { path: join(dirname(path), ...parts), url: `files/${i}/${parts.map(encodeURIComponent).join('/')}`, sibling: true };
    });
    return [main, ...beside];
  });
  const mains = files.filter((f) => !('sibling' in f));
  const server = createServer((request, response) => serve(request, response, appDir, files));
  await new Promise<void>((resolve, reject) => {
    server.once('error', (e: NodeJS.ErrnoException) =>
      reject(e.code === 'EADDRINUSE' ? new LanternError(`port ${options.port} is already in use`, 'Choose another with --port, or --port 0 for any free one') : e),
    );
    server.listen(options.port ?? 0, options.host ?? '127.0.0.1', resolve);
  });
  const address = server.address() as AddressInfo;
  const host = address.family === 'IPv6' ? `[${address.address}]` : address.address;
  return {
    url: `http://${host}:${address.port}/`,
    fileUrls: mains.map((f) => f.url),
    close: () =>
      new Promise<void>((resolve) => {
        server.closeAllConnections();
        server.close(() => resolve());
      }),
  };
}

function serve(request: IncomingMessage, response: ServerResponse, appDir: string, files: readonly { path: string; url: string }[]): void {
  if (request.method !== 'GET' && request.method !== 'HEAD') return reply(response, 405, 'only GET and HEAD');
  let path: string;
  try {
    path = decodeURIComponent(new URL(request.url ?? '/', 'http://x').pathname);
  } catch {
    return reply(response, 400, 'bad path');
  }
  const offered = files.find((f) => `/${decodeURIComponent(f.url)}` === path);
  if (offered) return sendFile(request, response, offered.path, 'application/octet-stream');
  const relative = path === '/' ? 'index.html' : path.slice(1);
  const full = normalize(join(appDir, relative));
  if (!full.startsWith(appDir + sep) || relative.split('/').includes('..')) return reply(response, 404, 'not found');
  sendFile(request, response, full, CONTENT_TYPES[extname(full)] ?? 'application/octet-stream');
}

function sendFile(request: IncomingMessage, response: ServerResponse, path: string, type: string): void {
  let size: number;
  try {
    const stat = statSync(path);
    if (!stat.isFile()) return reply(response, 404, 'not found');
    size = stat.size;
  } catch {
    return reply(response, 404, 'not found');
  }
  response.writeHead(200, { 'content-type': type, 'content-length': size, 'cache-control': 'no-cache' });
  if (request.method === 'HEAD') {
    response.end();
    return;
  }
  createReadStream(path)
    .on('error', () => response.destroy())
    .pipe(response);
}

function reply(response: ServerResponse, status: number, text: string): void {
  response.writeHead(status, { 'content-type': 'text/plain; charset=utf-8' });
  response.end(`${text}\n`);
}
