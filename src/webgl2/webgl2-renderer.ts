/**
 * The WebGL2 backend's frame (issue #30): WebGL2 has no compute, storage buffers or atomics, so the
 * path tracer is a fragment program (one fragment a pixel) that reads the previous sum from one
 * RGBA32F target and writes the sum plus its new samples to the other; the two ping-pong. The tone
 * map pass (passes/tonemap-fragment) turns the sum into the 8-bit image of the image's size, which
 * present blits to the canvas (linear filter, flipped). Every program is GLSL the build translated
 * from WGSL (glsl.ts); uniforms are the bytes the WGSL layout gives (program.ts checks std140
 * agrees), textures the packed scene's (textures.ts). Row 0 of every target is the image's top row,
 * as in WebGPU (naga flips vertex positions, so a WGSL pass's top lands in GL's row 0), so read-backs
 * match the WebGPU path's layout; the canvas shows GL's row 0 at the bottom, hence the flipped blit.
 */
import { LanternError } from '../errors.ts';
import { StructArray } from '../gpu/pack/struct-array.ts';
import { reflectModule, structLayout, type StructLayout } from '../gpu/wgsl/reflect.ts';
import { TONE_MAPPERS, type ToneMapper } from '../passes/variants.ts';
import { openWebGl2, type WebGl2Canvas, type WebGl2Context } from './context.ts';
import { translatedProgram, type GlslProgram } from './glsl.ts';
import { compileProgram, type LinkedProgram, type Wait } from './program.ts';
import { checkTexturesFit, uploadTexture, type WebGl2Texture, type WebGl2TextureSource } from './textures.ts';

/** A (group, binding) pair as a map key. */
export const slot = (group: number, binding: number): string => `${group}:${binding}`;

/** The tone map's binding of the accumulated sums (passes/tonemap-fragment.wgsl). */
const TONEMAP_ACCUMULATION = slot(0, 1);
const TONEMAP_PARAMS = slot(0, 0);

interface Target {
  readonly texture: WebGLTexture;
  readonly framebuffer: WebGLFramebuffer;
}

/** A compile as the page reports it: the program, how long it took. */
export interface WebGl2Compile {
  readonly key: string;
  readonly ms: number;
}

export interface WebGl2RendererOptions {
  /** Waits between polls of a parallel compile (the page: one animation frame). */
  readonly wait?: Wait;
  /** Told as each program finishes compiling. */
  readonly onCompile?: (compile: WebGl2Compile) => void;
}

/** What one accumulation draw binds besides the previous sum: uniforms' bytes and the scene's textures, by slot. */
export interface AccumulateInputs {
  readonly uniforms: ReadonlyMap<string, ArrayBufferView>;
  /** Samples per pixel the draw adds (what sampleCount grows by). */
  readonly samples: number;
}

export class WebGl2Renderer {
  private tracer?: { linked: LinkedProgram; accumulation: string };
  private readonly uniformBuffers = new Map<string, WebGLBuffer>();
  private sceneTextures = new Map<string, WebGl2Texture>();
  private accumulation: [Target, Target] | undefined;
  private image: Target | undefined;
  private widthValue = 0;
  private heightValue = 0;
  private samples = 0;
  private readonly tonemapParams: StructArray;
  private readonly vertexArray: WebGLVertexArrayObject;
  /** Every program compiled so far, in order. */
  readonly compiles: WebGl2Compile[] = [];

  private constructor(
    readonly ctx: WebGl2Context,
    private readonly tonemapProgram: LinkedProgram,
    private readonly options: WebGl2RendererOptions,
  ) {
    this.tonemapParams = new StructArray(structLayout(reflectModule('passes/tonemap-fragment').defs, 'TonemapFragmentParams'), 1);
    // WebGL2 draws without attributes from gl_VertexID, but a bound vertex array is still the rule.
    this.vertexArray = ctx.gl.createVertexArray();
  }

