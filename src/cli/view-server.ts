/**
 * The small local web server behind `lantern view`: the built page (dist/app) and the scene files
 * named on the command line, each at `files/<n>/<name>`, with the siblings its format says it
 * refers to (a glTF's buffers and textures) at `files/<n>/<relative path>`, nothing else. It binds
 * to 127.0.0.1 by default and never serves a path it was not given (no directory listing, no `..`),
 * nor a sibling whose real path (links followed, at each request) leaves the scene file's folder:
 * `textures/` may be a link to /etc, and the name alone does not say so. It serves regular files only.
 *
 * What else it refuses (the README's Security section says the same to users): a request whose
 * `Host` is not a name of this machine (a web page on another site whose name was re-pointed at
 * 127.0.0.1, "DNS rebinding", would otherwise read the served files); connections past a cap, and
 * those that are slow to send their request or idle. Every response says `nosniff` and carries a
 * Content-Security-Policy that lets the page run its own scripts, workers and WebAssembly and
 * nothing from elsewhere. A file is streamed with stream.pipeline, which closes the file when the
 * client goes away mid-download.
 */
import { closeSync, constants, createReadStream, existsSync, fstatSync, openSync, realpathSync } from 'node:fs';
import { createServer, type IncomingMessage, type ServerResponse } from 'node:http';
import { isIP, type AddressInfo } from 'node:net';
import { hostname, networkInterfaces } from 'node:os';
import { basename, dirname, extname, join, normalize, resolve, sep } from 'node:path';
import { pipeline } from 'node:stream';
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

/**
 * What the page needs and no more: its own scripts and module workers (meshoptimizer's decoder
 * workers start from blob: URLs), WebAssembly compiled from its own bytes (meshoptimizer), fetches
 * of the served files and of data:/blob: URLs (glTF embeds buffers as data: URIs; files dropped on
 * the page are blob: URLs), images from data:/blob: URLs, inline styles (tweakpane adds a <style>).
 * No other origin, no plug-ins, no framing, no forms.
 */
export const CONTENT_SECURITY_POLICY = [
  "default-src 'none'",
  "script-src 'self' 'wasm-unsafe-eval'",
  "worker-src 'self' blob:",
  "connect-src 'self' data: blob:",
  "img-src 'self' data: blob:",
  "style-src 'self' 'unsafe-inline'",
  "base-uri 'none'",
  "form-action 'none'",
  "frame-ancestors 'none'",
].join('; ');

/** Headers on every response. */
const SECURITY_HEADERS = {
  'x-content-type-options': 'nosniff',
  'content-security-policy': CONTENT_SECURITY_POLICY,
  'referrer-policy': 'no-referrer',
  'cross-origin-resource-policy': 'same-origin',
};

/** Limits on connections (see startViewServer); tests make them short. */
export interface ConnectionLimits {
  /** Open connections at once; more are closed as they arrive. */
  readonly maxConnections: number;
  /** Milliseconds a client may take to send a request's headers. */
  readonly headersTimeoutMs: number;
  /** Milliseconds a client may take to send a whole request. */
  readonly requestTimeoutMs: number;
  /** Milliseconds an idle kept-alive connection stays open. */
  readonly keepAliveTimeoutMs: number;
  /** Milliseconds of no traffic either way after which a connection is closed (a stalled download). */
  readonly idleTimeoutMs: number;
  /** How often Node checks the headers and request timeouts. */
  readonly checkIntervalMs: number;
}

/**
 * A browser opens about six connections to a host; 256 leaves room for several tabs and scripts
 * while a flood of idle sockets cannot use up the process's file descriptors.
 */
export const DEFAULT_CONNECTION_LIMITS: ConnectionLimits = {
  maxConnections: 256,
  headersTimeoutMs: 10_000,
  requestTimeoutMs: 30_000,
  keepAliveTimeoutMs: 5_000,
  idleTimeoutMs: 120_000,
  checkIntervalMs: 1_000,
};

