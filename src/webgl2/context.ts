/**
 * The WebGL2 backend's context: a `webgl2` context on the page's canvas with what the fragment path
 * tracer cannot do without (EXT_color_buffer_float: rendering to RGBA32F, the accumulation) and what
 * it uses when there (KHR_parallel_shader_compile: compiles polled instead of waited for), and the
 * limits a scene is checked against. A missing piece is one LanternError naming it.
 */
import { LanternError } from '../errors.ts';

/** What getContext needs of a canvas: an HTMLCanvasElement or an OffscreenCanvas. */
export interface WebGl2Canvas {
  getContext(id: 'webgl2', options?: WebGLContextAttributes): WebGL2RenderingContext | null;
}

export interface WebGl2Limits {
  readonly maxTextureSize: number;
  readonly maxArrayTextureLayers: number;
  /** Texture units the fragment stage may sample at once. */
  readonly maxTextureImageUnits: number;
  readonly maxUniformBlockSize: number;
  readonly maxFragmentUniformBlocks: number;
}

export interface WebGl2Context {
  readonly gl: WebGL2RenderingContext;
  /** KHR_parallel_shader_compile, or null where the browser lacks it (compiles then block at the first query). */
  readonly parallelCompile: { readonly COMPLETION_STATUS_KHR: number } | null;
  readonly limits: WebGl2Limits;
  /** The GL renderer string ("ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device ...))"). */
  readonly rendererName: string;
}

/** Opens the canvas's WebGL2 context; one LanternError naming what is missing when it cannot. */
export function openWebGl2(canvas: WebGl2Canvas): WebGl2Context {
  // No depth, stencil or multisampling: the canvas only ever receives the present pass's one triangle.
  const gl = canvas.getContext('webgl2', { alpha: false, antialias: false, depth: false, stencil: false, premultipliedAlpha: false, preserveDrawingBuffer: false, powerPreference: 'high-performance' });
  if (!gl) throw new LanternError('WebGL2 is not available: the canvas gave no webgl2 context', 'Enable hardware acceleration in the browser, or use a browser with WebGPU or WebGL2');
  if (!gl.getExtension('EXT_color_buffer_float')) {
    throw new LanternError('WebGL2 lacks EXT_color_buffer_float: the path tracer accumulates into RGBA32F targets', 'Use a browser or GPU with EXT_color_buffer_float, or one with WebGPU');
  }
  const parallel = gl.getExtension('KHR_parallel_shader_compile') as { COMPLETION_STATUS_KHR: number } | null;
  const limits: WebGl2Limits = {
    maxTextureSize: gl.getParameter(gl.MAX_TEXTURE_SIZE) as number,
    maxArrayTextureLayers: gl.getParameter(gl.MAX_ARRAY_TEXTURE_LAYERS) as number,
    maxTextureImageUnits: gl.getParameter(gl.MAX_TEXTURE_IMAGE_UNITS) as number,
    maxUniformBlockSize: gl.getParameter(gl.MAX_UNIFORM_BLOCK_SIZE) as number,
    maxFragmentUniformBlocks: gl.getParameter(gl.MAX_FRAGMENT_UNIFORM_BLOCKS) as number,
  };
  // RENDERER says only "WebKit WebGL" in Chromium; the debug extension names the GPU (SwiftShader).
  const debug = gl.getExtension('WEBGL_debug_renderer_info') as { UNMASKED_RENDERER_WEBGL: number } | null;
  const rendererName = String(gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  return { gl, parallelCompile: parallel ? { COMPLETION_STATUS_KHR: parallel.COMPLETION_STATUS_KHR } : null, limits, rendererName };
}
