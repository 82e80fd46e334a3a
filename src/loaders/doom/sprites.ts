/**
 * Sprites (https://doomwiki.org/wiki/Sprite): the pictures between S_START and S_END (or SS_START and
 * SS_END) of the WAD stack, a later WAD's lump replacing an earlier one of the same name. A lump's
 * name says what it shows: `NNNNFR` or `NNNNFRfr`, a four-character sprite name, a frame letter
 * (A, B, ...), a rotation digit (0: seen the same from every angle; 1–8: seen from in front, then
 * every 45° around), and optionally a second frame and rotation that use the same picture mirrored
 * (TROOA2A8: frame A seen from rotation 2, and mirrored from rotation 8). R_InitSpriteDefs reads
 * them so. Pictures decode with picture.ts; their left and top offsets place them on the thing.
 */
import { LanternError } from '../../errors.ts';
import type { Palette } from './palette.ts';
import type { Budget } from '../../budgets.ts';
import { decodePicture, readPictureHeader, type Picture } from './picture.ts';
import type { WadStack } from './wad.ts';

export interface SpriteLumpName {
  readonly sprite: string;
  readonly frame: string;
  /** 0 (every angle) or 1–8. */
  readonly rotation: number;
  /** The frame and rotation that show this picture mirrored. */
  readonly mirror?: { readonly frame: string; readonly rotation: number };
}

/** Frame letters run from A; vanilla allows 29 frames (A to ']'). */
const FRAME = /^[A-Z[\\\]]$/;

/** The parts of a sprite lump's name, or undefined when the name is not one. */
export function parseSpriteLumpName(name: string): SpriteLumpName | undefined {
  if (name.length !== 6 && name.length !== 8) return undefined;
  const rotationOf = (c: string) => (c >= '0' && c <= '8' ? Number(c) : undefined);
  const frame = name[4]!;
  const rotation = rotationOf(name[5]!);
  if (!FRAME.test(frame) || rotation === undefined) return undefined;
  const sprite = name.slice(0, 4);
  if (name.length === 6) return { sprite, frame, rotation };
  const frame2 = name[6]!;
  const rotation2 = rotationOf(name[7]!);
  if (!FRAME.test(frame2) || rotation2 === undefined) return undefined;
  return { sprite, frame, rotation, mirror: { frame: frame2, rotation: rotation2 } };
}

/** Where one rotation of a frame comes from: a lump, maybe mirrored. */
export interface SpriteView {
  readonly lump: string;
  readonly mirrored: boolean;
}

/** A frame of a sprite: one view for every angle (rotation 0) or eight (rotations 1–8 in order). */
export interface SpriteFrame {
  readonly views: readonly SpriteView[];
}

/** Where the scene builder gets sprites from (implemented by SpriteSet; tests may stub it). */
export interface SpriteSource {
  /** Frame `frame` of sprite `sprite`, or undefined when the WADs lack it or it is incomplete. */
  frame(sprite: string, frame: string): SpriteFrame | undefined;
  /** A sprite lump's picture, or undefined when it cannot be read (a warning says why). */
  picture(lump: string): Picture | undefined;
}

interface Slot {
  view: SpriteView;
  /** Load order of the file it comes from: rotation 0 from a later file replaces rotations 1–8. */
  file: number;
}

/** The sprites of a WAD stack, indexed by sprite and frame; pictures decoded on first use. */
export class SpriteSet implements SpriteSource {
  /** sprite + frame -> slots 0..8 (rotation 0 and 1–8). */
  private readonly frames = new Map<string, (Slot | undefined)[]>();
  private readonly pictures = new Map<string, Picture | undefined>();
  private readonly resolved = new Map<string, SpriteFrame | undefined>();
  private readonly warned = new Set<string>();

  constructor(
    private readonly stack: WadStack,
    private readonly palette: Palette,
    private readonly warn: (message: string) => void = () => {},
    /** Shared with the textures (DoomGraphics.texels) so one budget bounds every picture of a load. */
    private readonly texels?: Budget,
  ) {
    for (const [name, ref] of stack.namespace('sprites')) {
      const parsed = parseSpriteLumpName(name);
      if (!parsed) continue;
      const file = stack.files.indexOf(ref.file);
      this.put(parsed.sprite, parsed.frame, parsed.rotation, { view: { lump: name, mirrored: false }, file });
      if (parsed.mirror) this.put(parsed.sprite, parsed.mirror.frame, parsed.mirror.rotation, { view: { lump: name, mirrored: true }, file });
    }
  }

  /** Sprite names in the stack. */
  spriteNames(): string[] {
    return [...new Set([...this.frames.keys()].map((k) => k.slice(0, 4)))];
  }

  frame(sprite: string, frame: string): SpriteFrame | undefined {
    const key = sprite + frame;
    if (!this.resolved.has(key)) this.resolved.set(key, this.resolve(sprite, frame));
    return this.resolved.get(key);
  }

  picture(lump: string): Picture | undefined {
    if (!this.pictures.has(lump)) {
      const ref = this.stack.namespace('sprites').get(lump);
      let picture: Picture | undefined;
      if (ref) {
        try {
          const bytes = ref.file.data(ref.lump);
          const header = readPictureHeader(bytes, lump);
          this.texels?.add(header.width * header.height, `sprite ${lump}, ${header.width}×${header.height}`);
          picture = decodePicture(bytes, lump, this.palette, this.warn);
        } catch (e) {
          if (!(e instanceof LanternError)) throw e;
          this.warn(`sprite ${lump} in ${ref.file.name}: ${e.message}; not drawn`);
        }
      }
      this.pictures.set(lump, picture);
    }
    return this.pictures.get(lump);
  }

  private put(sprite: string, frame: string, rotation: number, slot: Slot): void {
    const key = sprite + frame;
    let slots = this.frames.get(key);
    if (!slots) this.frames.set(key, (slots = new Array<Slot | undefined>(9).fill(undefined)));
    slots[rotation] = slot;
  }

  private resolve(sprite: string, frame: string): SpriteFrame | undefined {
    const slots = this.frames.get(sprite + frame);
    if (!slots) return undefined;
    const zero = slots[0];
    const eight = slots.slice(1);
    const complete = eight.every((s) => s !== undefined);
    const latest = Math.max(...eight.map((s) => s?.file ?? -1));
    // A PWAD that gives a frame one picture for all angles replaces the IWAD's eight (and the reverse).
    if (zero && (!complete || zero.file >= latest)) return { views: [zero.view] };
    if (complete) return { views: eight.map((s) => s!.view) };
    const missing = eight.flatMap((s, i) => (s ? [] : [i + 1]));
    const key = sprite + frame;
    if (!this.warned.has(key)) {
      this.warned.add(key);
      this.warn(`sprite ${sprite} frame ${frame} lacks rotation(s) ${missing.join(', ')}; not drawn`);
    }
    return undefined;
  }
}
