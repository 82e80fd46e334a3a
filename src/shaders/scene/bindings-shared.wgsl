// Bind group 0's resources that are not the scene's record arrays: the scene info, the texture atlases,
// the punctual lights, the per-triangle attributes, the instances, the environment and the BSDF
// tables. Both scene/bindings (records in storage buffers) and scene/bindings-textures (records in
// textures, for the fragment tracer) import it, so the two declare these identically.
// Expects nothing.

#import scene/types

@group(0) @binding(0) var<uniform> scene_info: SceneInfo;
// rgba8unorm-srgb pages: textureLoad returns linear colour.
@group(0) @binding(7) var texture_atlas: texture_2d_array<f32>;
// rgba8unorm pages for data textures (TEXTURE_LINEAR).
@group(0) @binding(13) var texture_atlas_linear: texture_2d_array<f32>;
@group(0) @binding(14) var<uniform> punctual_lights: PunctualLights;
// Per-vertex tangents and the second uv set, only for scenes with normal maps or TEXCOORD_1 (else
// 1×1): f32 bits in an rgba32uint texture (gpu/pack/scene-pack.ts), read where a material needs them.
@group(0) @binding(15) var triangle_attributes: texture_2d<u32>;
// The instances of the two-level BVH (bvh/levels.ts; one, the static world, without moving instances):
// the bytes of Instance records, INSTANCE_TEXELS rgba32uint texels each, INSTANCES_PER_ROW to a row
// (scene/instances.wgsl instance_record reads one). A texture, not a storage buffer: the real-time
// chain's passes already use the ten storage buffers a browser may give a shader stage.
@group(0) @binding(16) var instance_data: texture_2d<u32>;

// ---- Environment (bindings 8–11): scene/environment.wgsl reads these; gpu/pack/environment-pack.ts
// packs them. environment_map is a lat-long image of f32 RGBA radiance (top row = +y) stored as the
// bits of an rgba32uint texture: rgba32float textures are unfilterable, which a layout reflected from
// texture_2d<f32> cannot say, and filtering is manual anyway (textureLoad + bitcast, full f32 range).
// environment_cdf holds the CDFs of its piecewise-constant sampling density as f32 bits (r32uint):
// row j < height the conditional CDF over the columns of row j, row height the marginal CDF over
// rows, each without its first entry (always 0), so max(width, height) texels a row: an 8192-wide
// map fits a device's maxTextureDimension2D of 8192. A texture, not a storage buffer: storage
// buffers are kept within WebGPU's per-stage limit.
#import scene/environment-types

@group(0) @binding(8) var<uniform> environment_info: EnvironmentInfo;
@group(0) @binding(9) var environment_map: texture_2d<u32>;
@group(0) @binding(10) var environment_cdf: texture_2d<u32>;

// ---- BSDF energy tables (binding 12): scene/bsdf-tables.wgsl reads them; gpu/pack/bsdf-tables.ts
// computes them. f32 values as the bits of an r32uint texture, BSDF_TABLE_TEXTURE_WIDTH values a
// row (a texture rather than a storage buffer, for the per-stage storage-buffer limit).
@group(0) @binding(12) var bsdf_tables: texture_2d<u32>;
