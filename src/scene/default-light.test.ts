import { describe, expect, it } from 'vitest';
import { fromTrs, IDENTITY } from '../math/mat4.ts';
import { luminance } from '../math/vec3.ts';
import { decideDefaultLight, DEFAULT_SKY, defaultSkyIrradiance, describeShare, OWN_LIGHT_SHARE, ownIrradiance, withDefaultLight } from './default-light.ts';
import { withEnvironment } from './environment-override.ts';
import { DAYLIGHT_EXPOSURE_STOPS, SkyModel } from './sky.ts';
import { diffuse, type Camera, type Material, type Mesh, type PunctualLight, type Scene, type Texture } from './types.ts';

const camera: Camera = { position: [0, 0, 5], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 };

/** A w × h axis-aligned quad in the plane z = 0 at (x, y), as two triangles with uvs over [u0, u1] × [0, 1]. */
function quads(list: { x?: number; y?: number; w: number; h: number; material: number; u0?: number; u1?: number }[]): Mesh {
  const positions: number[] = [], uvs: number[] = [], indices: number[] = [], materialIds: number[] = [];
  for (const q of list) {
    const x = q.x ?? 0, y = q.y ?? 0, u0 = q.u0 ?? 0, u1 = q.u1 ?? 1;
    const base = positions.length / 3;
    positions.push(x, y, 0, x + q.w, y, 0, x + q.w, y + q.h, 0, x, y + q.h, 0);
    uvs.push(u0, 1, u1, 1, u1, 0, u0, 0);
    indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
    materialIds.push(q.material, q.material);
  }
  return { name: 'quads', positions: new Float32Array(positions), uvs: new Float32Array(uvs), indices: new Uint32Array(indices), materialIds: new Uint32Array(materialIds) };
}

function scene(meshes: Mesh[], materials: Material[], extra: Partial<Scene> = {}): Scene {
  return { name: 'test', meshes, instances: meshes.map((_, i) => ({ id: i, mesh: i, worldFromObject: IDENTITY })), materials, camera, ...extra };
}

const WHITE = diffuse('white', [0.8, 0.8, 0.8]);
const panel = (radiance: number, extra: Partial<Material> = {}): Material => ({ kind: 'emissive', name: 'panel', emission: [radiance, radiance, radiance], ...extra }) as Material;

/** w × h sRGB texels, white in the left half, black in the right. */
function halfWhite(w: number, h: number): Texture {
  const rgba = new Uint8Array(w * h * 4);
  for (let y = 0; y < h; y++) for (let x = 0; x < w / 2; x++) rgba.set([255, 255, 255, 255], (y * w + x) * 4);
  return { name: 'half', width: w, height: h, rgba };
}

