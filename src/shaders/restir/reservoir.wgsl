// ReSTIR DI's building blocks (Bitterli et al. 2020, "Spatiotemporal reservoir resampling for
// real-time ray tracing with dynamic direct lighting"): light points (a light of the alias table
// and a point on it, named so that any pixel can evaluate it again), the goal function, weighted
// reservoirs and their 8-byte packing. Expects the scene (scene/lights: the alias table, the
// emitters, the environment). The passes are restir/restir (candidates, temporal and spatial reuse)
// and the frame path tracer, which shades the chosen point (integrator/path, RESTIR).
//
// Measures. A point on an emissive triangle or sphere is a point of area; the environment and the sun
// are directions; a punctual light is one point. Reservoirs from different pixels are combined in
// that shared measure, so a light point's contribution at x is f · L · cos θx · g · W with g the
// measure factor (cos θlight / d² for area, 1 otherwise), and the goal is p̂ = lum(L) · cos θx · g
// (the unshadowed contribution of a white Lambertian surface: the frame's radiance is demodulated by
// the albedo anyway). A candidate drawn with solid-angle density pdf then weighs p̂ / (pdf · g) =
// lum(L) · cos θx / pdf, the same in every measure.

#import lib/constants
#import lib/random
#import lib/color
#import lib/sampling
#import lib/ray-offset
#import scene/bvh
#import scene/lights

// Where on a light: two numbers of 11 bits (the light sample's random numbers, snapped to the centres
// of a 2048 × 2048 grid before the point is made, so the stored point is exactly the one sampled).
const RESTIR_GRID: u32 = 2048u;
// Slots of the alias table a reservoir can name (20 bits; LightView of a larger table: no light).
const RESTIR_MAX_SLOTS: u32 = 1048576u;
// Largest candidate count a reservoir stores (5 bits, counted in batches of the initial candidates).
const RESTIR_MAX_M: u32 = 31u;
// Shadow rays stop this fraction short of the light point, as the path tracer's do.
const RESTIR_SHADOW_SHORTEN: f32 = 1e-4;
// A G-buffer point (rebuilt from the stored depth) is lifted this fraction of its depth off the
// surface for its shadow rays, beyond offset_ray_origin's few ulps: the rebuilt point is not exactly
// on the triangle and the stored normal is the shading normal.
const RESTIR_LIFT: f32 = 2e-4;

// A light of the alias table (slot, and whether the slot's alias) and where on it: q are the
// snapped random numbers of sample_triangle_uniform, sample_environment or sample_sun, the snapped
// octahedral direction from a sphere's centre, or nothing for punctual lights.
struct LightPoint {
  slot: u32,
  use_alias: bool,
  q: vec2u,
}

// A light point as seen from a shading point x.
struct LightView {
  // Unit direction x → point, and the distance (T_MISS at infinity).
  direction: vec3f,
  distance: f32,
  // Radiance arriving along `direction` (a punctual light: its windowed intensity / d²); 0 where the
  // point sends nothing to x or cannot be drawn from x.
  radiance: vec3f,
  // The measure factor g: cos θlight / d² for points of area, 1 for directions and punctual lights.
  geometry: f32,
  // Solid-angle density (a punctual light: probability) with which restir_candidate draws this point
  // from x, light selection included.
  pdf: f32,
}

// A reservoir: the chosen point, its unbiased contribution weight W (estimates 1 / its density), and
// M, the candidates behind it in batches (a pixel's initial candidates are one batch).
struct Reservoir {
  point: LightPoint,
  w: f32,
  m: u32,
}

// Packed, 8 bytes: slot (20 bits), alias (1), M (5), q.x (11), q.y (11), W (16: e6m10 float).
// The frame-scratch words (denoise/gbuffer FRAME_WORDS per pixel) that hold a reservoir between the
// ReSTIR passes, and the final one from restir_lend until the path tracer has read it (word 0 is
// FRAME_RADIANCE, which the path tracer writes afterwards; word 3 is free until the temporal pass).
const RESTIR_SCRATCH_A: u32 = 0u;
const RESTIR_SCRATCH_B: u32 = 3u;

