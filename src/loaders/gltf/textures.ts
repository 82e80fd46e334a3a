/**
 * glTF textures → Scene.textures, made on demand by the materials that use them. One glTF image can
 * become two Lantern textures: the encoding ('srgb' for colour, 'linear' for data) belongs to the
 * Lantern texture, and glTF lets the same image serve as both (rare, but legal).
 *
 * An image that is missing or cannot be decoded becomes a 1×1 neutral texture, chosen by what the
 * slot means so the material still renders as if untextured: white for colour and data factors
 * (the factor alone then applies), a flat (0.5, 0.5, 1) for a normal map.
 *
 * Images are known by their bytes: glTF images with the same bytes (a hundred images naming one
 * file or buffer view) are one image, decoded once, and one Lantern texture per encoding. Each
 * texture is charged to the textureTexels budget from the image's header, before it is decoded: a
 * hundred images sharing one 5792² PNG were decoded in full, one by one, before each was refused.
 */
import type { Texture as GltfTexture, TextureInfo } from '@gltf-transform/core';
import type { Transform } from '@gltf-transform/extensions';
import { Budget } from '../../budgets.ts';
import { LanternError } from '../../errors.ts';
import type { Texture, TextureEncoding, TextureRef, UvTransform } from '../../scene/types.ts';
import { readImage, type DecodedImage, type ImageDecodeResult } from './images.ts';
import type { Warnings } from './warnings.ts';

/** What a texture slot holds, which decides its encoding and its fallback. */
export type TextureUse = 'color' | 'data' | 'normal';

const FALLBACK: Record<TextureUse, readonly [number, number, number, number]> = {
  color: [255, 255, 255, 255],
  data: [255, 255, 255, 255],
  normal: [128, 128, 255, 255],
};

export class TextureTable {
  readonly textures: Texture[] = [];
  private readonly byKey = new Map<string, number>();
  private readonly gltfIndex: Map<GltfTexture, number>;

  constructor(
    gltfTextures: readonly GltfTexture[],
    private readonly imageNames: readonly string[],
    private readonly imageMissing: readonly boolean[],
    private readonly warnings: Warnings,
  ) {
    this.gltfIndex = new Map(gltfTextures.map((t, i) => [t, i]));
  }

  /** A TextureRef for one material slot, or undefined when the slot is empty. */
  ref(texture: GltfTexture | null, info: TextureInfo | null, use: TextureUse, materialName: string): TextureRef | undefined {
    if (!texture || !info) return undefined;
    const index = this.textureFor(texture, use, materialName);
    const transform = info.getExtension<Transform>('KHR_texture_transform');
    // KHR_texture_transform's texCoord, when present, overrides the textureInfo's.
    const texCoord = transform?.getTexCoord() ?? info.getTexCoord();
    if (texCoord > 1) this.warnings.add(`material '${materialName}' uses TEXCOORD_${texCoord}; only sets 0 and 1 are supported, set 0 is used`);
    const uv: UvTransform | undefined = transform ? { offset: [...transform.getOffset()], rotation: transform.getRotation(), scale: [...transform.getScale()] } : undefined;
    return { texture: index, ...(texCoord === 1 ? { texCoord: 1 as const } : {}), ...(uv && !isIdentityTransform(uv) ? { transform: uv } : {}) };
  }

  /**
   * Counts an image of width × height against the textureTexels limit (each image is held to
   * imagePixels by its decoder); past it the image is dropped and the reason returned.
   */
  private chargeTexels(width: number, height: number, imageName: string): string | undefined {
    try {
      this.texels.add(width * height, `${imageName}, ${width}×${height}`);
      return undefined;
    } catch (e) {
      if (e instanceof LanternError) return e.message;
      throw e;
    }
  }

  private readonly texels = new Budget('textureTexels', 'texture texels');
  /** Image bytes seen so far, by a key cheap to compute (length and both ends), each with its id and, once decoded, its pixels. */
  private readonly images = new Map<string, Array<{ readonly bytes: Uint8Array; readonly id: number; decoded?: ImageDecodeResult }>>();
  private imageCount = 0;

