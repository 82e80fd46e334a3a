/**
 * Dispersion laws: how a glass's index of refraction varies with wavelength, and the named glasses
 * of the catalogues. A material's `ior` stays its index at the sodium d line (589.3 nm, glTF's
 * convention for KHR_materials_ior); the law gives the shape of n(λ) and is scaled to pass through it:
 *
 *   n(λ) = 1 + (ior − 1) · (n_law(λ) − 1) / (n_law(589.3 nm) − 1)
 *
 * which keeps the law's Abbe number (n_d − 1)/(n_F − n_C) whatever `ior` is (so "BK7's dispersion at
 * ior 1.6" means a glass as dispersive as BK7 relative to its refractivity). With `ior` equal to the
 * glass's own n_d the scale is 1 and n(λ) is the catalogue's.
 *
 * Laws (λ in micrometres in the formulas, as the catalogues print them):
 * - Sellmeier: n² = 1 + Σᵢ Bᵢ λ² / (λ² − Cᵢ)   (Schott's form, C in µm²)
 * - Cauchy:    n = A + B / λ²                    (B in µm²)
 * - Abbe:      the Cauchy law with n_d = ior and n_F − n_C = (ior − 1)/V_d (KHR_materials_dispersion
 *              stores 20/V_d); F = 486.13 nm, C = 656.27 nm.
 */
import { LanternError } from '../errors.ts';

export type Dispersion =
  | { readonly kind: 'sellmeier'; readonly B: readonly [number, number, number]; readonly C: readonly [number, number, number] }
  | { readonly kind: 'cauchy'; readonly A: number; readonly B: number }
  | { readonly kind: 'abbe'; readonly abbeNumber: number };

/** Fraunhofer lines (nm): d (helium/sodium, 587.6/589.3: glTF and this file use 589.3), F (hydrogen blue), C (hydrogen red). */
export const LAMBDA_D = 589.3;
export const LAMBDA_F = 486.13;
export const LAMBDA_C = 656.27;

/**
 * Named glasses by their published Sellmeier coefficients: Schott's catalogue (N-BK7, F2, SF11) and
 * Malitson 1965 (fused silica). n_d: 1.5168, 1.6200, 1.7847, 1.4585; Abbe numbers 64.2, 36.4, 25.7, 67.8.
 */
export const GLASSES = {
  BK7: { kind: 'sellmeier', B: [1.03961212, 0.231792344, 1.01046945], C: [0.00600069867, 0.0200179144, 103.560653] },
  F2: { kind: 'sellmeier', B: [1.34533359, 0.209073176, 0.937357162], C: [0.00997743871, 0.0470450767, 111.886764] },
  SF11: { kind: 'sellmeier', B: [1.73759695, 0.313747346, 1.89878101], C: [0.013188707, 0.0623068142, 155.23629] },
  'fused silica': { kind: 'sellmeier', B: [0.6961663, 0.4079426, 0.8974794], C: [0.0046791482, 0.0135120631, 97.9340025] },
} as const satisfies Record<string, Dispersion>;
export type GlassName = keyof typeof GLASSES;

/** The law's own index at `lambdaNm`, before scaling to a material's ior (Abbe: undefined, it has none of its own). */
function lawIndex(d: Exclude<Dispersion, { kind: 'abbe' }>, lambdaNm: number): number {
  const l2 = (lambdaNm / 1000) ** 2;
  if (d.kind === 'cauchy') return d.A + d.B / l2;
  let n2 = 1;
  for (let i = 0; i < 3; i++) n2 += (d.B[i]! * l2) / (l2 - d.C[i]!);
  return Math.sqrt(n2);
}

/** The Cauchy law with n(589.3) = ior and n_F − n_C = (ior − 1)/V. */
export function cauchyFromAbbe(ior: number, abbeNumber: number): { readonly kind: 'cauchy'; readonly A: number; readonly B: number } {
  const inv2 = (nm: number) => 1 / (nm / 1000) ** 2;
  const B = (ior - 1) / (abbeNumber * (inv2(LAMBDA_F) - inv2(LAMBDA_C)));
  return { kind: 'cauchy', A: ior - B * inv2(LAMBDA_D), B };
}

/**
 * What the GPU evaluates (shaders/scene/dispersion.wgsl): a Sellmeier or Cauchy law and the scale of
 * (n_law − 1) that puts n(589.3 nm) at the material's ior.
 */
export interface PackedDispersion {
  readonly law: 'sellmeier' | 'cauchy';
  readonly b: readonly [number, number, number];
  readonly c: readonly [number, number, number];
  readonly scale: number;
}

export function packDispersion(ior: number, d: Dispersion): PackedDispersion {
  const law = d.kind === 'abbe' ? cauchyFromAbbe(ior, d.abbeNumber) : d;
  const scale = (ior - 1) / (lawIndex(law, LAMBDA_D) - 1);
  return law.kind === 'cauchy'
    ? { law: 'cauchy', b: [law.A, law.B, 0], c: [0, 0, 0], scale }
    : { law: 'sellmeier', b: law.B, c: law.C, scale };
}

/** The index of refraction at `lambdaNm` of a material with index `ior` at 589.3 nm and dispersion `d`. */
export function iorAt(ior: number, d: Dispersion | undefined, lambdaNm: number): number {
  if (!d) return ior;
  const law = d.kind === 'abbe' ? cauchyFromAbbe(ior, d.abbeNumber) : d;
  const p = packDispersion(ior, d);
  return 1 + p.scale * (lawIndex(law, lambdaNm) - 1);
}

/** The Abbe number V_d = (n_d − 1)/(n_F − n_C) of a dispersion at ior. */
export function abbeNumberOf(ior: number, d: Dispersion): number {
  return (ior - 1) / (iorAt(ior, d, LAMBDA_F) - iorAt(ior, d, LAMBDA_C));
}

/** Refuses laws that give no index (non-finite, a pole inside the visible span, n ≤ 1). `where` names the material. */
export function validateDispersion(where: string, ior: number, d: Dispersion): void {
  const fail = (why: string) => {
    throw new LanternError(`${where} has an invalid dispersion (${d.kind}): ${why}`, 'give a Sellmeier law (B, C in µm²), a Cauchy law (A, B in µm²) or an Abbe number > 0');
  };
  switch (d.kind) {
    case 'abbe':
      if (!(d.abbeNumber > 0 && Number.isFinite(d.abbeNumber))) fail(`Abbe number ${d.abbeNumber} is not a positive number`);
      break;
    case 'cauchy':
      if (![d.A, d.B].every(Number.isFinite) || !(d.A > 1)) fail(`A = ${d.A}, B = ${d.B}: A must be > 1 and both finite`);
      break;
    case 'sellmeier':
      if (![...d.B, ...d.C].every(Number.isFinite) || d.C.some((c) => c < 0)) fail('every B and C must be finite and C ≥ 0');
      // A pole (λ² = C) between 360 and 830 nm would make n infinite there.
      if (d.C.some((c) => c >= 0.36 ** 2 && c <= 0.83 ** 2)) fail('a Sellmeier pole (C = λ²) lies inside 360–830 nm');
      break;
  }
  for (const lambda of [360, LAMBDA_F, LAMBDA_D, LAMBDA_C, 830]) {
    const n = iorAt(ior, d, lambda);
    if (!(n > 1 && n < 10)) fail(`n(${lambda} nm) = ${n} is outside (1, 10)`);
  }
}
