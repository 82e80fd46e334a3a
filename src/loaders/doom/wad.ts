/**
 * The WAD container (https://doomwiki.org/wiki/WAD): a 12-byte header ("IWAD"/"PWAD", lump count,
 * directory offset, little-endian int32s) and a directory of 16-byte entries (data offset, size,
 * 8-character NUL-padded name). Everything is validated when the file is read, so later code can
 * slice lumps without bounds checks. A WadStack layers an IWAD and PWADs the way the game does.
 */
import { LanternError } from '../../errors.ts';
import { checkLimit } from '../../budgets.ts';

export interface Lump {
  /** Upper-cased, up to 8 characters. */
  readonly name: string;
  readonly offset: number;
  readonly size: number;
  /** Position in the file's directory. */
  readonly index: number;
}

export interface WadFile {
  /** The name the user knows the file by (path or file name), used in every message. */
  readonly name: string;
  readonly kind: 'IWAD' | 'PWAD';
  readonly lumps: readonly Lump[];
  /** The lump's bytes (a view into the file, not a copy). */
  data(lump: Lump): Uint8Array;
}

export type MapFormat = 'doom' | 'hexen' | 'udmf';

export interface MapInfo {
  /** The marker lump's name: 'E1M1', 'MAP01', or anything else. */
  readonly name: string;
  readonly format: MapFormat;
  /** Name of the WAD the map comes from. */
  readonly file: string;
}

const HEADER_SIZE = 12;
const DIRECTORY_ENTRY_SIZE = 16;
const CORRUPT_HINT = 'the file is truncated or is not a WAD';

