// Lookups in the BSDF energy tables (directional albedos E(μ, roughness) of GGX lobes, and of rough
// dielectric interfaces by ior and side). Expects `bsdf_tables` from scene/bindings, filled with
// gpu/pack/bsdf-tables.ts's bsdfTableTexture(). Used for Kulla & Conty 2017 energy compensation.

#import scene/bindings

// The layout, mirrored from BSDF_TABLE_LAYOUT in gpu/pack/bsdf-tables.ts (a unit test keeps them
// equal). μ nodes are j/(N−1), perceptual roughness nodes i/(N−1), ior nodes even over [MIN, MAX].
const BSDF_TABLE_MU_SIZE: u32 = 32u;
const BSDF_TABLE_ROUGHNESS_SIZE: u32 = 32u;
const BSDF_TABLE_GLASS_MU_SIZE: u32 = 16u;
const BSDF_TABLE_GLASS_ROUGHNESS_SIZE: u32 = 16u;
const BSDF_TABLE_GLASS_IOR_SIZE: u32 = 16u;
const BSDF_TABLE_IOR_MIN: f32 = 1.01;
const BSDF_TABLE_IOR_MAX: f32 = 3.0;
// E1[roughness][μ]: GGX conductor with F = 1.
const BSDF_TABLE_E1_OFFSET: u32 = 0u;
// E5[roughness][μ]: the same weighted by (1 − wo·m)⁵, so Schlick(F0) gives F0·E1 + (1 − F0)·E5.
const BSDF_TABLE_E5_OFFSET: u32 = 1024u;
// E1avg[roughness], E5avg[roughness]: 2∫E(μ)μ dμ.
const BSDF_TABLE_E1_AVG_OFFSET: u32 = 2048u;
const BSDF_TABLE_E5_AVG_OFFSET: u32 = 2080u;
// Eglass[side][ior][roughness][μ]: rough interface R + T (no 1/η² factor); side 0: wo outside.
const BSDF_TABLE_GLASS_OFFSET: u32 = 2112u;
const BSDF_TABLE_SIZE: u32 = 10304u;

// Values a row of the bsdf_tables texture (gpu/pack/bsdf-tables.ts BSDF_TABLE_TEXTURE_WIDTH).
const BSDF_TABLE_TEXTURE_WIDTH: u32 = 1024u;

// Table value i.
fn bsdf_table(i: u32) -> f32 {
  return bitcast<f32>(textureLoad(bsdf_tables, vec2u(i % BSDF_TABLE_TEXTURE_WIDTH, i / BSDF_TABLE_TEXTURE_WIDTH), 0).r);
}

// Linear interpolation coordinates of x ∈ [0, 1] over n nodes: (lower index, fraction).
fn bsdf_table_coord(x: f32, n: u32) -> vec2f {
  let t = clamp(x, 0.0, 1.0) * f32(n - 1u);
  let i = min(floor(t), f32(n - 2u));
  return vec2f(i, t - i);
}

// Bilinear lookup in a [roughness][μ] table of size_r × size_mu starting at offset.
fn bsdf_table_2d(offset: u32, size_r: u32, size_mu: u32, roughness: f32, mu: f32) -> f32 {
  let cr = bsdf_table_coord(roughness, size_r);
  let cm = bsdf_table_coord(mu, size_mu);
  let i = offset + u32(cr.x) * size_mu + u32(cm.x);
  let lo = mix(bsdf_table(i), bsdf_table(i + 1u), cm.y);
  let hi = mix(bsdf_table(i + size_mu), bsdf_table(i + size_mu + 1u), cm.y);
  return mix(lo, hi, cr.y);
}

// Linear lookup in a [roughness] table.
fn bsdf_table_1d(offset: u32, roughness: f32) -> f32 {
  let c = bsdf_table_coord(roughness, BSDF_TABLE_ROUGHNESS_SIZE);
  let i = offset + u32(c.x);
  return mix(bsdf_table(i), bsdf_table(i + 1u), c.y);
}

// E1 and E5 of a GGX conductor at cosine mu (the Schlick split of the directional albedo).
fn bsdf_table_e1(roughness: f32, mu: f32) -> f32 {
  return bsdf_table_2d(BSDF_TABLE_E1_OFFSET, BSDF_TABLE_ROUGHNESS_SIZE, BSDF_TABLE_MU_SIZE, roughness, mu);
}

fn bsdf_table_e5(roughness: f32, mu: f32) -> f32 {
  return bsdf_table_2d(BSDF_TABLE_E5_OFFSET, BSDF_TABLE_ROUGHNESS_SIZE, BSDF_TABLE_MU_SIZE, roughness, mu);
}

fn bsdf_table_e1_avg(roughness: f32) -> f32 {
  return bsdf_table_1d(BSDF_TABLE_E1_AVG_OFFSET, roughness);
}

fn bsdf_table_e5_avg(roughness: f32) -> f32 {
  return bsdf_table_1d(BSDF_TABLE_E5_AVG_OFFSET, roughness);
}

// Directional albedo R + T of a rough dielectric interface (no radiance scaling); entering: wo on
// the outside (relative η = ior), else inside (η = 1/ior). Trilinear over (ior, roughness, μ).
fn bsdf_table_glass(entering: bool, ior: f32, roughness: f32, mu: f32) -> f32 {
  let side = select(1u, 0u, entering);
  let ci = bsdf_table_coord((ior - BSDF_TABLE_IOR_MIN) / (BSDF_TABLE_IOR_MAX - BSDF_TABLE_IOR_MIN), BSDF_TABLE_GLASS_IOR_SIZE);
  let slice = BSDF_TABLE_GLASS_ROUGHNESS_SIZE * BSDF_TABLE_GLASS_MU_SIZE;
  let base = BSDF_TABLE_GLASS_OFFSET + (side * BSDF_TABLE_GLASS_IOR_SIZE + u32(ci.x)) * slice;
  let lo = bsdf_table_2d(base, BSDF_TABLE_GLASS_ROUGHNESS_SIZE, BSDF_TABLE_GLASS_MU_SIZE, roughness, mu);
  let hi = bsdf_table_2d(base + slice, BSDF_TABLE_GLASS_ROUGHNESS_SIZE, BSDF_TABLE_GLASS_MU_SIZE, roughness, mu);
  return mix(lo, hi, ci.y);
}
