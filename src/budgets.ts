/**
 * The sizes Lantern agrees to read, checked before anything is allocated. Files come from anywhere,
 * and a small file can ask for a lot: a 400 KB .ply.gz inflates to gigabytes, a 23 KB WAD asks for
 * 48 textures of 4096², an EXR header claims a 100,000² image. Each loader compares what a header or
 * count asks for against these limits and refuses with one line naming the limit, the value found and
 * how to raise it; nothing is decoded first.
 *
 * The defaults hold every real file we know of with room to spare (Freedoom's largest map has 10,000
 * linedefs; the Stanford Dragon 437k vertices; an 8K equirectangular sky 8192×4096 pixels) while keeping
 * one load well under 2 GB. A user who means it raises them with `LANTERN_LIMITS` (read from the
 * environment, so worker threads see it too) or the CLI's `--limits`, both `name=value[,name=value…]`,
 * values as integers, with an optional k/M/G suffix (powers of 1024) or in exponent form (5e6).
 *
 * Pure: no node:* imports. The environment is read through globalThis, so the page (which has none)
 * simply gets the defaults.
 */
import { LanternError } from './errors.ts';

export interface Limits {
  /** Bytes a compressed stream (gzip, zlib) may inflate to. */
  readonly decompressedBytes: number;
  /** Vertices in one mesh file (PLY vertex records, glTF accessor elements). */
  readonly vertices: number;
  /** Faces in one mesh file (PLY face records). */
  readonly faces: number;
  /** Corners of one polygon (a PLY face list, a Doom sector's boundary). */
  readonly polygonVertices: number;
  /** Instances one scene places (glTF: nodes with a mesh, and each EXT_mesh_gpu_instancing row). */
  readonly instances: number;
  /** Bytes one glTF's accessors and embedded images take once read (glTF-Transform copies or zero-fills each), summed from its JSON. */
  readonly gltfBytes: number;
  /** Doom map records: linedefs, sidedefs, vertices, sectors and things, each. */
  readonly mapRecords: number;
  /** Lumps in one WAD directory. */
  readonly lumps: number;
  /** Texels of all textures one load composes or decodes together (RGBA8: 4 bytes each). */
  readonly textureTexels: number;
  /** Pixels of one image (EXR, HDR, PNG), read from its header before it is decoded. */
  readonly imagePixels: number;
  /** Work units one Doom sector's repair may spend (candidate gap pairs, point-in-ring tests). */
  readonly sectorWork: number;
  /** Warnings of one kind printed per load; the rest are counted in one closing line. */
  readonly warningsPerKind: number;
  /** Atoms and bonds of one molecule file (all its SD records together), each; charged from the counts lines. */
  readonly moleculeRecords: number;
  /** Bytes of one file the CLI reads (a scene file, a file beside it, an image), checked before it is read. */
  readonly fileBytes: number;
}

export const DEFAULT_LIMITS: Readonly<Limits> = Object.freeze({
  decompressedBytes: 1 << 29, // 512 MiB
  // 3.1 million each: a PLY at both limits (with normals) loads at 1.5 GB, about 280 bytes a triangle
  // and 130 a vertex with the BVH (docs/hardening.md has the figures); 1 << 25 let a 392 KB .ply.gz
  // of 10.3 million triangles load at 2.9 GB.
  vertices: 3 << 20,
  faces: 3 << 20,
  polygonVertices: 1 << 16,
  instances: 1 << 19, // 524,288
  gltfBytes: 1 << 29, // 512 MiB
  mapRecords: 1 << 20, // 1,048,576
  lumps: 1 << 20,
  textureTexels: 1 << 27, // 134 million: 512 MiB of RGBA8
  imagePixels: 1 << 25, // 8192×4096
  sectorWork: 1 << 22, // 4.2 million: 64 times what any sector of Freedoom's 68 maps needs
  warningsPerKind: 20,
  moleculeRecords: 1 << 19, // 524,288: at the limit, a ball-and-stick load takes 1.0 GB (docs/hardening.md)
  fileBytes: 1 << 29, // 512 MiB: an 8192×4096 float RGB EXR stored uncompressed is 403 MB
});

export type LimitName = keyof Limits;

export const LIMIT_NAMES = Object.keys(DEFAULT_LIMITS) as LimitName[];

/** The environment variable the limits are read from, and the CLI option that sets it. */
export const LIMITS_ENV = 'LANTERN_LIMITS';
export const LIMITS_OPTION = '--limits';

/**
 * `name=value[,name=value…]` as limits over the defaults (or over `base`). Unknown names, values that
 * are not positive whole numbers, and malformed pairs are one-line errors listing what is accepted.
 */
export function parseLimits(text: string, base: Readonly<Limits> = DEFAULT_LIMITS): Limits {
  const out: Record<string, number> = { ...base };
  for (const raw of text.split(',')) {
    const pair = raw.trim();
    if (pair === '') continue;
    const eq = pair.indexOf('=');
    if (eq <= 0) throw new LanternError(`bad limit '${pair}': expected name=value`, `limits are ${LIMIT_NAMES.join(', ')}`);
    const name = pair.slice(0, eq).trim();
    if (!(LIMIT_NAMES as string[]).includes(name)) throw new LanternError(`unknown limit '${name}'`, `limits are ${LIMIT_NAMES.join(', ')}`);
    const value = parseSize(pair.slice(eq + 1).trim());
    if (value === undefined) throw new LanternError(`bad value for limit ${name}: '${pair.slice(eq + 1).trim()}'`, 'give a positive whole number, e.g. 4G, 500k or 2e6');
    out[name] = value;
  }
  return out as unknown as Limits;
}