struct ReservoirTexel {
  a: u32,
  b: u32,
}

fn empty_reservoir() -> Reservoir {
  return Reservoir(LightPoint(0u, false, vec2u(0u)), 0.0, 0u);
}

// W as an unsigned float with 6 exponent bits and 10 mantissa bits (2⁻³¹ … 2³²: contribution
// weights are areas and solid angles over goal values, far outside f16 in millimetre scenes);
// 0 codes zero. Relative rounding 2⁻¹¹.
fn pack_weight(w: f32) -> u32 {
  if (!(w > 0.0)) {
    return 0u;
  }
  // Infinite or huge weights saturate (the largest code) rather than reach log2(∞).
  let wc = min(w, 1e10);
  var e = i32(floor(log2(wc)));
  var f = wc * exp2(f32(-e));
  if (f < 1.0) {
    e -= 1;
    f *= 2.0;
  }
  if (f >= 2.0) {
    e += 1;
    f *= 0.5;
  }
  var m = u32(round((f - 1.0) * 1024.0));
  if (m >= 1024u) {
    m = 0u;
    e += 1;
  }
  if (e < -31) {
    return 0u;
  }
  if (e > 31) {
    return (63u << 10u) | 1023u;
  }
  return (u32(e + 32) << 10u) | m;
}

fn unpack_weight(p: u32) -> f32 {
  let e = p >> 10u;
  if (e == 0u) {
    return 0.0;
  }
  return exp2(f32(i32(e) - 32)) * (1.0 + f32(p & 1023u) / 1024.0);
}

fn pack_reservoir(r: Reservoir) -> ReservoirTexel {
  let m = min(r.m, RESTIR_MAX_M);
  let a = (r.point.slot & (RESTIR_MAX_SLOTS - 1u)) | (select(0u, 1u, r.point.use_alias) << 20u) | (m << 21u) | ((r.point.q.x & 63u) << 26u);
  let b = (r.point.q.x >> 6u) | (r.point.q.y << 5u) | (pack_weight(r.w) << 16u);
  return ReservoirTexel(a, b);
}

fn unpack_reservoir(t: ReservoirTexel) -> Reservoir {
  let q = vec2u((t.a >> 26u) | ((t.b & 31u) << 6u), (t.b >> 5u) & 2047u);
  return Reservoir(LightPoint(t.a & (RESTIR_MAX_SLOTS - 1u), ((t.a >> 20u) & 1u) != 0u, q), unpack_weight(t.b >> 16u), (t.a >> 21u) & 31u);
}

fn restir_u(q: vec2u) -> vec2f {
  return (vec2f(q) + 0.5) / f32(RESTIR_GRID);
}

fn restir_q(u: vec2f) -> vec2u {
  return min(vec2u(u * f32(RESTIR_GRID)), vec2u(RESTIR_GRID - 1u));
}

// Octahedral map of a unit vector to [−1, 1]² and back (as denoise/gbuffer's pack_normal, unpacked).
fn octahedral_encode(n: vec3f) -> vec2f {
  let p = n.xy / max(abs(n.x) + abs(n.y) + abs(n.z), 1e-30);
  let sign_p = select(vec2f(-1.0), vec2f(1.0), p >= vec2f(0.0));
  return select(p, (1.0 - abs(p.yx)) * sign_p, n.z < 0.0);
}

fn octahedral_decode(e: vec2f) -> vec3f {
  var n = vec3f(e, 1.0 - abs(e.x) - abs(e.y));
  let t = max(-n.z, 0.0);
  n.x += select(t, -t, n.x >= 0.0);
  n.y += select(t, -t, n.y >= 0.0);
  return normalize(n);
}