  /** Opens the canvas's context and compiles the tone map program. */
  static async create(canvas: WebGl2Canvas, options: WebGl2RendererOptions = {}): Promise<WebGl2Renderer> {
    const ctx = openWebGl2(canvas);
    const tonemap = await compileTranslated(ctx, translatedProgram('tonemap'), options);
    const r = new WebGl2Renderer(ctx, tonemap, options);
    r.compiles.push({ key: tonemap.key, ms: tonemap.compileMs });
    return r;
  }

  get gl(): WebGL2RenderingContext {
    return this.ctx.gl;
  }

  get width(): number {
    return this.widthValue;
  }

  get height(): number {
    return this.heightValue;
  }

  /** Samples per pixel in the sums. */
  get sampleCount(): number {
    return this.samples;
  }

  /**
   * Compiles the path tracer (a translated program with a texture_2d<f32> of the previous sums at
   * `accumulation`, a slot) and makes it the one accumulate draws. The sums restart.
   */
  async setTracer(source: GlslProgram, accumulation: string, layouts?: (struct: string) => StructLayout): Promise<LinkedProgram> {
    const linked = await compileTranslated(this.ctx, source, this.options, layouts);
    if (!linked.samplers.some((s) => slot(s.group, s.binding) === accumulation)) throw new LanternError(`WebGL2: the path tracer '${source.key}' reads no texture at ${accumulation}, where the sums are bound`);
    this.compiles.push({ key: linked.key, ms: linked.compileMs });
    if (this.tracer) this.gl.deleteProgram(this.tracer.linked.program);
    this.tracer = { linked, accumulation };
    this.resetAccumulation();
    return linked;
  }

  /** Uploads a scene's textures in place of the last one's, after checking every one fits (one error listing those that do not). */
  setSceneTextures(sources: readonly WebGl2TextureSource[], sceneName: string): void {
    checkTexturesFit(sources, this.ctx.limits, sceneName);
    const arrays = new Set((this.tracer?.linked.samplers ?? []).filter((s) => s.type.includes('Array')).map((s) => slot(s.group, s.binding)));
    const made = new Map<string, WebGl2Texture>();
    try {
      for (const s of sources) made.set(slot(s.group, s.binding), uploadTexture(this.gl, s, this.ctx.limits, arrays.has(slot(s.group, s.binding)) || s.depthOrLayers > 1));
    } catch (e) {
      for (const t of made.values()) this.gl.deleteTexture(t.texture);
      throw e;
    }
    for (const t of this.sceneTextures.values()) this.gl.deleteTexture(t.texture);
    this.sceneTextures = made;
    this.resetAccumulation();
  }

  /** Makes the targets for a `width` × `height` image (and restarts the sums). */
  resize(width: number, height: number): void {
    if (width === this.widthValue && height === this.heightValue && this.accumulation) return;
    if (width > this.ctx.limits.maxTextureSize || height > this.ctx.limits.maxTextureSize) throw new LanternError(`WebGL2: a ${width} × ${height} image is larger than this GPU's ${this.ctx.limits.maxTextureSize} texels a side`);
    this.destroyTargets();
    const { gl } = this;
    this.accumulation = [this.target(gl.RGBA32F, width, height), this.target(gl.RGBA32F, width, height)];
    this.image = this.target(gl.RGBA8, width, height);
    this.widthValue = width;
    this.heightValue = height;
    this.resetAccumulation();
  }

