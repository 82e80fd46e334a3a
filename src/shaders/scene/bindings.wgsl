// Bind group 0, the scene, shared by every pass that traces rays (gpu/scene-resources.ts fills it).
// Expects nothing; provides the scene arrays under these names.

#import scene/types

@group(0) @binding(0) var<uniform> scene_info: SceneInfo;
@group(0) @binding(1) var<storage, read> bvh_nodes: array<BvhNode>;
@group(0) @binding(2) var<storage, read> triangles_hot: array<TriangleHot>;
@group(0) @binding(3) var<storage, read> triangles_shading: array<TriangleShading>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var<storage, read> light_slots: array<LightSlot>;
@group(0) @binding(6) var<storage, read> texture_rects: array<TextureRect>;
// rgba8unorm-srgb pages: textureLoad returns linear colour.
@group(0) @binding(7) var texture_atlas: texture_2d_array<f32>;

// ---- BSDF energy tables (shaders/scene/bsdf-tables.wgsl reads them) ----
// Directional albedos of the GGX lobes for energy compensation, built by gpu/pack/bsdf-tables.ts
// (bsdfTableBytes(); layout: BSDF_TABLE_* constants in scene/bsdf-tables.wgsl). The same bytes for
// every scene: upload once per device.
@group(0) @binding(12) var<storage, read> bsdf_tables: array<f32>;
