/**
 * Test helper: builds small, complete WAD files in code, so tests of the Doom loaders need no binary
 * fixtures. Encodes the same on-disk layouts the loaders read (https://doomwiki.org/wiki/WAD,
 * https://doomwiki.org/wiki/Map_format, https://doomwiki.org/wiki/Picture_format,
 * https://doomwiki.org/wiki/TEXTURE1_and_TEXTURE2, https://doomwiki.org/wiki/PNAMES).
 * Used only by tests; it throws plain Errors because a bad argument here is a bug in a test.
 */
import type { DoomMap, Linedef, MapVertex, Sector, Sidedef, Thing } from './map-types.ts';
import { LINEDEF_FLAGS, NO_SIDEDEF } from './map-types.ts';

/** Little-endian byte writer that grows as needed. */
class ByteWriter {
  private buf = new Uint8Array(64);
  private view = new DataView(this.buf.buffer);
  length = 0;

  /**
   * Room for n more bytes; returns where they start. It may replace buf and view, so callers call
   * it before reading either (`this.view.setX(this.reserve(n), ...)` would write to the old view).
   */
  private reserve(n: number): number {
    const at = this.length;
    if (at + n > this.buf.length) {
      const bigger = new Uint8Array(Math.max(this.buf.length * 2, at + n));
      bigger.set(this.buf);
      this.buf = bigger;
      this.view = new DataView(bigger.buffer);
    }
    this.length += n;
    return at;
  }

  u8(v: number): this {
    const at = this.reserve(1);
    this.view.setUint8(at, v);
    return this;
  }
  i16(v: number): this {
    const at = this.reserve(2);
    this.view.setInt16(at, v, true);
    return this;
  }
  u16(v: number): this {
    const at = this.reserve(2);
    this.view.setUint16(at, v, true);
    return this;
  }
  i32(v: number): this {
    const at = this.reserve(4);
    this.view.setInt32(at, v, true);
    return this;
  }
  /** An 8-byte, NUL-padded name. */
  name8(name: string): this {
    if (name.length > 8) throw new Error(`test-wad: name '${name}' is longer than 8 characters`);
    const at = this.reserve(8);
    for (let i = 0; i < name.length; i++) this.buf[at + i] = name.charCodeAt(i) & 0xff;
    return this;
  }
  bytes(b: Uint8Array): this {
    const at = this.reserve(b.length);
    this.buf.set(b, at);
    return this;
  }
  /** Overwrites a 32-bit value already written. */
  patchI32(at: number, v: number): void {
    this.view.setInt32(at, v, true);
  }
  result(): Uint8Array {
    return this.buf.slice(0, this.length);
  }
}

/** Assembles a WAD: header, then the lump data in order, then the directory (as id's tools did). */
export class WadBuilder {
  private readonly entries: Array<{ name: string; bytes: Uint8Array }> = [];

  /** Appends a lump. Names are written as given (the reader upper-cases them). */
  lump(name: string, bytes: Uint8Array): this {
    this.entries.push({ name, bytes });
    return this;
  }

  /** Appends a zero-length marker lump (map markers, F_START, P_END, ...). */
  marker(name: string): this {
    return this.lump(name, new Uint8Array(0));
  }

  /** Appends several lumps, e.g. the output of encodeMap. */
  lumps(entries: Iterable<readonly [string, Uint8Array]>): this {
    for (const [name, bytes] of entries) this.lump(name, bytes);
    return this;
  }

  build(kind: 'IWAD' | 'PWAD' = 'PWAD'): Uint8Array {
    const w = new ByteWriter();
    for (const c of kind) w.u8(c.charCodeAt(0));
    w.i32(this.entries.length);
    w.i32(0); // directory offset, patched below
    const offsets: number[] = [];
    for (const e of this.entries) {
      offsets.push(e.bytes.length > 0 ? w.length : 0);
      w.bytes(e.bytes);
    }
    w.patchI32(8, w.length);
    this.entries.forEach((e, i) => w.i32(offsets[i]!).i32(e.bytes.length).name8(e.name));
    return w.result();
  }
}

// ---- map lumps (https://doomwiki.org/wiki/Map_format) ----

export function encodeVertexes(vertices: readonly MapVertex[]): Uint8Array {
  const w = new ByteWriter();
  for (const v of vertices) w.i16(v.x).i16(v.y);
  return w.result();
}

/** NO_SIDEDEF is written as 0xFFFF. */
export function encodeLinedefs(linedefs: readonly Linedef[]): Uint8Array {
  const w = new ByteWriter();
  const side = (s: number) => (s === NO_SIDEDEF ? 0xffff : s);
  for (const l of linedefs) w.u16(l.v1).u16(l.v2).i16(l.flags).i16(l.special).i16(l.tag).u16(side(l.front)).u16(side(l.back));
  return w.result();
}