  /** Clears the sums: the next accumulate starts a new estimate. */
  resetAccumulation(): void {
    this.samples = 0;
    if (!this.accumulation) return;
    const { gl } = this;
    for (const t of this.accumulation) {
      gl.bindFramebuffer(gl.FRAMEBUFFER, t.framebuffer);
      gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }

  /** One draw of the path tracer over the image: reads the sums so far, writes them plus `inputs.samples` more a pixel. */
  accumulate(inputs: AccumulateInputs): void {
    const { tracer, accumulation } = this;
    if (!tracer) throw new LanternError('WebGL2: accumulate before the path tracer was compiled (setTracer)');
    if (!accumulation) throw new LanternError('WebGL2: accumulate before the image has a size (resize)');
    const [read, write] = accumulation;
    const textures = new Map<string, { texture: WebGLTexture; target: number }>(this.sceneTextures);
    textures.set(tracer.accumulation, { texture: read.texture, target: this.gl.TEXTURE_2D });
    this.draw(tracer.linked, write.framebuffer, this.widthValue, this.heightValue, inputs.uniforms, textures);
    this.accumulation = [write, read];
    this.samples += inputs.samples;
  }

  /** The sums -> the 8-bit image: the mean, 2^stops, the tone curve, sRGB (passes/tonemap-fragment). */
  tonemap(exposureStops: number, toneMapper: ToneMapper): void {
    const { accumulation, image } = this;
    if (!accumulation || !image) throw new LanternError('WebGL2: tone map before the image has a size (resize)');
    const p = this.tonemapParams;
    p.f32Field('exposure_scale')(0, 2 ** exposureStops);
    p.u32Field('tone_mapper')(0, TONE_MAPPERS.indexOf(toneMapper));
    p.f32Field('inv_sample_count')(0, this.samples > 0 ? 1 / this.samples : 0);
    const textures = new Map([[TONEMAP_ACCUMULATION, { texture: accumulation[0].texture, target: this.gl.TEXTURE_2D }]]);
    this.draw(this.tonemapProgram, image.framebuffer, this.widthValue, this.heightValue, new Map([[TONEMAP_PARAMS, new Uint8Array(p.bytes)]]), textures);
  }

  /** The 8-bit image -> the canvas's drawing buffer, scaled to it with a linear filter, row 0 at the top. */
  present(): void {
    const { image } = this;
    if (!image) throw new LanternError('WebGL2: present before the image has a size (resize)');
    const { gl } = this;
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, image.framebuffer);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
    gl.blitFramebuffer(0, 0, this.widthValue, this.heightValue, 0, gl.drawingBufferHeight, gl.drawingBufferWidth, 0, gl.COLOR_BUFFER_BIT, gl.LINEAR);
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  }

