/**
 * Energy tables for the BSDF module (shaders/scene/bsdf.wgsl): directional albedos of GGX lobes,
 * integrated numerically here once, read in WGSL by (bi/tri)linear lookups in one storage buffer
 * (`bsdf_tables`, scene bind group). Pure (no GPU, no DOM), so a Worker can build it.
 *
 * Tables (all single scattering, height-correlated Smith G2, GGX with alpha = roughness²):
 * - E1(μ, r):  ∫ D G2 / (4 μo μi) · μi dωi            — a conductor with F = 1 (Kulla & Conty 2017)
 * - E5(μ, r):  the same with F = (1 − wo·m)⁵          — so a Schlick conductor of reflectance F0 has
 *              E = F0·E1 + (1 − F0)·E5 (F is linear in F0), any F0, even coloured
 * - E1avg(r), E5avg(r): 2∫ E(μ) μ dμ of the above, exact for the linear interpolant of the table
 * - Eglass(side, ior, r, μ): reflection + refraction of a rough dielectric interface (Walter et al.
 *   2007), exact Fresnel, counted WITHOUT the 1/η² radiance factor; side 0 = wo outside (relative
 *   η = ior), side 1 = wo inside (relative η = 1/ior, total internal reflection included).
 *
 * μ nodes are j/(N−1) (μ = 0 evaluated at MU_MIN), roughness nodes i/(N−1) (alpha floored at
 * ALPHA_MIN), ior nodes evenly over [IOR_MIN, IOR_MAX]. Each entry averages the VNDF weight G2/G1
 * over a lattice in the sampler's unit square (Heitz 2018), so peaked lobes cost no more than flat
 * ones; accuracy about 1e-3 (the unit test compares with brute force). The WGSL constants in shaders/scene/bsdf-tables.wgsl mirror BSDF_TABLE_LAYOUT; a unit
 * test keeps the two equal.
 */

export const BSDF_TABLE_MU_SIZE = 32;
export const BSDF_TABLE_ROUGHNESS_SIZE = 32;
export const BSDF_TABLE_GLASS_MU_SIZE = 16;
export const BSDF_TABLE_GLASS_ROUGHNESS_SIZE = 16;
export const BSDF_TABLE_GLASS_IOR_SIZE = 16;
export const BSDF_TABLE_IOR_MIN = 1.01;
export const BSDF_TABLE_IOR_MAX = 3.0;
/** Cosine used for the μ = 0 node (the albedo's limit at grazing, without dividing by zero). */
const MU_MIN = 1e-3;
/** Alpha used for the roughness = 0 node: the smooth limit, where the lobe is a delta anyway. */
const ALPHA_MIN = 1e-4;
/**
 * wo lies in the xz plane, so the visible normals are mirror-symmetric in y: the sampler's u2 only
 * needs the half [1/4, 3/4) (φ from π/2 to 3π/2; φ → π − φ is the mirror), which halves the work.
 */
const HALF_START = 0.25;
/**
 * GGX has heavy tails: the few normals tilted far enough to send wi below the horizon sit in a thin
 * sliver u1 → 1 of the sampler's square, which even spacing misses for small alpha (0.7 % at
 * alpha 0.06). Points are even in v with u1 = 1 − (1 − v)^k instead, weighted by du1/dv.
 */
const TAIL_POWER = 3;
/** Points of the quadrature lattice over the VNDF unit square, per table. */
const CONDUCTOR_POINTS = 233;
const GLASS_POINTS = 377;
/** (√5 − 1)/2: the Fibonacci lattice's second coordinate steps by it. */
const GOLDEN_FRACTION = (Math.sqrt(5) - 1) / 2;

const conductorCount = BSDF_TABLE_MU_SIZE * BSDF_TABLE_ROUGHNESS_SIZE;

