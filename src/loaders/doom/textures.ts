/**
 * Wall textures and flats as RGBA images (https://doomwiki.org/wiki/TEXTURE1_and_TEXTURE2,
 * https://doomwiki.org/wiki/PNAMES, https://doomwiki.org/wiki/Flat).
 *
 * - PNAMES: int32 count, then 8-byte patch names. TEXTURE1 (and TEXTURE2 when present): int32
 *   count, int32 offsets, then per texture: name[8], int32 masked, int16 width, int16 height, int32
 *   (unused column directory), int16 patch count, and 10 bytes per patch: int16 x, int16 y, int16
 *   PNAMES index, int16 stepdir and colormap (unused). As in vanilla, the last file's TEXTURE1,
 *   TEXTURE2 and PNAMES are used (a PWAD's lumps replace, not extend, the IWAD's), and for a name
 *   defined twice the first definition wins (R_CheckTextureNumForName scans from the start).
 * - A texture is its patches drawn in order at their origins, clipped to the texture; pixels no
 *   patch covers stay transparent (alpha 0), which masked mid textures need.
 * - Flats are raw palette indices, row-major, between the flat markers; 64×64 normally.
 *
 * Images are composed on first use and memoised. Damage (a missing patch, a corrupt definition)
 * costs a warning and the damaged part; the header of a whole lump being unreadable is an error.
 */
import { LanternError } from '../../errors.ts';
import { Budget } from '../../budgets.ts';
import type { Texture } from '../../scene/types.ts';
import type { DoomImageSource } from './map-types.ts';
import { readPalette, type Palette } from './palette.ts';
import { drawPicture, MAX_PICTURE_PIXELS, readPictureHeader, type PictureHeader } from './picture.ts';
import { readName, type LumpRef, type WadStack } from './wad.ts';

export interface DoomGraphicsOptions {
  onWarning?: (message: string) => void;
}

interface PatchPlacement {
  readonly x: number;
  readonly y: number;
  /** Index into PNAMES. */
  readonly patch: number;
}

interface TextureDefinition {
  readonly name: string;
  readonly width: number;
  readonly height: number;
  readonly patches: readonly PatchPlacement[];
}

/** A patch ready to draw, or why it cannot be. */
type ResolvedPatch = { readonly name: string; readonly bytes: Uint8Array; readonly header: PictureHeader } | { readonly name: string; readonly problem: string };

export class DoomGraphics implements DoomImageSource {
  readonly palette: Palette;
  private readonly stack: WadStack;
  private readonly warn: (message: string) => void;
  private readonly definitions = new Map<string, TextureDefinition>();
  private readonly patchNames: readonly string[];
  private readonly patches = new Map<number, ResolvedPatch>();
  private readonly textures = new Map<string, Texture | undefined>();
  private readonly flats = new Map<string, Texture | undefined>();
  /**
   * Texels composed so far (textures, flats, and the sprites of a SpriteSet given this budget),
   * charged before each image is allocated: a 23 KB WAD can ask for 48 textures of 4096².
   */
  readonly texels = new Budget('textureTexels', 'texture texels');

  constructor(stack: WadStack, options: DoomGraphicsOptions = {}) {
    this.stack = stack;
    this.warn = options.onWarning ?? (() => {});
    this.palette = readPalette(stack);
    const textureLumps = (['TEXTURE1', 'TEXTURE2'] as const).map((n) => stack.lumpRef(n)).filter((r) => r !== undefined);
    const pnames = stack.lumpRef('PNAMES');
    if (textureLumps.length > 0 && !pnames) this.warn(`${stack.describe()}: no PNAMES lump, so no wall textures`);
    this.patchNames = pnames ? readPatchNames(pnames) : [];
    if (!pnames) return;
    for (const ref of textureLumps) {
      for (const def of readTextureLump(ref, this.warn)) if (!this.definitions.has(def.name)) this.definitions.set(def.name, def);
    }
  }

  /** Wall texture names in definition order. */
  textureNames(): string[] {
    return [...this.definitions.keys()];
  }

  /** Flat names in load order. */
  flatNames(): string[] {
    return [...this.stack.namespace('flats').keys()];
  }

  texture(name: string): Texture | undefined {
    const upper = name.toUpperCase();
    if (!this.textures.has(upper)) {
      const def = this.definitions.get(upper);
      this.textures.set(upper, def && this.compose(def));
    }
    return this.textures.get(upper);
  }

  flat(name: string): Texture | undefined {
    const upper = name.toUpperCase();
    if (!this.flats.has(upper)) {
      const ref = this.stack.namespace('flats').get(upper);
      this.flats.set(upper, ref && this.decodeFlat(upper, ref));
    }
    return this.flats.get(upper);
  }

  /**
   * The sky texture the game shows on a map's F_SKY1 surfaces: ExMy uses SKYx (Doom 1, Ultimate
   * Doom's episode 4 included); MAPxx uses SKY1 for maps 1–11, SKY2 for 12–20, SKY3 from 21 (Doom 2,
   * G_DoLoadLevel). Anything else, or a sky the WADs lack, falls back to SKY1.
   */
  sky(mapName: string): Texture | undefined {
    const upper = mapName.toUpperCase();
    const episode = /^E(\d+)M\d+$/.exec(upper);
    const level = /^MAP(\d+)$/.exec(upper);
    let sky = 'SKY1';
    if (episode) sky = `SKY${Number(episode[1])}`;
    else if (level) {
      const n = Number(level[1]);
      sky = n < 12 ? 'SKY1' : n < 21 ? 'SKY2' : 'SKY3';
    }
    return this.texture(sky) ?? this.texture('SKY1');
  }