describe('the light a scene brings', () => {
  it('is π L a / A of a Lambertian emitter over the reflecting area, at the camera exposure', () => {
    // A 1 × 1 panel of radiance 2 (black to light, so not counted in A) over 3 units of reflector.
    const s = scene([quads([{ w: 1, h: 1, material: 1 }, { w: 3, h: 1, material: 0 }])], [WHITE, panel(2)]);
    expect(ownIrradiance(s).irradiance).toBeCloseTo((Math.PI * 2 * 1) / 3, 10);
    expect(ownIrradiance({ ...s, camera: { ...camera, exposureStops: 1 } }).irradiance).toBeCloseTo((2 * Math.PI * 2) / 3, 10);
    // Both faces of a two-sided emitter send light.
    expect(ownIrradiance(scene(s.meshes.slice(), [WHITE, panel(2, { twoSidedEmission: true })])).irradiance).toBeCloseTo((2 * Math.PI * 2) / 3, 10);
    // An emitting reflector (a glTF material with emission) is part of A too.
    expect(ownIrradiance(scene(s.meshes.slice(), [WHITE, diffuse('glow', [0.5, 0.5, 0.5], [2, 2, 2])])).irradiance).toBeCloseTo((Math.PI * 2) / 4, 10);
  });

  it('weighs each placement by its area, and a material override as the instance shows it', () => {
    const mesh = quads([{ w: 1, h: 1, material: 1 }, { w: 3, h: 1, material: 0 }]);
    const one = ownIrradiance(scene([mesh], [WHITE, panel(2)])).irradiance;
    const twice = scene([mesh], [WHITE, panel(2)], {
      instances: [
        { id: 0, mesh: 0, worldFromObject: IDENTITY },
        { id: 1, mesh: 0, worldFromObject: fromTrs([5, 0, 0], [0, 0, 0.6, 0.8], [2, 2, 2]) },
      ],
    });
    // Scaled by 2, the second copy has 4 times the emitter and 4 times the reflector: the same ratio.
    expect(ownIrradiance(twice).irradiance).toBeCloseTo(one, 10);
    // The second copy shown all in white: its 16 units of area reflect, its panel no longer emits.
    const overridden = { ...twice, instances: [twice.instances[0]!, { ...twice.instances[1]!, material: 0 }] };
    expect(ownIrradiance(overridden).irradiance).toBeCloseTo((Math.PI * 2 * 1) / (3 + 16), 10);
  });

  it('reads an emission texture over each triangle’s uv footprint, repeating, after its transform', () => {
    const textures = [halfWhite(4, 2)];
    const lit = (u0: number, u1: number, extra: Partial<Material> = {}) =>
      ownIrradiance(scene([quads([{ w: 1, h: 1, material: 1, u0, u1 }, { w: 1, h: 1, material: 0 }])], [WHITE, panel(1, { emissionTexture: { texture: 0 }, ...extra })], { textures })).irradiance / (Math.PI / 1);
    expect(lit(0, 0.5)).toBeCloseTo(1, 10);
    expect(lit(0.5, 1)).toBeCloseTo(0, 10);
    expect(lit(0, 1)).toBeCloseTo(0.5, 10);
    // The texture repeats: u in [3, 3.5] is the white half again.
    expect(lit(3, 3.5)).toBeCloseTo(1, 10);
    expect(lit(-1, -0.5)).toBeCloseTo(1, 10);
    expect(lit(65536.5, 65537)).toBeCloseTo(0, 10);
    // KHR_texture_transform moves the white half's uvs onto the black half.
    expect(lit(0, 0.5, { emissionTexture: { texture: 0, transform: { offset: [0.5, 0], rotation: 0, scale: [1, 1] } } })).toBeCloseTo(0, 10);
    // A panorama-mapped emitter (Doom's sky) reads the whole texture.
    expect(lit(0, 0.5, { emissionMapping: { kind: 'panorama', repeats: 4, horizonV: 0.5, vPerRadian: 1 } })).toBeCloseTo(0.5, 10);
    // Linear data: code 51 is 0.2, not sRGB's 0.033.
    const grey: Texture = { name: 'grey', width: 1, height: 1, rgba: new Uint8Array([51, 51, 51, 255]), encoding: 'linear' };
    const greyLit = ownIrradiance(scene([quads([{ w: 1, h: 1, material: 1 }, { w: 1, h: 1, material: 0 }])], [WHITE, panel(1, { emissionTexture: { texture: 0 } })], { textures: [grey] })).irradiance;
    expect(greyLit / Math.PI).toBeCloseTo(0.2, 10);
  });

  it('reads a triangle without uvs at (0, 0), blended with its repeated neighbours as a bilinear lookup there is', () => {
    const mesh = quads([{ w: 1, h: 1, material: 1 }, { w: 1, h: 1, material: 0 }]);
    const { uvs: _uvs, ...bare } = mesh;
    const e = ownIrradiance(scene([bare], [WHITE, panel(1, { emissionTexture: { texture: 0 } })], { textures: [halfWhite(4, 2)] })).irradiance;
    expect(e / Math.PI).toBeCloseTo(0.5, 10);
  });

  it('averages a texture larger than its table down without changing the footprints’ means', () => {
    const e = (u0: number, u1: number) =>
      ownIrradiance(scene([quads([{ w: 1, h: 1, material: 1, u0, u1 }, { w: 1, h: 1, material: 0 }])], [WHITE, panel(1, { emissionTexture: { texture: 0 } })], { textures: [halfWhite(1500, 750)] })).irradiance / Math.PI;
    expect(e(0, 0.5)).toBeCloseTo(1, 6);
    expect(e(0.5, 1)).toBeCloseTo(0, 6);
    expect(e(0.25, 0.75)).toBeCloseTo(0.5, 3);
  });

  it('counts a point light’s 4πI as power and a directional light’s E as E/4 on average', () => {
    const mesh = quads([{ w: 2, h: 2, material: 0 }]);
    const lights: PunctualLight[] = [{ kind: 'point', name: 'bulb', position: [0, 0, 1], color: [1, 1, 1], intensity: 3, range: Infinity }];
    expect(ownIrradiance(scene([mesh], [WHITE], { lights })).irradiance).toBeCloseTo((4 * Math.PI * 3) / 4, 10);
    const sun: PunctualLight = { kind: 'directional', name: 'sun', direction: [0, -1, 0], color: [1, 1, 1], irradiance: 8 };
    expect(ownIrradiance(scene([mesh], [WHITE], { lights: [sun] })).irradiance).toBeCloseTo(2, 10);
    expect(ownIrradiance(scene([mesh], [WHITE])).hasLights).toBe(false);
  });
});