  /** The tone-mapped image, RGBA8 rows top first (tonemap first). */
  readImage(): Uint8Array {
    const { gl, image } = this;
    if (!image) throw new LanternError('WebGL2: readImage before the image has a size (resize)');
    const out = new Uint8Array(this.widthValue * this.heightValue * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, image.framebuffer);
    gl.readPixels(0, 0, this.widthValue, this.heightValue, gl.RGBA, gl.UNSIGNED_BYTE, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }

  /** The sums, RGBA32F rows top first: divide by sampleCount for the estimate. */
  readAccumulation(): Float32Array {
    const { gl, accumulation } = this;
    if (!accumulation) throw new LanternError('WebGL2: readAccumulation before the image has a size (resize)');
    const out = new Float32Array(this.widthValue * this.heightValue * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, accumulation[0].framebuffer);
    gl.readPixels(0, 0, this.widthValue, this.heightValue, gl.RGBA, gl.FLOAT, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return out;
  }

  /** Waits until the GPU has done everything submitted (a fence), for timing. */
  async finish(wait: Wait = () => new Promise((r) => setTimeout(r, 1))): Promise<void> {
    const { gl } = this;
    const sync = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!sync) return;
    gl.flush();
    try {
      for (;;) {
        const status = gl.clientWaitSync(sync, 0, 0);
        if (status === gl.ALREADY_SIGNALED || status === gl.CONDITION_SATISFIED) return;
        if (status === gl.WAIT_FAILED) throw new LanternError('WebGL2: waiting for the GPU failed');
        await wait();
      }
    } finally {
      gl.deleteSync(sync);
    }
  }

  destroy(): void {
    this.destroyTargets();
    for (const t of this.sceneTextures.values()) this.gl.deleteTexture(t.texture);
    for (const b of this.uniformBuffers.values()) this.gl.deleteBuffer(b);
    for (const p of [this.tonemapProgram, this.tracer?.linked]) if (p) this.gl.deleteProgram(p.program);
  }

  private draw(linked: LinkedProgram, framebuffer: WebGLFramebuffer | null, width: number, height: number, uniforms: ReadonlyMap<string, ArrayBufferView>, textures: ReadonlyMap<string, { texture: WebGLTexture; target: number }>): void {
    const { gl } = this;
    gl.useProgram(linked.program);
    for (const b of linked.blocks) {
      const key = slot(b.group, b.binding);
      const bytes = uniforms.get(key);
      if (!bytes) throw new LanternError(`WebGL2: '${linked.key}' reads the uniform ${b.struct} at ${key}, and no bytes were given for it`);
      const bufferKey = `${linked.key}/${key}`;
      let buffer = this.uniformBuffers.get(bufferKey);
      if (!buffer) {
        buffer = gl.createBuffer();
        this.uniformBuffers.set(bufferKey, buffer);
      }
      gl.bindBuffer(gl.UNIFORM_BUFFER, buffer);
      // std140's size may round the WGSL struct's up: the tail is zeros.
      const size = Math.max(b.dataSize, bytes.byteLength);
      const data = new Uint8Array(size);
      data.set(new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength));
      gl.bufferData(gl.UNIFORM_BUFFER, data, gl.DYNAMIC_DRAW);
      gl.bindBufferBase(gl.UNIFORM_BUFFER, b.bindingPoint, buffer);
    }
    for (const s of linked.samplers) {
      const key = slot(s.group, s.binding);
      const t = textures.get(key);
      if (!t) throw new LanternError(`WebGL2: '${linked.key}' samples a texture at ${key} (${s.type}), and none is bound there`);
      gl.activeTexture(gl.TEXTURE0 + s.unit);
      gl.bindTexture(t.target, t.texture);
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.viewport(0, 0, width, height);
    gl.bindVertexArray(this.vertexArray);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindVertexArray(null);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    for (const s of linked.samplers) {
      gl.activeTexture(gl.TEXTURE0 + s.unit);
      gl.bindTexture(textures.get(slot(s.group, s.binding))!.target, null);
    }
  }

  private target(internal: number, width: number, height: number): Target {
    const { gl } = this;
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, internal, width, height);
    // The 8-bit image is scaled onto the canvas with a linear filter; float sums are read with texelFetch.
    const filter = internal === gl.RGBA8 ? gl.LINEAR : gl.NEAREST;
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, filter);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, filter);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.bindTexture(gl.TEXTURE_2D, null);
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture, 0);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    if (status !== gl.FRAMEBUFFER_COMPLETE) throw new LanternError(`WebGL2: a ${width} × ${height} ${internal === gl.RGBA8 ? 'RGBA8' : 'RGBA32F'} target is incomplete (status 0x${status.toString(16)})`);
    return { texture, framebuffer };
  }

  private destroyTargets(): void {
    for (const t of [...(this.accumulation ?? []), ...(this.image ? [this.image] : [])]) {
      this.gl.deleteFramebuffer(t.framebuffer);
      this.gl.deleteTexture(t.texture);
    }
    this.accumulation = undefined;
    this.image = undefined;
  }
}

/** Compiles a translated program, its uniform blocks checked against its WGSL module's structs (or `layouts`). */
function compileTranslated(ctx: WebGl2Context, source: GlslProgram, options: WebGl2RendererOptions, layouts?: (struct: string) => StructLayout): Promise<LinkedProgram> {
  const defs = () => reflectModule(source.module).defs;
  return compileProgram(ctx, source, layouts ?? ((struct) => structLayout(defs(), struct)), options.wait).then((linked) => {
    options.onCompile?.({ key: linked.key, ms: linked.compileMs });
    return linked;
  });
}
