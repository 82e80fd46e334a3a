// Present: draws the tone-mapped image over the whole canvas (one full-screen triangle), scaling
// with a linear filter when the render resolution differs from the canvas. Browser only.
// Its own group 0: the image and a sampler.

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var image_sampler: sampler;

struct VertexOutput {
  @builtin(position) position: vec4f,
  // 0..1 across the image, (0, 0) top left.
  @location(0) uv: vec2f,
}

@vertex
fn present_vertex(@builtin(vertex_index) index: u32) -> VertexOutput {
  // A triangle covering clip space: (-1,-1), (3,-1), (-1,3).
  let xy = vec2f(f32((index << 1u) & 2u), f32(index & 2u));
  var out: VertexOutput;
  out.position = vec4f(xy * 2.0 - 1.0, 0.0, 1.0);
  out.uv = vec2f(xy.x, 1.0 - xy.y);
  return out;
}

@fragment
fn present_fragment(in: VertexOutput) -> @location(0) vec4f {
  return textureSampleLevel(image, image_sampler, in.uv, 0.0);
}
