// A probe of the WebGL2 host (tests/e2e/webgl2-host.test.ts): a stand-in "path tracer" whose every
// sample adds known values made of its uniform (a vec3 then scalars, where std140 and WGSL must agree),
// an RGBA32UI texture read through usampler2D and a layer of an RGBA8 2D array, so that the sums
// read back say whether uniforms, textures, ping-pong and row order came through.

struct ProbeParams {
  add: vec3f,
  scale: f32,
  layer: u32,
  samples: u32,
}

@group(0) @binding(0) var<uniform> params: ProbeParams;
@group(0) @binding(1) var records: texture_2d<u32>;
@group(0) @binding(2) var pages: texture_2d_array<f32>;
@group(2) @binding(1) var previous: texture_2d<f32>;

@vertex
fn vs_probe(@builtin(vertex_index) index: u32) -> @builtin(position) vec4f {
  let xy = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
  return vec4f(xy * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_probe(@builtin(position) position: vec4f) -> @location(0) vec4f {
  let p = vec2i(position.xy);
  let r = textureLoad(records, p, 0);
  let a = textureLoad(pages, p, i32(params.layer), 0);
  let sample = vec4f(f32(r.x) * params.scale + params.add.x, f32(r.y) * params.scale + params.add.y, a.r + params.add.z, f32(params.samples));
  return textureLoad(previous, p, 0) + sample;
}
