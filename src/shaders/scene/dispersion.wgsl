// A material's index of refraction at a wavelength: its dispersion law (Sellmeier or Cauchy) scaled so
// that n(589.3 nm) is the material's ior. Expects the Material record of scene/types; scene/dispersion.ts
// is the TypeScript twin (the laws, the named glasses and the scaling).

#import scene/types

fn material_is_dispersive(material: Material) -> bool {
  return material.dispersion_law != DISPERSION_NONE;
}

// n(λ) for λ in nm.
fn material_ior_at(material: Material, lambda_nm: f32) -> f32 {
  let l2 = (lambda_nm * 1e-3) * (lambda_nm * 1e-3);
  var n_law: f32;
  if (material.dispersion_law == DISPERSION_SELLMEIER) {
    let terms = material.dispersion_b * l2 / (vec3f(l2) - material.dispersion_c);
    n_law = sqrt(1.0 + terms.x + terms.y + terms.z);
  } else if (material.dispersion_law == DISPERSION_CAUCHY) {
    n_law = material.dispersion_b.x + material.dispersion_b.y / l2;
  } else {
    return material.ior;
  }
  return 1.0 + material.dispersion_scale * (n_law - 1.0);
}