describe('the default sky', () => {
  it('delivers ¼ ∫ L dω at the daylight exposure: the midpoint rule agrees with a stratified Monte Carlo estimate', () => {
    const model = new SkyModel(DEFAULT_SKY);
    // Stratified uniform directions over the sphere (z = cos θ uniform in [−1, 1]).
    const n = 256;
    let sum = 0;
    let seed = 12345;
    const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    for (let i = 0; i < n; i++) {
      for (let j = 0; j < n; j++) {
        const y = -1 + (2 * (i + random())) / n, phi = (2 * Math.PI * (j + random())) / n, r = Math.sqrt(1 - y * y);
        sum += luminance(model.radiance([r * Math.sin(phi), y, r * Math.cos(phi)]));
      }
    }
    const integral = (4 * Math.PI * sum) / (n * n) + 2 * Math.PI * (1 - model.sunCosMax) * luminance(model.sunRadiance);
    expect(defaultSkyIrradiance() / ((integral / 4) * 2 ** DAYLIGHT_EXPOSURE_STOPS)).toBeCloseTo(1, 2);
    // About one at its exposure: a white surface under it shows ~0.3, a well-exposed image.
    expect(defaultSkyIrradiance()).toBeGreaterThan(0.5);
    expect(defaultSkyIrradiance()).toBeLessThan(2);
  });
});