export function encodeSidedefs(sidedefs: readonly Sidedef[]): Uint8Array {
  const w = new ByteWriter();
  for (const s of sidedefs) w.i16(s.xOffset).i16(s.yOffset).name8(s.upper).name8(s.lower).name8(s.middle).u16(s.sector);
  return w.result();
}

export function encodeSectors(sectors: readonly Sector[]): Uint8Array {
  const w = new ByteWriter();
  for (const s of sectors) {
    w.i16(s.floorHeight).i16(s.ceilingHeight).name8(s.floorFlat).name8(s.ceilingFlat).i16(s.lightLevel).i16(s.special).i16(s.tag);
  }
  return w.result();
}

export function encodeThings(things: readonly Thing[]): Uint8Array {
  const w = new ByteWriter();
  for (const t of things) w.i16(t.x).i16(t.y).i16(t.angle).i16(t.type).i16(t.flags);
  return w.result();
}

/** The marker and the ten lumps of a Doom-format map, in the vanilla order; the node lumps are empty. */
export function encodeMap(map: DoomMap): Array<[string, Uint8Array]> {
  const empty = new Uint8Array(0);
  return [
    [map.name, empty],
    ['THINGS', encodeThings(map.things)],
    ['LINEDEFS', encodeLinedefs(map.linedefs)],
    ['SIDEDEFS', encodeSidedefs(map.sidedefs)],
    ['VERTEXES', encodeVertexes(map.vertices)],
    ['SEGS', empty],
    ['SSECTORS', empty],
    ['NODES', empty],
    ['SECTORS', encodeSectors(map.sectors)],
    ['REJECT', empty],
    ['BLOCKMAP', empty],
  ];
}

export type MapPoint = readonly [number, number];

/**
 * Builds maps as plain objects for the geometry tests: sectors, and lines whose front (right) and
 * back sidedefs name them. One-sided lines are impassable (flag 1) with a middle texture 'WALL';
 * two-sided lines carry TWO_SIDED and upper/lower 'WALL'. Sectors default to floor 0, ceiling 128,
 * FLOOR4_8 / CEIL3_5, light 255.
 */
export class MapBuilder {
  readonly vertices: MapVertex[] = [];
  readonly linedefs: Linedef[] = [];
  readonly sidedefs: Sidedef[] = [];
  readonly sectors: Sector[] = [];
  readonly things: Thing[] = [];

  sector(props: Partial<Sector> = {}): number {
    return this.sectors.push({ floorHeight: 0, ceilingHeight: 128, floorFlat: 'FLOOR4_8', ceilingFlat: 'CEIL3_5', lightLevel: 255, special: 0, tag: 0, ...props }) - 1;
  }

  /** A line from a to b; `front` and `back` are sector indices (absent: no sidedef on that side). */
  line(a: MapPoint, b: MapPoint, front?: number, back?: number, sides: Partial<Sidedef> = {}, flags = 0): void {
    const side = (sector?: number) =>
      sector === undefined ? NO_SIDEDEF : this.sidedefs.push({ xOffset: 0, yOffset: 0, upper: 'WALL', lower: 'WALL', middle: back === undefined ? 'WALL' : '-', sector, ...sides }) - 1;
    const vertex = (p: MapPoint) => this.vertices.push({ x: p[0], y: p[1] }) - 1;
    const kind = back === undefined ? LINEDEF_FLAGS.BLOCKING : LINEDEF_FLAGS.TWO_SIDED;
    this.linedefs.push({ v1: vertex(a), v2: vertex(b), flags: flags | kind, special: 0, tag: 0, front: side(front), back: side(back) });
  }

  /** Lines along the points and back to the first. */
  loop(points: readonly MapPoint[], front?: number, back?: number, sides: Partial<Sidedef> = {}, flags = 0): void {
    points.forEach((p, i) => this.line(p, points[(i + 1) % points.length]!, front, back, sides, flags));
  }

  player(x: number, y: number, angle: number): void {
    this.things.push({ x, y, angle, type: 1, flags: 7 });
  }

  build(name = 'TEST'): DoomMap {
    return { name, vertices: this.vertices, linedefs: this.linedefs, sidedefs: this.sidedefs, sectors: this.sectors, things: this.things };
  }
}

