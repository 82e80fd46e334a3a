/**
 * Every program the WebGL2 backend draws with, as WGSL entry points: the single list that
 * scripts/glsl-translation.ts translates at build time (and its test checks). Each is a linked WGSL
 * module of src/shaders with a vertex and a fragment entry; the key is what the host asks
 * translatedProgram for. Pure: links WGSL text, no GL.
 */
import { linkWgsl } from '../gpu/wgsl/linker.ts';

export interface WebGl2ProgramSpec {
  readonly key: string;
  /** The WGSL module of src/shaders the entries are in (for reflection: its uniform structs). */
  readonly module: string;
  /** The exact WGSL translated (the linked module, overrides frozen where the program has any). */
  readonly wgsl: string;
  readonly vertexEntry: string;
  readonly fragmentEntry: string;
}

function fromModule(key: string, module: string, vertexEntry: string, fragmentEntry: string): WebGl2ProgramSpec {
  return { key, module, wgsl: linkWgsl(module).code, vertexEntry, fragmentEntry };
}

/** The programs, in a fixed order. */
export function webGl2ProgramSpecs(): WebGl2ProgramSpec[] {
  return [
    // The accumulated sums -> the tone-mapped 8-bit image (the image's size).
    fromModule('tonemap', 'passes/tonemap-fragment', 'vs_tonemap', 'fs_tonemap'),
  ];
}