describe('the default-light decision', () => {
  /** A unit box open at the front (+z): floor, ceiling, back and two sides, and a square ceiling light of side `light` and radiance `radiance`. */
  function openBox(radiance: number, light: number): Scene {
    // Each wall as a quad in the z = 0 plane placed by an instance: five reflectors of area 1, the panel just below the ceiling.
    const wall = quads([{ x: -0.5, y: -0.5, w: 1, h: 1, material: 0 }]);
    const lamp = quads([{ x: -light / 2, y: -light / 2, w: light, h: light, material: 1 }]);
    const r = Math.SQRT1_2;
    const place = (mesh: number, t: [number, number, number], q: [number, number, number, number]) => ({ id: 0, mesh, worldFromObject: fromTrs(t, q, [1, 1, 1]) });
    const instances = [
      place(0, [0, 0, -0.5], [0, 0, 0, 1]),
      place(0, [0, -0.5, 0], [-r, 0, 0, r]),
      place(0, [0, 0.5, 0], [r, 0, 0, r]),
      place(0, [-0.5, 0, 0], [0, r, 0, r]),
      place(0, [0.5, 0, 0], [0, -r, 0, r]),
      place(1, [0, 0.499, 0], [r, 0, 0, r]),
    ].map((inst, id) => ({ ...inst, id }));
    return { name: 'box', meshes: [wall, lamp], instances, materials: [WHITE, panel(radiance)], camera };
  }

  it('leaves a box lit by its own ceiling panel without a sky', () => {
    // The original Cornell box's light: radiance (17, 12, 4), luminance ≈ 12.5, over 1/16 of the ceiling.
    const d = decideDefaultLight(openBox(12.5, 0.25));
    expect(d.share).toBeCloseTo((Math.PI * 12.5 * 0.0625) / 5 / defaultSkyIrradiance(), 10);
    expect(d.sky).toBe(false);
    expect(d.note).toMatch(/^its own lights light it \(\d+ % of the light of a default sky\); no sky is added$/);
    const lit = withDefaultLight(openBox(12.5, 0.25));
    expect(lit.environment).toBeUndefined();
    expect(lit.camera).toEqual(camera);
  });

  it('gives a model with a tiny dim emitter the sky, and says how little its emitters give', () => {
    // A 1 mm² indicator of radiance 1 on a 1 m² panel.
    const s = scene([quads([{ w: 1, h: 1, material: 0 }, { w: 1e-3, h: 1e-3, material: 1 }])], [WHITE, panel(1)]);
    const d = decideDefaultLight(s);
    expect(d.sky).toBe(true);
    expect(d.hasLights).toBe(true);
    expect(d.note).toBe('its emitters give less than 0.001 % of the light of a default sky; a default sky lights it');
    const lit = withDefaultLight(s);
    expect(lit.environment).toEqual(DEFAULT_SKY);
    expect(lit.camera.exposureStops).toBeCloseTo(DAYLIGHT_EXPOSURE_STOPS, 12);
    expect(lit.lightingNote).toBe(d.note);
  });

  it('decides at OWN_LIGHT_SHARE of the sky’s light', () => {
    // A 1 × 1 panel over 1 unit of reflector: E_own = π L.
    const at = (share: number) => decideDefaultLight(scene([quads([{ w: 1, h: 1, material: 1 }, { w: 1, h: 1, material: 0 }])], [WHITE, panel((share * defaultSkyIrradiance()) / Math.PI)]));
    expect(at(OWN_LIGHT_SHARE * 0.99).sky).toBe(true);
    expect(at(OWN_LIGHT_SHARE * 1.01).sky).toBe(false);
    expect(at(OWN_LIGHT_SHARE * 1.01).share).toBeCloseTo(OWN_LIGHT_SHARE * 1.01, 10);
  });

  it('says when a model has no light at all', () => {
    const lit = withDefaultLight(scene([quads([{ w: 1, h: 1, material: 0 }])], [WHITE]));
    expect(lit.environment).toEqual(DEFAULT_SKY);
    expect(lit.lightingNote).toBe('the model has no light of its own; a default sky lights it');
  });

  it('gives way to an environment the user picks: none takes the sky, its exposure and the note away', () => {
    const lit = withDefaultLight(scene([quads([{ w: 1, h: 1, material: 0 }])], [WHITE]));
    const dark = withEnvironment(lit, { kind: 'none' });
    expect(dark.environment).toEqual({ kind: 'none' });
    expect(dark.camera.exposureStops).toBeCloseTo(0, 12);
    expect(dark.lightingNote).toBeUndefined();
  });

  it('writes the share with two figures', () => {
    expect(describeShare(0.0031)).toBe('0.31 % of the light of a default sky');
    expect(describeShare(0.4234)).toBe('42 % of the light of a default sky');
    expect(describeShare(3.14159)).toBe('3.1 times the light of a default sky');
    expect(describeShare(1e-9)).toBe('less than 0.001 % of the light of a default sky');
    expect(describeShare(0)).toBe('none of the light of a default sky');
  });
});