/** A rectangle clockwise (north first): its inside is on the right, where front sidedefs face. */
export const cw = (x: number, y: number, w: number, h = w): MapPoint[] => [[x, y], [x, y + h], [x + w, y + h], [x + w, y]];
/** The same rectangle counter-clockwise: front sidedefs face out (a pillar's faces). */
export const ccw = (x: number, y: number, w: number, h = w): MapPoint[] => cw(x, y, w, h).reverse();

/**
 * Two rooms (x 0..128 and 144..272, y 0..128) joined by a 16-unit sector between them (x 128..144):
 * a door (manual special 1 on both faces) or a lift (walk-over 88 on room A's edge, tag 1).
 * The door faces are upper-unpegged on one side, offset on the other; the jambs lower-unpegged.
 * Player start in room A, facing east (toward the door).
 */
export function twoRooms(middle: Partial<Sector>, kind: 'door' | 'lift', roomB: Partial<Sector> = {}): DoomMap {
  const m = new MapBuilder();
  const a = m.sector();
  const door = m.sector({ floorHeight: 0, ceilingHeight: 0, ...middle });
  const b = m.sector(roomB);
  const line = (p: MapPoint, q: MapPoint, front: number, back?: number, sides = {}, flags = 0) => m.line(p, q, front, back, sides, flags);
  line([0, 0], [0, 128], a);
  line([0, 128], [128, 128], a);
  line([128, 0], [0, 0], a);
  line([128, 128], [128, 0], a, door, { upper: 'DOOR', yOffset: 5 });
  line([128, 128], [144, 128], door, undefined, { middle: 'JAMB' }, LINEDEF_FLAGS.LOWER_UNPEGGED);
  line([144, 0], [128, 0], door, undefined, { middle: 'JAMB' }, LINEDEF_FLAGS.LOWER_UNPEGGED);
  line([144, 0], [144, 128], b, door, { upper: 'DOOR', lower: 'WALL' }, LINEDEF_FLAGS.UPPER_UNPEGGED);
  line([144, 128], [272, 128], b);
  line([272, 128], [272, 0], b);
  line([272, 0], [144, 0], b);
  if (kind === 'door') {
    for (const i of [3, 6]) m.linedefs[i] = { ...m.linedefs[i]!, special: 1 };
  } else {
    m.sectors[door] = { ...m.sectors[door]!, tag: 1 };
    m.linedefs[3] = { ...m.linedefs[3]!, special: 88, tag: 1 };
  }
  m.player(64, 64, 0);
  return m.build();
}

/**
 * A one-sector square room, `size` units on a side, with the player 1 start in the middle: the
 * smallest map the geometry builders can turn into a scene. Walls use STARTAN3, floor FLOOR4_8,
 * ceiling CEIL3_5 (Doom names; provide them in the WAD if a test composes images).
 */
export function squareRoom(name = 'MAP01', size = 256): DoomMap {
  const vertices = [
    { x: 0, y: 0 },
    { x: 0, y: size },
    { x: size, y: size },
    { x: size, y: 0 },
  ];
  // Clockwise around the room, so the front (right) side of every line faces inward.
  const linedefs: Linedef[] = [0, 1, 2, 3].map((i) => ({
    v1: i, v2: (i + 1) % 4, flags: 1, special: 0, tag: 0, front: i, back: NO_SIDEDEF,
  }));
  const sidedefs: Sidedef[] = [0, 1, 2, 3].map(() => ({ xOffset: 0, yOffset: 0, upper: '-', lower: '-', middle: 'STARTAN3', sector: 0 }));
  const sectors: Sector[] = [{ floorHeight: 0, ceilingHeight: 128, floorFlat: 'FLOOR4_8', ceilingFlat: 'CEIL3_5', lightLevel: 160, special: 0, tag: 0 }];
  const things: Thing[] = [{ x: size / 2, y: size / 2, angle: 90, type: 1, flags: 7 }];
  return { name, vertices, linedefs, sidedefs, sectors, things };
}

// ---- graphics ----

/** A distinctive colour per palette index, so tests can tell indices apart in decoded RGBA. */
export function testPaletteColor(index: number): [number, number, number] {
  return [index, 255 - index, (index * 37) & 0xff];
}

/**
 * A PLAYPAL lump: `colors` (default: testPaletteColor for all 256 indices, missing entries black)
 * as palette 0, repeated 14 times like the real lump (the loader reads only the first).
 */
export function encodePalette(colors?: ReadonlyArray<readonly [number, number, number]>): Uint8Array {
  const one = new Uint8Array(768);
  for (let i = 0; i < 256; i++) {
    const c = colors ? colors[i] : testPaletteColor(i);
    if (c) one.set(c, i * 3);
  }
  const out = new Uint8Array(768 * 14);
  for (let p = 0; p < 14; p++) out.set(one, p * 768);
  return out;
}

