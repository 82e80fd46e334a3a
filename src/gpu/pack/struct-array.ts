/**
 * An array of WGSL structs in one ArrayBuffer, written through typed views at offsets that come from
 * reflection (StructLayout). Packing code asks for a field's word offset once, then writes in a tight
 * loop: no per-element objects, no hand-written offsets.
 */
import type { StructLayout } from '../wgsl/reflect.ts';

export class StructArray {
  readonly bytes: ArrayBuffer;
  readonly f32: Float32Array;
  readonly u32: Uint32Array;

  /** `count` may be 0; the buffer then still holds one zeroed element, since WebGPU bindings cannot be empty. */
  constructor(readonly layout: StructLayout, readonly count: number) {
    this.bytes = new ArrayBuffer(layout.stride * Math.max(1, count));
    this.f32 = new Float32Array(this.bytes);
    this.u32 = new Uint32Array(this.bytes);
  }

  /** First word of element i. */
  base(i: number): number {
    return i * this.layout.strideWords;
  }

  /** A writer for one field: (element, value...) with the offset resolved and type-checked once. */
  vec3(field: string): (i: number, x: number, y: number, z: number) => void {
    const o = this.layout.word(field, 'vec3f');
    const s = this.layout.strideWords;
    const f32 = this.f32;
    return (i, x, y, z) => {
      const b = i * s + o;
      f32[b] = x;
      f32[b + 1] = y;
      f32[b + 2] = z;
    };
  }

  vec4(field: string): (i: number, x: number, y: number, z: number, w: number) => void {
    const o = this.layout.word(field, 'vec4f');
    const s = this.layout.strideWords;
    const f32 = this.f32;
    return (i, x, y, z, w) => {
      const b = i * s + o;
      f32[b] = x;
      f32[b + 1] = y;
      f32[b + 2] = z;
      f32[b + 3] = w;
    };
  }

  vec2(field: string): (i: number, x: number, y: number) => void {
    const o = this.layout.word(field, 'vec2f');
    const s = this.layout.strideWords;
    const f32 = this.f32;
    return (i, x, y) => {
      const b = i * s + o;
      f32[b] = x;
      f32[b + 1] = y;
    };
  }

  vec2u(field: string): (i: number, x: number, y: number) => void {
    const o = this.layout.word(field, 'vec2u');
    const s = this.layout.strideWords;
    const u32 = this.u32;
    return (i, x, y) => {
      const b = i * s + o;
      u32[b] = x;
      u32[b + 1] = y;
    };
  }

  f32Field(field: string): (i: number, value: number) => void {
    const o = this.layout.word(field, 'f32');
    const s = this.layout.strideWords;
    const f32 = this.f32;
    return (i, v) => {
      f32[i * s + o] = v;
    };
  }

  u32Field(field: string): (i: number, value: number) => void {
    const o = this.layout.word(field, 'u32');
    const s = this.layout.strideWords;
    const u32 = this.u32;
    return (i, v) => {
      u32[i * s + o] = v;
    };
  }
}
