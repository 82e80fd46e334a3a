/**
 * Textures of the WebGL2 backend: the packed scene's data textures (u32 records as RGBA32UI read by
 * usampler2D and texelFetch, the atlases as 2D arrays) and the float targets, uploaded from the
 * same bytes the WebGPU path uploads. A texture larger than the context allows is refused before
 * anything is allocated, naming the texture, its size and the limit.
 */
import { LanternError } from '../errors.ts';
import type { WebGl2Limits } from './context.ts';

/** The formats the backend uploads, named as WebGPU names them. */
export type WebGl2TextureFormat = 'rgba32uint' | 'r32uint' | 'rgba32float' | 'rg32float' | 'r32float' | 'rgba16float' | 'rgba8unorm' | 'rgba8unorm-srgb';

/** One texture's bytes: a 2D texture (depthOrLayers 1) or a 2D array of depthOrLayers layers. */
export interface WebGl2TextureSource {
  readonly name: string;
  readonly group: number;
  readonly binding: number;
  readonly format: WebGl2TextureFormat | string;
  readonly width: number;
  readonly height: number;
  readonly depthOrLayers: number;
  readonly data: ArrayBufferView;
}

interface FormatInfo {
  readonly internal: number;
  readonly format: number;
  readonly type: number;
  /** Bytes a texel. */
  readonly bytes: number;
  /** Sampled through a linear filter (false: integer and 32-bit float formats, read with texelFetch). */
  readonly filterable: boolean;
}

function formatInfo(gl: WebGL2RenderingContext, format: string): FormatInfo | undefined {
  switch (format) {
    case 'rgba32uint': return { internal: gl.RGBA32UI, format: gl.RGBA_INTEGER, type: gl.UNSIGNED_INT, bytes: 16, filterable: false };
    case 'r32uint': return { internal: gl.R32UI, format: gl.RED_INTEGER, type: gl.UNSIGNED_INT, bytes: 4, filterable: false };
    case 'rgba32float': return { internal: gl.RGBA32F, format: gl.RGBA, type: gl.FLOAT, bytes: 16, filterable: false };
    case 'rg32float': return { internal: gl.RG32F, format: gl.RG, type: gl.FLOAT, bytes: 8, filterable: false };
    case 'r32float': return { internal: gl.R32F, format: gl.RED, type: gl.FLOAT, bytes: 4, filterable: false };
    case 'rgba16float': return { internal: gl.RGBA16F, format: gl.RGBA, type: gl.HALF_FLOAT, bytes: 8, filterable: true };
    case 'rgba8unorm': return { internal: gl.RGBA8, format: gl.RGBA, type: gl.UNSIGNED_BYTE, bytes: 4, filterable: true };
    case 'rgba8unorm-srgb': return { internal: gl.SRGB8_ALPHA8, format: gl.RGBA, type: gl.UNSIGNED_BYTE, bytes: 4, filterable: true };
    default: return undefined;
  }
}

/** An uploaded texture and the target it was made for. */
export interface WebGl2Texture {
  readonly name: string;
  readonly texture: WebGLTexture;
  readonly target: number;
  readonly width: number;
  readonly height: number;
  readonly layers: number;
}

/** Whether `source` fits the context, as the one-line reason it does not (undefined: it fits). */
export function textureMisfit(source: Pick<WebGl2TextureSource, 'name' | 'width' | 'height' | 'depthOrLayers'>, limits: WebGl2Limits): string | undefined {
  const { name, width, height, depthOrLayers } = source;
  if (width > limits.maxTextureSize || height > limits.maxTextureSize) return `${name} is ${width} × ${height} texels, this GPU's WebGL2 allows ${limits.maxTextureSize} × ${limits.maxTextureSize}`;
  if (depthOrLayers > limits.maxArrayTextureLayers) return `${name} has ${depthOrLayers} layers, this GPU's WebGL2 allows ${limits.maxArrayTextureLayers}`;
  return undefined;
}

/** Checks every texture of a scene before any is made: one LanternError listing what does not fit. */
export function checkTexturesFit(sources: readonly WebGl2TextureSource[], limits: WebGl2Limits, sceneName: string): void {
  const misfits = sources.map((s) => textureMisfit(s, limits)).filter((m): m is string => m !== undefined);
  if (misfits.length > 0) throw new LanternError(`the scene '${sceneName}' does not fit WebGL2's texture limits: ${misfits.join('; ')}`, 'Open it in a browser with WebGPU');
}

/**
 * Uploads one texture: TEXTURE_2D for one layer read as a 2D sampler, TEXTURE_2D_ARRAY where
 * `array` (the program's sampler is a sampler2DArray). Nearest filtering for integer and 32-bit
 * float data, linear otherwise; edges clamped.
 */
export function uploadTexture(gl: WebGL2RenderingContext, source: WebGl2TextureSource, limits: WebGl2Limits, array: boolean): WebGl2Texture {
  const info = formatInfo(gl, source.format);
  if (!info) throw new LanternError(`WebGL2: the texture ${source.name} has format ${source.format}, which the WebGL2 backend does not upload`);
  const misfit = textureMisfit(source, limits);
  if (misfit) throw new LanternError(`WebGL2: ${misfit}`);
  const { width, height, depthOrLayers: layers } = source;
  const expected = width * height * layers * info.bytes;
  if (source.data.byteLength < expected) throw new LanternError(`WebGL2: the texture ${source.name} has ${source.data.byteLength} bytes, ${width} × ${height} × ${layers} ${source.format} needs ${expected}`);
  if (!array && layers !== 1) throw new LanternError(`WebGL2: the texture ${source.name} has ${layers} layers but is read as a 2D texture`);
  const texture = gl.createTexture();
  const target = array ? gl.TEXTURE_2D_ARRAY : gl.TEXTURE_2D;
  gl.bindTexture(target, texture);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
  const view = typedView(source.data, info.type);
  if (array) {
    gl.texStorage3D(target, 1, info.internal, width, height, layers);
    gl.texSubImage3D(target, 0, 0, 0, 0, width, height, layers, info.format, info.type, view);
  } else {
    gl.texStorage2D(target, 1, info.internal, width, height);
    gl.texSubImage2D(target, 0, 0, 0, width, height, info.format, info.type, view);
  }
  const filter = info.filterable ? gl.LINEAR : gl.NEAREST;
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, filter);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, filter);
  gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  gl.bindTexture(target, null);
  return { name: source.name, texture, target, width, height, layers };
}

/** The typed array texSubImage wants for `type`, over the same bytes. */
function typedView(data: ArrayBufferView, type: number): ArrayBufferView {
  const { buffer, byteOffset, byteLength } = data;
  // WebGL2RenderingContext constants: UNSIGNED_INT 0x1405, FLOAT 0x1406, HALF_FLOAT 0x140b, UNSIGNED_BYTE 0x1401.
  switch (type) {
    case 0x1405: return new Uint32Array(buffer, byteOffset, byteLength / 4);
    case 0x1406: return new Float32Array(buffer, byteOffset, byteLength / 4);
    case 0x140b: return new Uint16Array(buffer, byteOffset, byteLength / 2);
    default: return new Uint8Array(buffer, byteOffset, byteLength);
  }
}