export interface PatchOptions {
  readonly leftOffset?: number;
  readonly topOffset?: number;
}

/**
 * A picture-format lump (patch or sprite) from palette indices, row-major, -1 = transparent.
 * Runs of opaque pixels become posts of at most 128 pixels. Posts starting below row 254 use the
 * tall-patch convention (a topdelta not above the current top is relative to it), with empty
 * stepping posts where needed, so tall pictures round-trip too.
 */
export function encodePatch(width: number, height: number, pixels: ArrayLike<number>, options: PatchOptions = {}): Uint8Array {
  if (pixels.length !== width * height) throw new Error(`test-wad: ${pixels.length} pixels for a ${width}×${height} patch`);
  const columns: Uint8Array[] = [];
  for (let x = 0; x < width; x++) {
    const c = new ByteWriter();
    let top = -1; // the decoder's running top, as in the tall-patch rule
    const post = (start: number, length: number) => {
      if (start > top && start <= 254) c.u8(start);
      else {
        if (top < 254) {
          c.u8(254).u8(0).u8(0).u8(0); // empty absolute post at 254: from here on, every topdelta is relative
          top = 254;
        }
        while (start - top > 254) {
          c.u8(254).u8(0).u8(0).u8(0);
          top += 254;
        }
        c.u8(start - top);
      }
      top = start;
      c.u8(length).u8(0);
      for (let y = start; y < start + length; y++) c.u8(pixels[y * width + x]!);
      c.u8(0);
    };
    let y = 0;
    while (y < height) {
      if (pixels[y * width + x]! < 0) {
        y++;
        continue;
      }
      const start = y;
      while (y < height && y - start < 128 && pixels[y * width + x]! >= 0) y++;
      post(start, y - start);
    }
    c.u8(0xff);
    columns.push(c.result());
  }
  const w = new ByteWriter().i16(width).i16(height).i16(options.leftOffset ?? 0).i16(options.topOffset ?? 0);
  let offset = 8 + 4 * width;
  for (const c of columns) {
    w.i32(offset);
    offset += c.length;
  }
  for (const c of columns) w.bytes(c);
  return w.result();
}

export function encodePnames(names: readonly string[]): Uint8Array {
  const w = new ByteWriter().i32(names.length);
  for (const n of names) w.name8(n);
  return w.result();
}

export interface TextureDefinition {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  readonly masked?: boolean;
  /** `patch` indexes PNAMES; (x, y) is the patch's top-left corner in the texture. */
  readonly patches: ReadonlyArray<{ readonly x: number; readonly y: number; readonly patch: number }>;
}

/** A TEXTURE1/TEXTURE2 lump in the Doom layout (22-byte header per texture, 10 bytes per patch). */
export function encodeTextureLump(textures: readonly TextureDefinition[]): Uint8Array {
  const w = new ByteWriter().i32(textures.length);
  let offset = 4 + 4 * textures.length;
  for (const t of textures) {
    w.i32(offset);
    offset += 22 + 10 * t.patches.length;
  }
  for (const t of textures) {
    w.name8(t.name).i32(t.masked ? 1 : 0).i16(t.width).i16(t.height).i32(0).i16(t.patches.length);
    for (const p of t.patches) w.i16(p.x).i16(p.y).i16(p.patch).i16(1).i16(0);
  }
  return w.result();
}

/** A flat: `fill` repeated, or the given indices; 64×64 unless another byte count is asked for. */
export function encodeFlat(fill: number | ArrayLike<number>, size = 4096): Uint8Array {
  const out = new Uint8Array(size);
  if (typeof fill === 'number') out.fill(fill);
  else out.set(Array.from(fill).slice(0, size));
  return out;
}

/**
 * A complete little IWAD around squareRoom: PLAYPAL (testPaletteColor), the room's map, the wall
 * texture STARTAN3 (64×128, one 64×128 patch WALLPAT of index 100 + x % 4, a transparent 4×4 hole
 * at its top-left corner) and SKY1 (256×128, patch SKYPAT of index 200), the flats FLOOR4_8 (all
 * 10), CEIL3_5 (all 20) and F_SKY1 (all 30) between F_START and F_END, patches between P_START and
 * P_END. Enough to run the whole Doom pipeline in a test.
 */
export function squareRoomWad(mapName = 'MAP01', kind: 'IWAD' | 'PWAD' = 'IWAD'): Uint8Array {
  return squareRoomsWad([{ name: mapName }], kind);
}