const SUFFIX: Readonly<Record<string, number>> = { '': 1, k: 1024, K: 1024, m: 1024 ** 2, M: 1024 ** 2, g: 1024 ** 3, G: 1024 ** 3 };

function parseSize(text: string): number | undefined {
  const m = /^(\d+(?:\.\d+)?(?:e\d+)?)([kKmMgG]?)$/.exec(text);
  if (!m) return undefined;
  const value = Number(m[1]) * SUFFIX[m[2]!]!;
  return Number.isSafeInteger(value) && value > 0 ? value : undefined;
}

let configured: Limits | undefined;

/** The limits in force: those configured, else LANTERN_LIMITS over the defaults, else the defaults. */
export function limits(): Limits {
  if (!configured) {
    const env = (globalThis as { process?: { env?: Record<string, string | undefined> } }).process?.env?.[LIMITS_ENV];
    configured = env ? parseLimits(env) : { ...DEFAULT_LIMITS };
  }
  return configured;
}

/**
 * Sets the limits for this thread (undefined: back to the environment's or the defaults). The CLI
 * also puts its `--limits` text in LANTERN_LIMITS so its worker threads agree.
 */
export function configureLimits(next: Partial<Limits> | undefined): void {
  configured = next === undefined ? undefined : { ...limits(), ...next };
}

/**
 * The CLI's `--limits name=value,…`: over LANTERN_LIMITS' values (the option wins), configured for
 * this thread and written back to the environment so that worker threads started later agree.
 */
export function applyLimitsOption(text: string | undefined): void {
  if (text === undefined) return;
  const env = (globalThis as { process?: { env?: Record<string, string | undefined> } }).process?.env;
  const merged = parseLimits(text, limits());
  configured = merged;
  if (env) env[LIMITS_ENV] = LIMIT_NAMES.map((name) => `${name}=${merged[name]}`).join(',');
}

/** Runs `f` with some limits changed, then restores them (tests). */
export function withLimits<T>(changes: Partial<Limits>, f: () => T): T {
  const before = limits();
  configured = { ...before, ...changes };
  try {
    return f();
  } finally {
    configured = before;
  }
}

/** The one-line refusal: what is too big, the value found, the limit, and how to raise it. */
export function overLimit(name: LimitName, found: number, what: string): LanternError {
  const limit = limits()[name];
  return new LanternError(
    `${what}: ${formatCount(found)} is over the limit ${name}=${formatCount(limit)}`,
    `if the file is what you mean to open, raise it with ${LIMITS_OPTION} ${name}=${suggest(found)} (or ${LIMITS_ENV}=${name}=${suggest(found)})`,
  );
}

/** Throws `overLimit` when `found` exceeds the limit; `found` may be NaN or Infinity (refused too). */
export function checkLimit(name: LimitName, found: number, what: string): void {
  if (!(found <= limits()[name])) throw overLimit(name, found, what);
}

function formatCount(n: number): string {
  return Number.isFinite(n) ? Math.round(n).toLocaleString('en-US') : String(n);
}

function suggest(found: number): string {
  if (!Number.isFinite(found)) return 'N';
  const units: Array<[string, number]> = [['G', 1024 ** 3], ['M', 1024 ** 2], ['k', 1024]];
  for (const [s, u] of units) if (found >= u) return `${Math.ceil(found / u)}${s}`;
  return String(Math.ceil(found));
}

/**
 * A running total against one limit: textures composed so far, bytes inflated so far. `add` refuses
 * before the amount is allocated.
 */
export class Budget {
  private used = 0;
  constructor(
    readonly name: LimitName,
    private readonly what: string,
  ) {}

  add(amount: number, item: string): void {
    const total = this.used + amount;
    if (!(total <= limits()[this.name])) throw overLimit(this.name, total, `${this.what} (with ${item})`);
    this.used = total;
  }

  get total(): number {
    return this.used;
  }
}

/**
 * Warnings of one kind (the message with its numbers and quoted names blanked) pass through up to
 * `warningsPerKind` times; `finish` then says how many of each kind were held back. One WAD with
 * broken sectors printed 119,996 lines before this.
 */
export class WarningCap {
  private readonly counts = new Map<string, { shown: number; held: number; example: string }>();
  readonly warn: (message: string) => void;

  constructor(
    private readonly sink: (message: string) => void,
    private readonly perKind = limits().warningsPerKind,
  ) {
    this.warn = (message) => {
      const kind = warningKind(message);
      let c = this.counts.get(kind);
      if (!c) this.counts.set(kind, (c = { shown: 0, held: 0, example: message }));
      if (c.shown < this.perKind) {
        c.shown++;
        this.sink(message);
      } else c.held++;
    };
  }

  /** One line per kind that was cut short; call once the load is over. */
  finish(): void {
    for (const c of this.counts.values()) {
      if (c.held > 0) this.sink(`… and ${c.held.toLocaleString('en-US')} more warning${c.held > 1 ? 's' : ''} like "${clip(c.example, 100)}" (${LIMITS_OPTION} warningsPerKind=N shows more)`);
    }
    this.counts.clear();
  }
}

export function warningKind(message: string): string {
  return message
    .replace(/'[^']*'|"[^"]*"/g, "''")
    .replace(/\b[A-Z][A-Z0-9_\-\[\]\\]*\b/g, 'N')
    .replace(/-?\d+(\.\d+)?/g, '#')
    .slice(0, 60);
}

function clip(s: string, n: number): string {
  return s.length <= n ? s : `${s.slice(0, n - 1)}…`;
}