export function readWad(bytes: Uint8Array, fileName: string): WadFile {
  if (bytes.length < HEADER_SIZE) {
    throw new LanternError(`${fileName}: not a WAD file (only ${bytes.length} bytes, less than the 12-byte header)`, CORRUPT_HINT);
  }
  const magic = String.fromCharCode(bytes[0]!, bytes[1]!, bytes[2]!, bytes[3]!);
  if (magic !== 'IWAD' && magic !== 'PWAD') {
    throw new LanternError(`${fileName}: not a WAD file (it starts with ${JSON.stringify(magic)}, not "IWAD" or "PWAD")`, 'Lantern reads Doom WAD files; ZIP-based .pk3/.pk7 packages are not supported');
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const count = view.getInt32(4, true);
  const directoryOffset = view.getInt32(8, true);
  if (count < 0) throw new LanternError(`${fileName}: corrupt WAD header (negative lump count ${count})`, CORRUPT_HINT);
  if (directoryOffset < 0) throw new LanternError(`${fileName}: corrupt WAD header (negative directory offset ${directoryOffset})`, CORRUPT_HINT);
  // Checked before anything is allocated: a directory that the file cannot hold means a bad header.
  if (directoryOffset + count * DIRECTORY_ENTRY_SIZE > bytes.length) {
    throw new LanternError(
      `${fileName}: corrupt WAD: the directory (${count} lumps at offset ${directoryOffset}) runs past the end of the ${bytes.length}-byte file`,
      CORRUPT_HINT,
    );
  }
  checkLimit('lumps', count, `${fileName}: lumps in the WAD directory`);
  const lumps: Lump[] = [];
  for (let i = 0; i < count; i++) {
    const at = directoryOffset + i * DIRECTORY_ENTRY_SIZE;
    const offset = view.getInt32(at, true);
    const size = view.getInt32(at + 4, true);
    const name = readName(bytes, at + 8);
    if (size < 0) throw new LanternError(`${fileName}: corrupt WAD: lump ${i} (${name}) has a negative size ${size}`, CORRUPT_HINT);
    // Empty lumps (markers) are never read; tools write all sorts of offsets for them.
    if (size > 0 && (offset < 0 || offset + size > bytes.length)) {
      throw new LanternError(
        `${fileName}: corrupt WAD: lump ${i} (${name}, ${size} bytes at offset ${offset}) lies outside the ${bytes.length}-byte file`,
        CORRUPT_HINT,
      );
    }
    lumps.push({ name, offset: size > 0 ? offset : 0, size, index: i });
  }
  return {
    name: fileName,
    kind: magic,
    lumps,
    data: (lump) => bytes.subarray(lump.offset, lump.offset + lump.size),
  };
}

/**
 * An 8-byte name: up to the first NUL (tools leave garbage after it), upper-cased in ASCII only,
 * like vanilla's strupr-based lookups.
 */
export function readName(bytes: Uint8Array, at: number): string {
  let name = '';
  for (let i = 0; i < 8; i++) {
    const c = bytes[at + i] ?? 0;
    if (c === 0) break;
    name += String.fromCharCode(c >= 0x61 && c <= 0x7a ? c - 0x20 : c);
  }
  return name;
}

/** A lump together with the file it lives in. */
export interface LumpRef {
  readonly file: WadFile;
  readonly lump: Lump;
}

export type Namespace = 'flats' | 'patches' | 'sprites';

/**
 * Marker pairs bounding each namespace. The doubled forms (FF_START, PP_START, SS_START) come from
 * PWADs written for DeuTex/vanilla tricks; the numbered ones (F1_START, P2_END, ...) nest inside the
 * outer pair in the IWADs and are just markers. PWADs commonly mix them (FF_START ... F_END).
 */
const NAMESPACE_MARKERS: Record<Namespace, { start: readonly string[]; end: readonly string[]; letter: string }> = {
  flats: { start: ['F_START', 'FF_START'], end: ['F_END', 'FF_END'], letter: 'F' },
  patches: { start: ['P_START', 'PP_START'], end: ['P_END', 'PP_END'], letter: 'P' },
  sprites: { start: ['S_START', 'SS_START'], end: ['S_END', 'SS_END'], letter: 'S' },
};

/** The lumps of one map, all from the file that holds its marker. */
export interface MapLumps {
  readonly info: MapInfo;
  /** A lump of the map by name (THINGS, LINEDEFS, ...), or undefined when the map lacks it. */
  lump(name: string): Uint8Array | undefined;
}

/** Lumps that follow a Doom- or Hexen-format map marker (https://doomwiki.org/wiki/Map_format). */
const MAP_LUMP_NAMES = new Set([
  'THINGS', 'LINEDEFS', 'SIDEDEFS', 'VERTEXES', 'SEGS', 'SSECTORS', 'NODES', 'SECTORS', 'REJECT', 'BLOCKMAP', 'BEHAVIOR', 'SCRIPTS',
]);

interface FoundMap {
  readonly info: MapInfo;
  readonly file: WadFile;
  readonly lumps: ReadonlyMap<string, Lump>;
}

/**
 * An IWAD and the PWADs loaded over it, in load order. As in the game, a later file wins: its lump,
 * flat, patch or map replaces an earlier file's of the same name.
 */
export class WadStack {
  readonly files: readonly WadFile[];
  private readonly byName = new Map<string, LumpRef>();
  private readonly namespaces = new Map<Namespace, Map<string, LumpRef>>();
  /** Per file, the directory indices inside each namespace. */
  private readonly inNamespace = new Map<WadFile, Map<Namespace, Set<number>>>();
  private readonly mapList: FoundMap[];
  /** Maps by name (built on first use). */
  private mapIndex: Map<string, FoundMap> | undefined;
  /** Per file, by name, the last non-empty lump outside its flat namespace (built on first use). */
  private patchIndex: Map<WadFile, Map<string, Lump>> | undefined;

  constructor(files: readonly WadFile[]) {
    this.files = files;
    for (const file of files) for (const lump of file.lumps) this.byName.set(lump.name, { file, lump });
    for (const ns of Object.keys(NAMESPACE_MARKERS) as Namespace[]) {
      const merged = new Map<string, LumpRef>();
      for (const file of files) {
        const indices = namespaceIndices(file, ns);
        let perFile = this.inNamespace.get(file);
        if (!perFile) this.inNamespace.set(file, (perFile = new Map()));
        perFile.set(ns, indices);
        for (const i of indices) {
          const lump = file.lumps[i]!;
          merged.set(lump.name, { file, lump });
        }
      }
      this.namespaces.set(ns, merged);
    }
    this.mapList = orderMaps(files.map(findMaps));
  }

  /** The last lump of that name in any file (the game's W_GetNumForName), or undefined. */
  lump(name: string): Uint8Array | undefined {
    const ref = this.lumpRef(name);
    return ref && ref.file.data(ref.lump);
  }

  lumpRef(name: string): LumpRef | undefined {
    return this.byName.get(name.toUpperCase());
  }

  /** The entries of a namespace merged across files (later files override), in load order. */
  namespace(ns: Namespace): ReadonlyMap<string, LumpRef> {
    return this.namespaces.get(ns)!;
  }

  /**
   * A wall patch by name. Vanilla finds patches with a global lookup, so PWADs often replace them
   * without P_START markers, and textures may use sprites (Freedoom's SLAD10 uses TFOGF0); but a
   * flat, which is not a picture, may share a patch's name. So: the last file that has a lump of
   * that name outside its flat namespace wins, and inside a file a lump between patch markers is
   * preferred.
   */
  patch(name: string): LumpRef | undefined {
    const upper = name.toUpperCase();
    const inPatches = this.namespace('patches').get(upper);
    // Looked up in a per-file index by name: scanning every lump per missing patch took 14 s for a
    // WAD naming 8,000 patches it lacks.
    const index = this.buildPatchIndex();
    for (let f = this.files.length - 1; f >= 0; f--) {
      const file = this.files[f]!;
      if (inPatches?.file === file) return inPatches;
      const lump = index.get(file)!.get(upper);
      if (lump) return { file, lump };
    }
    return undefined;
  }

  private buildPatchIndex(): Map<WadFile, Map<string, Lump>> {
    if (!this.patchIndex) {
      this.patchIndex = new Map<WadFile, Map<string, Lump>>();
      for (const file of this.files) {
        const flats = this.inNamespace.get(file)!.get('flats')!;
        const any = new Map<string, Lump>();
        // In directory order, so a later lump of a name replaces an earlier one: the last one wins, as in the scan it replaces.
        for (const lump of file.lumps) if (lump.size > 0 && !flats.has(lump.index)) any.set(lump.name, lump);
        this.patchIndex.set(file, any);
      }
    }
    return this.patchIndex;
  }

  /**
   * Every map, each name once (a later file's map replaces an earlier one's). The maps of the last
   * file that has any come first, in its directory order, then the remaining maps of earlier files:
   * so the first map of `doom2.wad+mymap.wad` is the PWAD's, which is what a user loading a PWAD
   * without naming a map wants to see.
   */
  maps(): MapInfo[] {
    return this.mapList.map((m) => m.info);
  }

  /** The lumps of a map (name case-insensitive), or undefined when no file has it. */
  mapLumps(name: string): MapLumps | undefined {
    const upper = name.toUpperCase();
    this.mapIndex ??= new Map(this.mapList.map((m) => [m.info.name, m]));
    const found = this.mapIndex.get(upper);
    if (!found) return undefined;
    return {
      info: found.info,
      lump: (lumpName) => {
        const lump = found.lumps.get(lumpName.toUpperCase());
        return lump && found.file.data(lump);
      },
    };
  }

  /** "a.wad" or "a.wad + b.wad", for messages. */
  describe(): string {
    return this.files.map((f) => f.name).join(' + ') || '(no WAD files)';
  }
}

/** Directory indices of the lumps in a namespace: between an outer start and end marker, markers excluded. */
function namespaceIndices(file: WadFile, ns: Namespace): Set<number> {
  const { start, end, letter } = NAMESPACE_MARKERS[ns];
  const nested = new RegExp(`^${letter}{1,2}\\d*_(START|END)$`);
  const indices = new Set<number>();
  let inside = false;
  for (const lump of file.lumps) {
    if (start.includes(lump.name)) inside = true;
    else if (end.includes(lump.name)) inside = false;
    else if (inside && lump.size > 0 && !nested.test(lump.name)) indices.add(lump.index);
  }
  return indices;
}

/**
 * Maps in one file's directory. A map is a marker lump (any name) followed either by the Doom/Hexen
 * map lumps, THINGS among them, or by TEXTMAP ... ENDMAP (UDMF, https://doomwiki.org/wiki/UDMF).
 * A BEHAVIOR lump (ACS bytecode) marks the Hexen format. A later map of the same name in the same
 * file replaces the earlier one.
 */
function findMaps(file: WadFile): FoundMap[] {
  const found = new Map<string, FoundMap>();
  const lumps = file.lumps;
  for (let i = 0; i + 1 < lumps.length; i++) {
    const marker = lumps[i]!;
    const next = lumps[i + 1]!;
    if (MAP_LUMP_NAMES.has(marker.name) || marker.name === 'TEXTMAP' || marker.name === 'ENDMAP') continue;
    const own = new Map<string, Lump>();
    let format: MapFormat;
    let j = i + 1;
    if (next.name === 'TEXTMAP') {
      for (; j < lumps.length && lumps[j]!.name !== 'ENDMAP'; j++) if (!own.has(lumps[j]!.name)) own.set(lumps[j]!.name, lumps[j]!);
      format = 'udmf';
    } else if (MAP_LUMP_NAMES.has(next.name)) {
      for (; j < lumps.length && MAP_LUMP_NAMES.has(lumps[j]!.name) && !own.has(lumps[j]!.name); j++) own.set(lumps[j]!.name, lumps[j]!);
      if (!own.has('THINGS')) continue;
      format = own.has('BEHAVIOR') ? 'hexen' : 'doom';
    } else continue;
    found.delete(marker.name); // re-insert so directory order follows the last definition
    found.set(marker.name, { info: { name: marker.name, format, file: file.name }, file, lumps: own });
    i = j - 1;
  }
  return [...found.values()];
}

function orderMaps(perFile: readonly FoundMap[][]): FoundMap[] {
  const out: FoundMap[] = [];
  const seen = new Set<string>();
  for (let f = perFile.length - 1; f >= 0; f--) {
    for (const m of perFile[f]!) {
      if (seen.has(m.info.name)) continue;
      seen.add(m.info.name);
      out.push(m);
    }
  }
  return out;
}