export interface ViewServerOptions {
  /** The built page: a folder with index.html. */
  readonly appDir: string;
  /** Scene files to offer, in order: a path, or a path with the siblings it refers to. */
  readonly files?: readonly (string | OfferedFile)[];
  readonly host?: string;
  /** 0 picks a free port. */
  readonly port?: number;
  readonly limits?: Partial<ConnectionLimits>;
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
  /** False when the server listens beyond this machine (--host 0.0.0.0, a LAN address): anyone who can reach the port can read the served files. */
  readonly loopbackOnly: boolean;
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
      return { path: join(dirname(path), ...parts), url: `files/${i}/${parts.map(encodeURIComponent).join('/')}`, within: dirname(path), sibling: true };
    });
    return [main, ...beside];
  });
  const mains = files.filter((f) => !('sibling' in f));
  const limits = { ...DEFAULT_CONNECTION_LIMITS, ...options.limits };
  let allowedHosts: ReadonlySet<string> = new Set();
  const server = createServer(
    { headersTimeout: limits.headersTimeoutMs, requestTimeout: limits.requestTimeoutMs, keepAliveTimeout: limits.keepAliveTimeoutMs, connectionsCheckingInterval: limits.checkIntervalMs },
    (request, response) => {
      if (!hostAllowed(request.headers.host, allowedHosts)) return reply(response, 421, 'this server answers only to the names of the machine it runs on');
      serve(request, response, appDir, files);
    },
  );
  server.maxConnections = limits.maxConnections;
  server.setTimeout(limits.idleTimeoutMs, (socket) => socket.destroy());
  const host = options.host ?? '127.0.0.1';
  const port = options.port ?? 0;
  await new Promise<void>((resolve, reject) => {
    server.once('error', (e: NodeJS.ErrnoException) => reject(listenError(e, host, port)));
    server.listen(port, host, resolve);
  });
  const address = server.address() as AddressInfo;
  allowedHosts = hostNames(address.address);
  const urlHost = address.family === 'IPv6' ? `[${address.address}]` : address.address;
  return {
    url: `http://${urlHost}:${address.port}/`,
    fileUrls: mains.map((f) => f.url),
    loopbackOnly: isLoopback(address.address),
    close: () =>
      new Promise<void>((resolve) => {
        server.closeAllConnections();
        server.close(() => resolve());
      }),
  };
}

/** A failure to listen as one line that names the address and what to do. */
function listenError(e: NodeJS.ErrnoException, host: string, port: number): Error {
  switch (e.code) {
    case 'EADDRINUSE':
      return new LanternError(`port ${port} is already in use`, 'Choose another with --port, or --port 0 for any free one');
    case 'EACCES':
      return new LanternError(`not allowed to listen on port ${port}`, 'Ports below 1024 need privileges: choose another with --port');
    case 'EADDRNOTAVAIL':
      return new LanternError(`cannot listen on ${host}: it is not an address of this machine`, 'Use --host 127.0.0.1 (this machine only) or an address of one of its network interfaces');
    case 'ENOTFOUND':
    case 'EAI_AGAIN':
    case 'EAI_FAIL':
    case 'EAI_NONAME':
      return new LanternError(`cannot listen on '${host}': no such host`, 'Give --host an IP address, such as 127.0.0.1');
    case 'EINVAL':
      return new LanternError(`cannot listen on ${host}, port ${port}: invalid address`, 'Give --host an IP address, such as 127.0.0.1');
    default:
      return e;
  }
}

const isLoopback = (address: string): boolean => address === '::1' || address.startsWith('127.') || address.startsWith('::ffff:127.');

/**
 * The names a request may give in `Host`: the loopback names, the bound address and, when bound to
 * every interface (0.0.0.0, ::), every address of this machine and its host name. A web page on
 * another site can make a browser send its own domain name here (by re-pointing that name at this
 * machine); it cannot make it send one of these.
 */
function hostNames(bound: string): ReadonlySet<string> {
  const names = new Set(['localhost', '127.0.0.1', '::1', bound]);
  if (bound === '0.0.0.0' || bound === '::') {
    for (const list of Object.values(networkInterfaces())) for (const a of list ?? []) names.add(a.address);
    names.add(hostname().toLowerCase());
  }
  return names;
}