  private compose(def: TextureDefinition): Texture {
    const { name, width, height } = def;
    this.texels.add(width * height, `texture ${name}, ${width}×${height}`);
    const rgba = new Uint8Array(width * height * 4);
    const target = { width, height, pixels: new Uint32Array(rgba.buffer) };
    for (const placement of def.patches) {
      const patch = this.resolvePatch(placement.patch);
      if ('problem' in patch) {
        this.warn(`texture ${name}: skipped patch ${patch.name}: ${patch.problem}`);
        continue;
      }
      const damage = drawPicture(patch.bytes, patch.header, this.palette, target, placement.x, placement.y);
      if (damage) this.warn(`texture ${name}: patch ${patch.name}: ${damage}`);
    }
    return { name, width, height, rgba };
  }

  private resolvePatch(index: number): ResolvedPatch {
    let resolved = this.patches.get(index);
    if (!resolved) {
      resolved = this.findPatch(index);
      this.patches.set(index, resolved);
    }
    return resolved;
  }

  private findPatch(index: number): ResolvedPatch {
    const name = this.patchNames[index];
    if (name === undefined) return { name: `#${index}`, problem: `PNAMES has no entry ${index} (it has ${this.patchNames.length})` };
    const ref = this.stack.patch(name);
    if (!ref) return { name, problem: 'no such lump in the WADs' };
    const bytes = ref.file.data(ref.lump);
    try {
      return { name, bytes, header: readPictureHeader(bytes, name) };
    } catch (e) {
      if (e instanceof LanternError) return { name, problem: `${e.message} (in ${ref.file.name})` };
      throw e;
    }
  }

  private decodeFlat(name: string, ref: LumpRef): Texture | undefined {
    const bytes = ref.file.data(ref.lump);
    const size = flatSize(bytes.length);
    if (!size) {
      this.warn(`flat ${name} in ${ref.file.name}: ${bytes.length} bytes is not a flat size (64×64 is 4096 bytes); skipped`);
      return undefined;
    }
    const [width, height] = size;
    this.texels.add(width * height, `flat ${name}, ${width}×${height}`);
    const rgba = new Uint8Array(width * height * 4);
    const pixels = new Uint32Array(rgba.buffer);
    const colors = this.palette.packed;
    for (let i = 0; i < pixels.length; i++) pixels[i] = colors[bytes[i]!]!;
    return { name, width, height, rgba };
  }
}

/**
 * Width and height of a flat from its byte count: squares of powers of two (4096 = 64×64, 16384 =
 * 128×128, ... up to 1024×1024), 8192 = 64 wide × 128 tall and Heretic's 4160 (64×64 plus a spare
 * row) as ZDoom reads them; anything else is not a flat.
 */
export function flatSize(bytes: number): [number, number] | undefined {
  if (bytes === 8192) return [64, 128];
  if (bytes === 4160) return [64, 64];
  for (let side = 8; side <= 1024; side *= 2) if (side * side === bytes) return [side, side];
  return undefined;
}

function readPatchNames(ref: LumpRef): string[] {
  const bytes = ref.file.data(ref.lump);
  const count = bytes.length >= 4 ? new DataView(bytes.buffer, bytes.byteOffset, 4).getInt32(0, true) : -1;
  if (count < 0 || 4 + 8 * count > bytes.length) {
    throw new LanternError(`${ref.file.name}: the PNAMES lump is corrupt (${count} names in ${bytes.length} bytes)`, 'the WAD is damaged');
  }
  const names: string[] = [];
  for (let i = 0; i < count; i++) names.push(readName(bytes, 4 + 8 * i));
  return names;
}

/** The texture definitions of one TEXTURE1/TEXTURE2 lump; damaged entries are skipped with a warning. */
function readTextureLump(ref: LumpRef, warn: (message: string) => void): TextureDefinition[] {
  const bytes = ref.file.data(ref.lump);
  const lumpName = `${ref.file.name}: ${ref.lump.name}`;
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const count = bytes.length >= 4 ? view.getInt32(0, true) : -1;
  if (count < 0 || 4 + 4 * count > bytes.length) {
    throw new LanternError(`${lumpName} is corrupt (${count} textures in ${bytes.length} bytes)`, 'the WAD is damaged');
  }
  const out: TextureDefinition[] = [];
  for (let i = 0; i < count; i++) {
    const at = view.getInt32(4 + 4 * i, true);
    if (at < 0 || at + 22 > bytes.length) {
      warn(`${lumpName}: texture ${i} lies outside the lump; skipped`);
      continue;
    }
    const name = readName(bytes, at);
    const width = view.getInt16(at + 12, true);
    const height = view.getInt16(at + 14, true);
    const patchCount = view.getInt16(at + 20, true);
    if (width <= 0 || height <= 0 || width * height > MAX_PICTURE_PIXELS) {
      warn(`${lumpName}: texture ${name} has an invalid size ${width}×${height}; skipped`);
      continue;
    }
    if (patchCount < 0 || at + 22 + 10 * patchCount > bytes.length) {
      warn(`${lumpName}: texture ${name}'s ${patchCount} patches run past the end of the lump; skipped`);
      continue;
    }
    const patches: PatchPlacement[] = [];
    for (let p = 0, q = at + 22; p < patchCount; p++, q += 10) {
      patches.push({ x: view.getInt16(q, true), y: view.getInt16(q + 2, true), patch: view.getInt16(q + 4, true) });
    }
    out.push({ name, width, height, patches });
  }
  return out;
}