/** Offsets (in f32 elements) of each table in the buffer: the one place the layout is written. */
export const BSDF_TABLE_LAYOUT = {
  E1_OFFSET: 0,
  E5_OFFSET: conductorCount,
  E1_AVG_OFFSET: 2 * conductorCount,
  E5_AVG_OFFSET: 2 * conductorCount + BSDF_TABLE_ROUGHNESS_SIZE,
  GLASS_OFFSET: 2 * conductorCount + 2 * BSDF_TABLE_ROUGHNESS_SIZE,
  SIZE:
    2 * conductorCount +
    2 * BSDF_TABLE_ROUGHNESS_SIZE +
    2 * BSDF_TABLE_GLASS_IOR_SIZE * BSDF_TABLE_GLASS_ROUGHNESS_SIZE * BSDF_TABLE_GLASS_MU_SIZE,
} as const;

type V3 = [number, number, number];

/** Smith Λ for GGX at a direction of cosine μ (> 0) to the normal. */
export function ggxLambda(mu: number, alpha: number): number {
  const mu2 = mu * mu;
  return 0.5 * (Math.sqrt(1 + (alpha * alpha * (1 - mu2)) / mu2) - 1);
}

/** Exact unpolarized Fresnel reflectance at cos θi ≥ 0 for relative index η = n_t / n_i (1 at TIR). */
export function fresnelDielectric(cosI: number, eta: number): number {
  const sin2T = (1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return 1;
  const cosT = Math.sqrt(1 - sin2T);
  const rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  const rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

/**
 * A GGX microfacet normal from the distribution of normals visible from wo (wo.z > 0), Heitz 2018:
 * stretch wo to the alpha = 1 configuration, pick a point on the projected hemisphere (a disk whose
 * far half is squashed by the view), lift it to the hemisphere and unstretch the normal.
 */
export function sampleGgxVndf(wo: V3, alpha: number, u1: number, u2: number): V3 {
  const vx = alpha * wo[0], vy = alpha * wo[1], vz = wo[2];
  const vl = Math.sqrt(vx * vx + vy * vy + vz * vz);
  const hx = vx / vl, hy = vy / vl, hz = vz / vl;
  const lensq = hx * hx + hy * hy;
  let t1x = 1, t1y = 0;
  if (lensq > 0) {
    const inv = 1 / Math.sqrt(lensq);
    t1x = -hy * inv;
    t1y = hx * inv;
  }
  // T2 = Vh × T1 (T1 has no z component).
  const t2x = -hz * t1y, t2y = hz * t1x, t2z = hx * t1y - hy * t1x;
  const r = Math.sqrt(u1);
  const phi = 2 * Math.PI * u2;
  const p1 = r * Math.cos(phi);
  const s = 0.5 * (1 + hz);
  const p2 = (1 - s) * Math.sqrt(1 - p1 * p1) + s * r * Math.sin(phi);
  const pz = Math.sqrt(Math.max(0, 1 - p1 * p1 - p2 * p2));
  const nx = p1 * t1x + p2 * t2x + pz * hx;
  const ny = p1 * t1y + p2 * t2y + pz * hy;
  const nz = p2 * t2z + pz * hz;
  const mx = alpha * nx, my = alpha * ny, mz = Math.max(0, nz);
  const ml = Math.sqrt(mx * mx + my * my + mz * mz);
  return [mx / ml, my / ml, mz / ml];
}

/** E1 and E5 of a GGX conductor at cosine mu: the mean VNDF weight G2/G1 (times (1 − c)⁵ for E5). */
export function conductorAlbedo(mu: number, alpha: number, points = CONDUCTOR_POINTS): { e1: number; e5: number } {
  const v = visibleNormals(mu, alpha, points);
  let e1 = 0, e5 = 0;
  for (let k = 0; k < v.cells; k++) {
    e1 += v.reflected[k]!;
    e5 += v.reflected[k]! * (1 - v.c[k]!) ** 5;
  }
  return { e1, e5 };
}

/** Visible normals of the quadrature lattice for wo = (√(1−μ²), 0, μ): wo·m, m.z and the reflected VNDF weight. */
interface VisibleNormals {
  readonly c: Float64Array;
  readonly mz: Float64Array;
  /** The cell's share of the square (du1/dv · cell area): the quadrature weights, summing to 1. */
  readonly weight: Float64Array;
  /** G2/G1 of the mirror direction times the weight, 0 where it falls below the horizon. */
  readonly reflected: Float64Array;
  readonly lambdaO: number;
  /** The number of lattice points (including those whose normal faces away, which count as 0). */
  readonly cells: number;
}

function visibleNormals(mu: number, alpha: number, points: number): VisibleNormals {
  const wo: V3 = [Math.sqrt(1 - mu * mu), 0, mu];
  const lambdaO = ggxLambda(mu, alpha);
  const n = points;
  const c = new Float64Array(n), mz = new Float64Array(n), weight = new Float64Array(n), reflected = new Float64Array(n);
  for (let k = 0; k < n; k++) {
    // A Fibonacci lattice rather than a tensor grid: where the integrand jumps along a curve (the
    // horizon, the critical angle) that lines up with a grid row (at μ = 1 those curves are circles,
    // i.e. rows of constant u1), a grid's errors add up row by row; a lattice's cancel.
    const v = (k + 0.5) / n;
    const u2 = HALF_START + 0.5 * ((k * GOLDEN_FRACTION + 0.5 / n) % 1);
    const u1 = 1 - (1 - v) ** TAIL_POWER;
    const w = (TAIL_POWER * (1 - v) ** (TAIL_POWER - 1)) / n;
    const m = sampleGgxVndf(wo, alpha, u1, u2);
    c[k] = wo[0] * m[0] + wo[2] * m[2];
    mz[k] = m[2];
    weight[k] = w;
    const wrz = 2 * c[k]! * m[2] - mu;
    reflected[k] = wrz > 0 && c[k]! > 0 ? (w * (1 + lambdaO)) / (1 + lambdaO + ggxLambda(wrz, alpha)) : 0;
  }
  return { c, mz, weight, reflected, lambdaO, cells: n };
}

function glassAlbedoOf(v: VisibleNormals, mu: number, alpha: number, eta: number): number {
  // The hot loop of the table (ior × side × points per entry): Fresnel inlined so that cos θt,
  // needed by both F and the refracted direction, is computed once.
  const onePlusLambdaO = 1 + v.lambdaO;
  const invEta = 1 / eta;
  const invEta2 = invEta * invEta;
  let e = 0;
  for (let k = 0; k < v.cells; k++) {
    const c = v.c[k]!;
    if (c <= 0) continue;
    const sin2T = (1 - c * c) * invEta2;
    if (sin2T >= 1) {
      e += v.reflected[k]!; // total internal reflection: F = 1
      continue;
    }
    const cosT = Math.sqrt(1 - sin2T);
    const rs = (c - eta * cosT) / (c + eta * cosT);
    const rp = (eta * c - cosT) / (eta * c + cosT);
    const f = 0.5 * (rs * rs + rp * rp);
    e += f * v.reflected[k]!;
    // Refraction through m: wt = −wo/η + (c/η − cos θt) m.
    const wtz = -mu * invEta + (c * invEta - cosT) * v.mz[k]!;
    if (wtz < 0) e += (v.weight[k]! * (1 - f) * onePlusLambdaO) / (onePlusLambdaO + ggxLambda(-wtz, alpha));
  }
  return e;
}

/** Reflectance + transmittance (no 1/η² factor) of a rough interface of relative index eta, wo.z = mu. */
export function glassAlbedo(mu: number, alpha: number, eta: number, points = GLASS_POINTS): number {
  return glassAlbedoOf(visibleNormals(mu, alpha, points), mu, alpha, eta);
}

export function tableMu(j: number, size: number): number {
  return Math.max(MU_MIN, j / (size - 1));
}

export function tableAlpha(i: number, size: number): number {
  const r = i / (size - 1);
  return Math.max(ALPHA_MIN, r * r);
}

export function tableIor(k: number): number {
  return BSDF_TABLE_IOR_MIN + ((BSDF_TABLE_IOR_MAX - BSDF_TABLE_IOR_MIN) * k) / (BSDF_TABLE_GLASS_IOR_SIZE - 1);
}

/** 2∫₀¹ E(μ) μ dμ of the piecewise-linear interpolant through nodes at μ = j/(n−1). */
function cosineWeightedMean(values: ArrayLike<number>, offset: number, n: number): number {
  const h = 1 / (n - 1);
  let sum = 0;
  for (let j = 0; j + 1 < n; j++) {
    const a = j * h, b = a + h;
    // ∫ₐᵇ (Eₐ(b − μ) + E_b(μ − a))/h · μ dμ = h/6 · (Eₐ(2a + b) + E_b(a + 2b))
    sum += (h / 6) * (values[offset + j]! * (2 * a + b) + values[offset + j + 1]! * (a + 2 * b));
  }
  return 2 * sum;
}

let cached: Float32Array | undefined;

/** The whole table buffer (BSDF_TABLE_LAYOUT), built once per process and shared. */
export function bsdfTableData(): Float32Array {
  if (cached) return cached;
  const L = BSDF_TABLE_LAYOUT;
  const t = new Float32Array(L.SIZE);
  const nMu = BSDF_TABLE_MU_SIZE, nR = BSDF_TABLE_ROUGHNESS_SIZE;
  for (let i = 0; i < nR; i++) {
    const alpha = tableAlpha(i, nR);
    for (let j = 0; j < nMu; j++) {
      const { e1, e5 } = conductorAlbedo(tableMu(j, nMu), alpha);
      t[L.E1_OFFSET + i * nMu + j] = e1;
      t[L.E5_OFFSET + i * nMu + j] = e5;
    }
    t[L.E1_AVG_OFFSET + i] = cosineWeightedMean(t, L.E1_OFFSET + i * nMu, nMu);
    t[L.E5_AVG_OFFSET + i] = cosineWeightedMean(t, L.E5_OFFSET + i * nMu, nMu);
  }
  const gMu = BSDF_TABLE_GLASS_MU_SIZE, gR = BSDF_TABLE_GLASS_ROUGHNESS_SIZE, gI = BSDF_TABLE_GLASS_IOR_SIZE;
  // The visible normals depend on (μ, α) only: one set serves every ior and both sides.
  for (let i = 0; i < gR; i++) {
    const alpha = tableAlpha(i, gR);
    for (let j = 0; j < gMu; j++) {
      const mu = tableMu(j, gMu);
      const normals = visibleNormals(mu, alpha, GLASS_POINTS);
      for (let side = 0; side < 2; side++) {
        for (let k = 0; k < gI; k++) {
          const ior = tableIor(k);
          const eta = side === 0 ? ior : 1 / ior;
          t[L.GLASS_OFFSET + ((side * gI + k) * gR + i) * gMu + j] = glassAlbedoOf(normals, mu, alpha, eta);
        }
      }
    }
  }
  cached = t;
  return t;
}

/** Values a row of the bsdf_tables texture (BSDF_TABLE_TEXTURE_WIDTH in shaders/scene/bsdf-tables.wgsl). */
export const BSDF_TABLE_TEXTURE_WIDTH = 1024;
/** The bsdf_tables texture's format: f32 values as their bits. */
export const BSDF_TABLE_TEXTURE_FORMAT: GPUTextureFormat = 'r32uint';

/**
 * The table as the texels of the `bsdf_tables` texture (binding 12 of the scene group): rows of
 * BSDF_TABLE_TEXTURE_WIDTH values, the last padded with zeros.
 */
export function bsdfTableTexture(): { width: number; height: number; data: Float32Array } {
  const t = bsdfTableData();
  const height = Math.ceil(t.length / BSDF_TABLE_TEXTURE_WIDTH);
  const data = new Float32Array(BSDF_TABLE_TEXTURE_WIDTH * height);
  data.set(t);
  return { width: BSDF_TABLE_TEXTURE_WIDTH, height, data };
}