fn no_light_view() -> LightView {
  return LightView(vec3f(0.0, 0.0, 1.0), 0.0, vec3f(0.0), 0.0, 0.0);
}

// The light code and instance a light point names (as sample_light reads its slot).
fn light_point_code(point: LightPoint) -> vec2u {
  let slot = scene_light_slot(point.slot);
  let code = select(slot.light, slot.alias_light, point.use_alias);
  let instance = select(0u, select(slot.instance, slot.alias_instance, point.use_alias), SCENE_HAS_INSTANCES);
  return vec2u(code, instance);
}

// A point of an emissive triangle (uniform by area from u, as sample_triangle_light) seen from x.
fn view_triangle_point(triangle: u32, instance: u32, x: vec3f, u: vec2f) -> LightView {
  let t = triangle_light_point(triangle, instance, x, u);
  if (!(t.geometry > 0.0) || !(t.sample.pdf > 0.0)) {
    return no_light_view();
  }
  return LightView(t.sample.direction, t.sample.distance, t.sample.radiance, t.geometry, t.sample.pdf);
}

// The centre and radius of an emissive sphere (leaf order) of `instance`.
fn sphere_of(sphere: u32, instance: u32) -> vec4f {
  let prim = world_primitive(instance, sphere);
  return vec4f(prim.v0, prim.e1.x);
}

// A point of an emissive sphere, named by its snapped octahedral direction q from the centre, seen
// from x: drawn by sample_sphere_light's cone (uniform in solid angle) where it lies on the cap x sees.
fn view_sphere_point(sphere: u32, instance: u32, x: vec3f, q: vec2u) -> LightView {
  let s = sphere_of(sphere, instance);
  let normal = octahedral_decode(restir_u(q) * 2.0 - 1.0);
  let point = s.xyz + s.w * normal;
  let to_centre = s.xyz - x;
  let d2_centre = dot(to_centre, to_centre);
  let sin2_max = s.w * s.w / d2_centre;
  let to_light = point - x;
  let distance2 = dot(to_light, to_light);
  let distance = sqrt(distance2);
  let wi = to_light / distance;
  let cos_light = -dot(normal, wi);
  if (!(sin2_max < 1.0) || !(cos_light > 0.0) || !(distance > 0.0)) {
    return no_light_view();
  }
  let material = scene_material(instance_material(instance, sphere));
  let area = 4.0 * PI * s.w * s.w;
  let pdf = light_selection_pmf(material, area) / sphere_cone_solid_angle(sin2_max);
  return LightView(wi, distance, material_emission(material, sphere_uv(point - s.xyz), wi), cos_light / distance2, pdf);
}

// Any light point seen from x (no light: radiance and pdf 0).
fn view_light_point(point: LightPoint, x: vec3f) -> LightView {
  if (point.slot >= scene_light_count()) {
    return no_light_view();
  }
  let ci = light_point_code(point);
  let kind = ci.x >> LIGHT_KIND_SHIFT;
  let index = ci.x & LIGHT_INDEX_MASK;
  if (kind == LIGHT_KIND_TRIANGLE) {
    if (SCENE_HAS_ANALYTIC_PRIMITIVES && (scene_triangle_flags(index) & PRIMITIVE_SPHERE) != 0u) {
      return view_sphere_point(index, ci.y, x, point.q);
    }
    return view_triangle_point(index, ci.y, x, restir_u(point.q));
  }
  if (SCENE_HAS_PUNCTUAL_LIGHTS && kind == LIGHT_KIND_PUNCTUAL) {
    let s = sample_punctual_light(index, x);
    return LightView(s.direction, s.distance, select(vec3f(0.0), s.radiance, s.pdf > 0.0), 1.0, s.pdf);
  }
  if (SCENE_HAS_ENVIRONMENT && kind == LIGHT_KIND_ENVIRONMENT) {
    let s = sample_environment(restir_u(point.q));
    let pdf = s.pdf * scene_info.environment_select_pmf;
    return LightView(s.direction, T_MISS, select(vec3f(0.0), s.radiance, pdf > 0.0), 1.0, pdf);
  }
  if (SCENE_HAS_ENVIRONMENT && kind == LIGHT_KIND_SUN) {
    let s = sample_sun(restir_u(point.q));
    let pdf = s.pdf * scene_info.sun_select_pmf;
    return LightView(s.direction, T_MISS, select(vec3f(0.0), s.radiance, pdf > 0.0), 1.0, pdf);
  }
  return no_light_view();
}