/** Whether a `Host` header (name or address, with or without a port) is one of `names`. */
export function hostAllowed(header: string | undefined, names: ReadonlySet<string>): boolean {
  if (!header) return false;
  const value = header.trim().toLowerCase();
  // [v6]:port, [v6], name:port, name.
  const bracketed = /^\[([0-9a-f:.]+)\](?::\d+)?$/.exec(value);
  const name = bracketed ? bracketed[1]! : value.replace(/:\d+$/, '');
  if (bracketed ? isIP(name) !== 6 : name.includes(':')) return false;
  // Names under .localhost resolve to this machine by definition (RFC 6761); a trailing dot is the same name.
  const plain = name.endsWith('.') ? name.slice(0, -1) : name;
  return names.has(plain) || plain.endsWith('.localhost') || (isIP(plain) === 4 && plain.startsWith('127.'));
}

/** A file offered, and for a sibling the folder its real path must stay in. */
interface Offered {
  readonly path: string;
  readonly url: string;
  readonly within?: string;
}

function serve(request: IncomingMessage, response: ServerResponse, appDir: string, files: readonly Offered[]): void {
  if (request.method !== 'GET' && request.method !== 'HEAD') return reply(response, 405, 'only GET and HEAD');
  let path: string;
  try {
    path = decodeURIComponent(new URL(request.url ?? '/', 'http://x').pathname);
  } catch {
    return reply(response, 400, 'bad path');
  }
  const offered = files.find((f) => `/${decodeURIComponent(f.url)}` === path);
  if (offered) return sendFile(request, response, offered.path, offered.within, 'application/octet-stream');
  const relative = path === '/' ? 'index.html' : path.slice(1);
  const full = normalize(join(appDir, relative));
  if (!full.startsWith(appDir + sep) || relative.split('/').includes('..')) return reply(response, 404, 'not found');
  sendFile(request, response, full, appDir, CONTENT_TYPES[extname(full)] ?? 'application/octet-stream');
}

/**
 * The real path of `path` when it is inside the real path of `folder` (or anywhere, with no folder),
 * else undefined. Both are resolved now, links and all: a check on the name alone let a link beside
 * the scene (a file, or a folder on the sibling's way) serve what it pointed at.
 */
export function realPathInside(path: string, folder: string | undefined): string | undefined {
  try {
    const real = realpathSync(path);
    if (folder === undefined) return real;
    const root = realpathSync(folder);
    return real.startsWith(root.endsWith(sep) ? root : root + sep) ? real : undefined;
  } catch {
    return undefined;
  }
}

function sendFile(request: IncomingMessage, response: ServerResponse, path: string, within: string | undefined, type: string): void {
  const real = realPathInside(path, within);
  if (real === undefined) return reply(response, 404, 'not found');
  // Opened, then checked through the descriptor that is streamed: a regular file, not a device or a
  // pipe (opened without blocking, so a pipe cannot hold the request), of the size sent.
  let fd: number;
  let size: number;
  try {
    fd = openSync(real, constants.O_RDONLY | (constants.O_NONBLOCK ?? 0));
  } catch {
    return reply(response, 404, 'not found');
  }
  try {
    const stat = fstatSync(fd);
    if (!stat.isFile()) throw new Error('not a regular file');
    size = stat.size;
  } catch {
    closeSync(fd);
    return reply(response, 404, 'not found');
  }
  response.writeHead(200, { ...SECURITY_HEADERS, 'content-type': type, 'content-length': size, 'cache-control': 'no-cache' });
  if (request.method === 'HEAD' || size === 0) {
    closeSync(fd);
    response.end();
    return;
  }
  // pipeline, not pipe: a client that goes away mid-download destroys the file stream too (pipe
  // left it open, one descriptor per aborted download). A read error ends the response early. The
  // stream stops at the size sent, should the file grow meanwhile.
  pipeline(createReadStream('', { fd, start: 0, end: size - 1 }), response, () => undefined);
}

function reply(response: ServerResponse, status: number, text: string): void {
  response.writeHead(status, { ...SECURITY_HEADERS, 'content-type': 'text/plain; charset=utf-8' });
  response.end(`${text}\n`);
}