  /** The image with these bytes (the same entry for equal bytes, wherever they came from). */
  private imageOf(bytes: Uint8Array): { readonly bytes: Uint8Array; readonly id: number; decoded?: ImageDecodeResult } {
    const key = `${bytes.length}:${hashBytes(bytes.subarray(0, 4096))}:${hashBytes(bytes.subarray(-4096))}`;
    const candidates = this.images.get(key) ?? [];
    const found = candidates.find((c) => sameBytes(c.bytes, bytes));
    if (found) return found;
    const image = { bytes, id: this.imageCount++ };
    candidates.push(image);
    this.images.set(key, candidates);
    return image;
  }

  private textureFor(texture: GltfTexture, use: TextureUse, materialName: string): number {
    const i = this.gltfIndex.get(texture) ?? -1;
    const encoding: TextureEncoding = use === 'color' ? 'srgb' : 'linear';
    const imageName = this.imageNames[i] ?? texture.getName() ?? `texture ${i}`;
    const bytes = this.imageMissing[i] ? undefined : texture.getImage();
    const image = bytes && bytes.length > 0 ? this.imageOf(bytes) : undefined;
    const key = `${image ? image.id : `gltf ${i}`}:${encoding}:${use === 'normal' ? 'n' : ''}`;
    const known = this.byKey.get(key);
    if (known !== undefined) return known;

    let decoded: DecodedImage | undefined;
    if (this.imageMissing[i]) {
      this.warnings.missingFile(imageName, 'textures that use it are replaced by neutral ones');
    } else {
      // The size from the header is charged first; only an image within the budget is decoded.
      const source = image ? readImage(image.bytes, imageName) : { ok: false as const, reason: 'it is empty' };
      let refused = source.ok ? this.chargeTexels(source.width, source.height, imageName) : source.reason;
      if (source.ok && !refused) {
        const result = (image!.decoded ??= source.decode());
        if (result.ok) decoded = result.image;
        else refused = result.reason;
      }
      if (refused) this.warnings.add(`texture ${imageName} (material '${materialName}') is replaced by a neutral one: ${refused}`);
    }
    const name = encoding === 'linear' && use !== 'normal' ? `${imageName} (linear)` : use === 'normal' ? `${imageName} (normal)` : imageName;
    const out: Texture = decoded
      ? { name, width: decoded.width, height: decoded.height, rgba: decoded.rgba, encoding }
      : { name: `${name} (fallback)`, width: 1, height: 1, rgba: new Uint8Array(FALLBACK[use]), encoding };
    const index = this.textures.length;
    this.textures.push(out);
    this.byKey.set(key, index);
    return index;
  }
}

const isIdentityTransform = (t: UvTransform): boolean =>
  t.offset[0] === 0 && t.offset[1] === 0 && t.rotation === 0 && t.scale[0] === 1 && t.scale[1] === 1;

/** FNV-1a over a few kilobytes: a key for finding images with equal bytes, confirmed by comparing them. */
function hashBytes(bytes: Uint8Array): number {
  let h = 0x811c9dc5;
  for (let i = 0; i < bytes.length; i++) h = Math.imul(h ^ bytes[i]!, 0x01000193);
  return h >>> 0;
}

/** Byte equality, four bytes at a time where both arrays allow it (a thousand copies of one image are compared whole). */
function sameBytes(a: Uint8Array, b: Uint8Array): boolean {
  if (a === b) return true;
  if (a.length !== b.length) return false;
  let i = 0;
  if (a.byteOffset % 4 === 0 && b.byteOffset % 4 === 0) {
    const words = a.length >> 2;
    const [wa, wb] = [new Uint32Array(a.buffer, a.byteOffset, words), new Uint32Array(b.buffer, b.byteOffset, words)];
    for (let w = 0; w < words; w++) if (wa[w] !== wb[w]) return false;
    i = words * 4;
  }
  for (; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}