// One candidate for the shading point x, drawn as sample_light draws (a slot of the alias table, its
// light or alias, a point on it), with the random numbers snapped to the grid. Requires lights.
fn restir_candidate(x: vec3f, rng: ptr<function, Rng>) -> LightPoint {
  let u_select = rng_next_2d(rng);
  let u = rng_next_2d(rng);
  let light_count = scene_light_count();
  let slot_index = min(u32(u_select.x * f32(light_count)), light_count - 1u);
  var point = LightPoint(slot_index, !(u_select.y < scene_light_slot(slot_index).keep), restir_q(u));
  if (SCENE_HAS_ANALYTIC_PRIMITIVES) {
    let ci = light_point_code(point);
    let index = ci.x & LIGHT_INDEX_MASK;
    if ((ci.x >> LIGHT_KIND_SHIFT) == LIGHT_KIND_TRIANGLE && (scene_triangle_flags(index) & PRIMITIVE_SPHERE) != 0u) {
      // A sphere's point depends on x (its cone): name it by where it lies on the sphere instead.
      let ls = sample_sphere_light(index, ci.y, x, restir_u(point.q));
      let s = sphere_of(index, ci.y);
      let on_sphere = normalize(x + ls.distance * ls.direction - s.xyz);
      point.q = restir_q(octahedral_encode(on_sphere) * 0.5 + 0.5);
    }
  }
  return point;
}

// p̂ at a shading point with unit normal n (turned toward the viewer): the unshadowed contribution of
// a white Lambertian surface, times π, in luminance.
fn restir_goal(v: LightView, n: vec3f) -> f32 {
  let cos_x = dot(n, v.direction);
  if (!(cos_x > 0.0) || !(v.pdf > 0.0)) {
    return 0.0;
  }
  return luminance(v.radiance) * cos_x * v.geometry;
}

// Whether nothing blocks the light point from a G-buffer point x (normal n, linear depth `depth`).
fn restir_visible(x: vec3f, n: vec3f, depth: f32, v: LightView) -> bool {
  let origin = offset_ray_origin(x, n) + n * (RESTIR_LIFT * max(depth, 0.0));
  return !trace_any(Ray(origin, 0.0, v.direction, v.distance * (1.0 - RESTIR_SHADOW_SHORTEN)));
}

// Streaming weighted reservoir sampling: offers `point` with resampling weight `weight`; keeps it
// with probability weight / (running sum). `goal` (p̂ of the kept point here) goes along.
struct ReservoirStream {
  point: LightPoint,
  goal: f32,
  weight_sum: f32,
  m: u32,
  // Which offer was kept (its index among the offers), for the 1/Z test of the combination.
  chosen: u32,
}

// ReservoirStream.chosen before any offer was kept.
const NOT_CHOSEN: u32 = 0xffffffffu;

fn empty_stream() -> ReservoirStream {
  return ReservoirStream(LightPoint(0u, false, vec2u(0u)), 0.0, 0.0, 0u, NOT_CHOSEN);
}

fn stream_offer(s: ptr<function, ReservoirStream>, point: LightPoint, weight: f32, goal: f32, m: u32, index: u32, u: f32) {
  (*s).m += m;
  if (!(weight > 0.0)) {
    return;
  }
  (*s).weight_sum += weight;
  if (u * (*s).weight_sum < weight) {
    (*s).point = point;
    (*s).goal = goal;
    (*s).chosen = index;
  }
}
