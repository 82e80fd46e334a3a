/**
 * glTF textures → Scene.textures, made on demand by the materials that use them. One glTF image can
 * become two Lantern textures: the encoding ('srgb' for colour, 'linear' for data) belongs to the
 * Lantern texture, and glTF lets the same image serve as both (rare, but legal).
 *
 * An image that is missing or cannot be decoded becomes a 1×1 neutral texture, chosen by what the
 * slot means so the material still renders as if untextured: white for colour and data factors
 * (the factor alone then applies), a flat (0.5, 0.5, 1) for a normal map.
 */
import type { Texture as GltfTexture, TextureInfo } from '@gltf-transform/core';
import type { Transform } from '@gltf-transform/extensions';
import { Budget } from '../../budgets.ts';
import { LanternError } from '../../errors.ts';
import type { Texture, TextureEncoding, TextureRef, UvTransform } from '../../scene/types.ts';
import { decodeImage, type DecodedImage } from './images.ts';
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
   * Counts a decoded image against the textureTexels limit (each image is already held to
   * imagePixels by its header); past it the image is dropped and the reason returned.
   */
  private chargeTexels(image: DecodedImage, imageName: string): string | undefined {
    try {
      this.texels.add(image.width * image.height, `${imageName}, ${image.width}×${image.height}`);
      return undefined;
    } catch (e) {
      if (e instanceof LanternError) return e.message;
      throw e;
    }
  }

  private readonly texels = new Budget('textureTexels', 'texture texels');

  private textureFor(texture: GltfTexture, use: TextureUse, materialName: string): number {
    const i = this.gltfIndex.get(texture) ?? -1;
    const encoding: TextureEncoding = use === 'color' ? 'srgb' : 'linear';
    const imageName = this.imageNames[i] ?? texture.getName() ?? `texture ${i}`;
    const key = `${i}:${encoding}:${use === 'normal' ? 'n' : ''}`;
    const known = this.byKey.get(key);
    if (known !== undefined) return known;

    let decoded: DecodedImage | undefined;
    if (this.imageMissing[i]) {
      this.warnings.missingFile(imageName, 'textures that use it are replaced by neutral ones');
    } else {
      const bytes = texture.getImage();
      const result = bytes && bytes.length > 0 ? decodeImage(bytes, imageName) : { ok: false as const, reason: 'it is empty' };
      const refused = result.ok ? this.chargeTexels(result.image, imageName) : result.reason;
      if (result.ok && !refused) decoded = result.image;
      else this.warnings.add(`texture ${imageName} (material '${materialName}') is replaced by a neutral one: ${refused}`);
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