/** Like squareRoomWad, with one square room map per entry (sizes default to 256 units). */
export function squareRoomsWad(maps: readonly { name: string; size?: number }[], kind: 'IWAD' | 'PWAD' = 'IWAD'): Uint8Array {
  const builder = new WadBuilder().lump('PLAYPAL', encodePalette());
  for (const m of maps) builder.lumps(encodeMap(squareRoom(m.name, m.size)));
  const wall = Array.from({ length: 64 * 128 }, (_, i) => (i % 64 < 4 && i < 64 * 4 ? -1 : 100 + ((i % 64) % 4)));
  const sky = new Array<number>(256 * 128).fill(200);
  return builder
    .lump('PNAMES', encodePnames(['WALLPAT', 'SKYPAT']))
    .lump('TEXTURE1', encodeTextureLump([
      { name: 'STARTAN3', width: 64, height: 128, patches: [{ x: 0, y: 0, patch: 0 }] },
      { name: 'SKY1', width: 256, height: 128, patches: [{ x: 0, y: 0, patch: 1 }] },
    ]))
    .marker('P_START')
    .lump('WALLPAT', encodePatch(64, 128, wall))
    .lump('SKYPAT', encodePatch(256, 128, sky))
    .marker('P_END')
    .marker('F_START')
    .lump('FLOOR4_8', encodeFlat(10))
    .lump('CEIL3_5', encodeFlat(20))
    .lump('F_SKY1', encodeFlat(30))
    .marker('F_END')
    .build(kind);
}

export interface AnimatedRoomOptions {
  /** Sector 0's special (default 12, a slow strobe in sync). */
  readonly special?: number;
  /** Whether the WAD has NUKAGE3, the last frame of the NUKAGE cycle (default true). */
  readonly withNukage3?: boolean;
  /** A BOOM ANIMATED lump to include. */
  readonly animated?: Uint8Array;
}

/**
 * A little IWAD for the animation tests (animations.ts): sector 0 (light 160, special `special`),
 * 256 units square, floored with NUKAGE2 under a CEIL1_2 lamp, around sector 1 (64 units square,
 * light 96, floor 16, floor and ceiling CEIL3_5). Its west wall (linedef 0, front side facing east)
 * scrolls (special 48). STARTAN3 (64×128) has vertical stripes of palette index 100 + x % 4. The
 * player stands at (224, 128) looking west. Flats in WAD order: NUKAGE1 (41), NUKAGE2 (42),
 * FLOOR4_8 (10), NUKAGE3 (43), CEIL3_5 (20), CEIL1_2 (250): FLOOR4_8, between NUKAGE1 and NUKAGE3,
 * joins the NUKAGE cycle, as it would in Doom.
 */
export function animatedRoomWad(options: AnimatedRoomOptions = {}): Uint8Array {
  const b = new MapBuilder();
  const walls = { upper: 'STARTAN3', lower: 'STARTAN3', middle: 'STARTAN3' };
  const s0 = b.sector({ lightLevel: 160, special: options.special ?? 12, floorFlat: 'NUKAGE2', ceilingFlat: 'CEIL1_2' });
  const s1 = b.sector({ lightLevel: 96, floorHeight: 16, floorFlat: 'CEIL3_5' });
  b.loop(cw(0, 0, 256), s0, undefined, walls);
  b.loop(ccw(96, 96, 64), s0, s1, { ...walls, middle: '-' });
  b.linedefs[0] = { ...b.linedefs[0]!, special: 48 };
  b.player(224, 128, 180);
  const stripes = Array.from({ length: 64 * 128 }, (_, i) => 100 + ((i % 64) % 4));
  const wad = new WadBuilder()
    .lump('PLAYPAL', encodePalette())
    .lumps(encodeMap(b.build('MAP01')))
    .lump('PNAMES', encodePnames(['WALLPAT']))
    .lump('TEXTURE1', encodeTextureLump([{ name: 'STARTAN3', width: 64, height: 128, patches: [{ x: 0, y: 0, patch: 0 }] }]))
    .marker('P_START')
    .lump('WALLPAT', encodePatch(64, 128, stripes))
    .marker('P_END')
    .marker('F_START')
    .lump('NUKAGE1', encodeFlat(41))
    .lump('NUKAGE2', encodeFlat(42))
    .lump('FLOOR4_8', encodeFlat(10));
  if (options.withNukage3 ?? true) wad.lump('NUKAGE3', encodeFlat(43));
  wad.lump('CEIL3_5', encodeFlat(20)).lump('CEIL1_2', encodeFlat(250)).marker('F_END');
  if (options.animated) wad.lump('ANIMATED', options.animated);
  return wad.build('IWAD');
}
