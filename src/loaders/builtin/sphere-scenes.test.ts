import { describe, expect, it } from 'vitest';
import { traverseClosest } from '../../bvh/traverse.ts';
import { cameraBasis } from '../../gpu/view.ts';
import { prepareScene } from '../../renderer/prepare.ts';
import { PRIMITIVE_KIND } from '../../scene/triangles.ts';
import { expectLanternError } from '../../expect-lantern-error.ts';
import { isIdentity } from '../../math/mat4.ts';
import { seededRandom } from '../../math/seeded-random.ts';
import { add, dot, length, normalize, scale, sub, type Vec3 } from '../../math/vec3.ts';
import type { Environment } from '../../scene/environment.ts';
import { inView } from '../../scene/framing.ts';
import type { Mesh, Scene } from '../../scene/types.ts';
import { builtinScene, isBuiltinScene } from './index.ts';
import { GOLD } from './materials.ts';
import { GOLDEN_GRID } from './golden-grid.ts';
import { HEX_GRID } from './hex-grid.ts';
import { fuzzToRoughness, RTIOW_DEFAULT_SEED } from './rtiow.ts';

const SPHERE_SCENES = ['spheres', 'rtiow', 'orb', 'golden-grid', 'hex-grid', 'caffeine'] as const;

interface WorldSphere {
  readonly center: Vec3;
  readonly radius: number;
  readonly material: number;
}

/** Every sphere of the scene (its meshes are placed untransformed: checked here). */
function spheresOf(scene: Scene): WorldSphere[] {
  return scene.instances.flatMap((instance) => {
    const mesh = scene.meshes[instance.mesh] as Mesh;
    const s = mesh.spheres;
    if (!s) return [];
    expect(isIdentity(instance.worldFromObject)).toBe(true);
    return Array.from(s.radii, (radius, i) => ({ center: [s.centers[3 * i]!, s.centers[3 * i + 1]!, s.centers[3 * i + 2]!] as Vec3, radius, material: s.materialIds[i]! }));
  });
}


/** The gradient environment's radiance in direction y (scene/environment.ts: linear in y either side of the horizon). */
function gradient(environment: Environment | undefined, y: number): Vec3 {
  if (environment?.kind !== 'gradient') throw new Error('not a gradient sky');
  const { zenith, horizon, ground } = environment;
  const to = y >= 0 ? zenith : ground;
  return add(horizon, scale(sub(to, horizon), Math.abs(y)));
}

describe('sphere scenes: structure', () => {
  it.each(SPHERE_SCENES)('%s: spheres are analytic, well formed and lit', (name) => {
    const scene = builtinScene(name);
    const spheres = spheresOf(scene);
    expect(spheres.length).toBeGreaterThan(0);
    for (const mesh of scene.meshes) {
      const s = mesh.spheres;
      if (s) {
        expect(s.centers.length).toBe(3 * s.radii.length);
        expect(s.materialIds.length).toBe(s.radii.length);
      }
      const c = mesh.capsules;
      if (c) {
        expect(c.endpoints.length).toBe(6 * c.radii.length);
        expect(c.materialIds.length).toBe(c.radii.length);
        for (const r of c.radii) expect(r).toBeGreaterThan(0);
        for (const m of c.materialIds) expect(m).toBeLessThan(scene.materials.length);
      }
    }
    for (const s of spheres) {
      expect(s.center.every(Number.isFinite)).toBe(true);
      expect(s.radius).toBeGreaterThan(0);
      expect(s.material).toBeLessThan(scene.materials.length);
    }
    // Lit: an environment with radiance, or an emitter that something draws.
    const emitters = new Set(scene.materials.flatMap((m, i) => (m.emission.some((e) => e > 0) ? [i] : [])));
    const drawnEmitter = spheres.some((s) => emitters.has(s.material)) || scene.meshes.some((m) => [...m.materialIds].some((id) => emitters.has(id)));
    const env = scene.environment;
    const envLit = env !== undefined && env.kind !== 'none' && !(env.kind === 'constant' && env.radiance.every((c) => c === 0));
    expect(drawnEmitter || envLit).toBe(true);
    // The camera looks at something: the first listed sphere that is not a ground sphere is in view.
    const subject = spheres.find((s) => s.radius < 50)!;
    expect(inView(scene.camera, subject.center, 16 / 9)).toBe(true);
  });

  it.each(SPHERE_SCENES)('%s: seen from its camera (pinhole rays through the CPU oracle), its subject spans a good part of a 16:9 frame', (name) => {
    const prepared = prepareScene(builtinScene(name));
    const { bvh, triangles } = prepared;
    const b = cameraBasis(prepared.scene.camera, 16 / 9);
    // The subject: spheres and capsules, less any ground sphere (radius 50 or more).
    const isSubject = (primitive: number) => {
      const kind = triangles.kinds[primitive];
      if (kind === PRIMITIVE_KIND.capsule) return true;
      if (kind !== PRIMITIVE_KIND.sphere) return false;
      const mesh = prepared.scene.meshes[prepared.scene.instances[triangles.instanceIds[primitive]!]!.mesh]!;
      return mesh.spheres!.radii[triangles.meshTriangleIds[primitive]!]! < 50;
    };
    const [W, H] = [32, 18];
    let subject = 0;
    let centre = false;
    const xs: number[] = [], ys: number[] = [];
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        const nx = (2 * (x + 0.5)) / W - 1, ny = 1 - (2 * (y + 0.5)) / H;
        const direction = [0, 1, 2].map((k) => b.forward[k]! + nx * b.right[k]! + ny * b.up[k]!) as unknown as Vec3;
        const hit = traverseClosest(bvh, triangles.positions, { origin: b.position, direction }, triangles.kinds);
        if (hit && isSubject(hit.triangle)) {
          subject++;
          xs.push(x);
          ys.push(y);
          if (Math.abs(x - W / 2 + 0.5) <= 3 && Math.abs(y - H / 2 + 0.5) <= 2) centre = true;
        }
      }
    }
    // Framed: the subject spans at least half the frame's width or height and leaves something else
    // in view, some of it near the centre. (Coverage is low for a ball-and-stick molecule, sticks and
    // small balls with space between: caffeine covers about 6 %.)
    expect(subject / (W * H)).toBeGreaterThan(0.04);
    expect(subject / (W * H)).toBeLessThan(0.97);
    const span = Math.max((Math.max(...xs) - Math.min(...xs) + 1) / W, (Math.max(...ys) - Math.min(...ys) + 1) / H);
    expect(span).toBeGreaterThan(0.5);
    expect(centre).toBe(true);
  });

  it('a built-in parameter only where the scene takes one', () => {
    expect(isBuiltinScene('rtiow')).toBe(true);
    expect(isBuiltinScene('rtiow:42')).toBe(true);
    expect(isBuiltinScene('cornell:42')).toBe(false);
    expectLanternError(() => builtinScene('cornell:42'), /the scene 'cornell' takes no parameter/);
    expectLanternError(() => builtinScene('rtiow:seven'), /'rtiow:seven': the seed must be a whole number/);
    expectLanternError(() => builtinScene('rtiow:-1'), /the seed must be a whole number/);
    expectLanternError(() => builtinScene('rtiow:4294967296'), /the seed must be a whole number/);
  });
});

describe('rtiow', () => {
  it('the same seed gives the same scene, another seed another field; the plain name is the default seed', () => {
    expect(builtinScene('rtiow:7')).toEqual(builtinScene('rtiow:7'));
    expect(spheresOf(builtinScene('rtiow:7'))).not.toEqual(spheresOf(builtinScene('rtiow:8')));
    expect({ ...builtinScene(`rtiow:${RTIOW_DEFAULT_SEED}`), name: 'rtiow' }).toEqual(builtinScene('rtiow'));
    expect(builtinScene('rtiow:7').name).toBe('rtiow:7');
  });

  it("follows the book: ground, three large spheres, a 22 × 22 field of small ones clear of (4, 0.2, 0)", () => {
    for (const seed of [1, 2, 3]) {
      const scene = builtinScene(`rtiow:${seed}`);
      const [ground, glass, brown, bronze, ...small] = spheresOf(scene) as [WorldSphere, WorldSphere, WorldSphere, WorldSphere, ...WorldSphere[]];
      const material = (s: WorldSphere) => scene.materials[s.material]!;
      expect(ground).toMatchObject({ center: [0, -1000, 0], radius: 1000 });
      expect(material(ground)).toMatchObject({ kind: 'diffuse', albedo: [0.5, 0.5, 0.5] });
      expect(glass).toMatchObject({ center: [0, 1, 0], radius: 1 });
      expect(material(glass)).toMatchObject({ kind: 'dielectric', ior: 1.5, roughness: 0 });
      expect(brown).toMatchObject({ center: [-4, 1, 0], radius: 1 });
      expect(material(brown)).toMatchObject({ kind: 'diffuse', albedo: [0.4, 0.2, 0.1] });
      expect(bronze).toMatchObject({ center: [4, 1, 0], radius: 1 });
      expect(material(bronze)).toMatchObject({ kind: 'metallic-roughness', metallic: 1, roughness: 0, baseColor: [0.7, 0.6, 0.5] });

      // Each cell (a, b) holds at most one sphere, inside [a, a + 0.9] × [b, b + 0.9]; most cells hold one.
      expect(small.length).toBeGreaterThan(470);
      expect(small.length).toBeLessThanOrEqual(484);
      const cells = new Set<string>();
      for (const s of small) {
        expect(s.radius).toBeCloseTo(0.2, 6);
        expect(s.center[1]).toBeCloseTo(0.2, 6);
        const a = Math.floor(s.center[0]), b = Math.floor(s.center[2]);
        expect(a).toBeGreaterThanOrEqual(-11);
        expect(a).toBeLessThanOrEqual(10);
        expect(b).toBeGreaterThanOrEqual(-11);
        expect(b).toBeLessThanOrEqual(10);
        expect(s.center[0] - a).toBeLessThanOrEqual(0.9 + 1e-6);
        expect(s.center[2] - b).toBeLessThanOrEqual(0.9 + 1e-6);
        cells.add(`${a},${b}`);
        expect(length(sub(s.center, [4, 0.2, 0]))).toBeGreaterThan(0.9);
      }
      expect(cells.size).toBe(small.length);

      // Materials in the book's proportions (80 % diffuse, 15 % metal, 5 % glass; ±6 % for ~480 draws)
      // and ranges: diffuse albedo a product of two uniforms, metal albedo in [0.5, 1], fuzz ≤ 0.5.
      const kinds = { diffuse: 0, metal: 0, glass: 0 };
      for (const s of small) {
        const m = material(s);
        if (m.kind === 'diffuse') {
          kinds.diffuse++;
          for (const c of m.albedo) expect(c >= 0 && c <= 1).toBe(true);
        } else if (m.kind === 'metallic-roughness') {
          kinds.metal++;
          for (const c of m.baseColor) expect(c >= 0.5 && c <= 1).toBe(true);
          expect(m.roughness).toBeLessThanOrEqual(fuzzToRoughness(0.5) + 1e-12);
        } else {
          kinds.glass++;
          expect(m).toMatchObject({ kind: 'dielectric', ior: 1.5 });
        }
      }
      expect(Math.abs(kinds.diffuse / small.length - 0.8)).toBeLessThan(0.06);
      expect(Math.abs(kinds.metal / small.length - 0.15)).toBeLessThan(0.06);
      expect(Math.abs(kinds.glass / small.length - 0.05)).toBeLessThan(0.04);
      // The mean of a product of two uniforms is 1/4.
      const albedos = small.map(material).flatMap((m) => (m.kind === 'diffuse' ? [...m.albedo] : []));
      expect(albedos.reduce((x, y) => x + y, 0) / albedos.length).toBeCloseTo(0.25, 1);
    }
  });

  it("has the book's camera, lens and sky", () => {
    const scene = builtinScene('rtiow');
    const camera = scene.camera;
    expect(camera.position).toEqual([13, 2, 3]);
    const f = normalize(camera.forward);
    for (const [i, v] of normalize([-13, -2, -3]).entries()) expect(f[i]).toBeCloseTo(v, 12);
    expect(camera.up).toEqual([0, 1, 0]);
    expect(camera.vfovDegrees).toBe(20);
    expect(camera.lens).toEqual({ apertureRadius: 0.05, focusDistance: 10 });
    // The book: (1 - t)·white + t·(0.5, 0.7, 1.0) with t = 0.5·(y + 1).
    for (const y of [-1, -0.6, -0.1, 0, 0.3, 0.5, 1]) {
      const t = 0.5 * (y + 1);
      const book: Vec3 = [1 - t + 0.5 * t, 1 - t + 0.7 * t, 1];
      const ours = gradient(scene.environment, y);
      for (let c = 0; c < 3; c++) expect(ours[c]).toBeCloseTo(book[c]!, 12);
    }
  });

  it('fuzz maps to a GGX roughness whose reflected lobe is as wide as the fuzzed one', () => {
    expect(fuzzToRoughness(0)).toBe(0);
    // Monte Carlo over the book's fuzz: the mean square angle between r and normalize(r + fuzz·u),
    // u uniform in the unit ball, against the 2α (α = roughness²) RMS tilt of a GGX reflection.
    const random = seededRandom(11);
    for (const fuzz of [0.05, 0.1]) {
      let sum = 0;
      const n = 20000;
      for (let i = 0; i < n; i++) {
        let u: Vec3;
        do u = [2 * random() - 1, 2 * random() - 1, 2 * random() - 1];
        while (dot(u, u) > 1);
        const d = normalize(add([0, 0, 1], scale(u, fuzz)));
        sum += Math.acos(Math.min(1, d[2])) ** 2;
      }
      const rms = Math.sqrt(sum / n);
      const alpha = fuzzToRoughness(fuzz) ** 2;
      expect(rms / (2 * alpha)).toBeGreaterThan(0.95);
      expect(rms / (2 * alpha)).toBeLessThan(1.05);
    }
  });
});

describe('the other sphere scenes', () => {
  it('spheres: ground, diffuse, glass and metal spheres and an emissive sphere lamp under a gradient sky', () => {
    const scene = builtinScene('spheres');
    const kinds = spheresOf(scene).map((s) => scene.materials[s.material]!.kind);
    expect(kinds).toEqual(['diffuse', 'diffuse', 'dielectric', 'metallic-roughness', 'emissive']);
    expect(scene.environment?.kind).toBe('gradient');
    for (const s of spheresOf(scene).slice(1, 4)) expect(inView(scene.camera, s.center, 16 / 9)).toBe(true);
  });

  it('orb: a glass orb resting on a polished floor, a lamp above to the side, the caustic spot in view', () => {
    const scene = builtinScene('orb');
    const [orb, lamp] = spheresOf(scene) as [WorldSphere, WorldSphere];
    expect(scene.materials[orb.material]).toMatchObject({ kind: 'dielectric', ior: 1.5, roughness: 0 });
    expect(orb.center[1] - orb.radius).toBeCloseTo(0, 6); // resting on the floor y = 0
    expect(scene.materials[lamp.material]!.kind).toBe('emissive');
    expect(lamp.center[1]).toBeGreaterThan(orb.center[1] + orb.radius);
    const floor = scene.materials[scene.meshes[0]!.materialIds[0]!]!;
    expect(floor).toMatchObject({ kind: 'metallic-roughness', metallic: 0 });
    expect(floor.kind === 'metallic-roughness' && floor.roughness).toBeLessThan(0.2);
    // A ball lens focuses behind itself, on the far side from the lamp: the floor there is in view.
    const away = normalize(sub(orb.center, lamp.center));
    const t = -orb.center[1] / away[1];
    const spot = add(orb.center, scale(away, t));
    expect(inView(scene.camera, spot, 16 / 9)).toBe(true);
    expect(inView(scene.camera, orb.center, 16 / 9)).toBe(true);
  });

  it('golden-grid: a square grid of gold spheres on the floor, the lens focused on one of them', () => {
    const scene = builtinScene('golden-grid');
    const spheres = spheresOf(scene);
    expect(spheres).toHaveLength(GOLDEN_GRID.count ** 2);
    for (const s of spheres) {
      expect(scene.materials[s.material]).toMatchObject({ kind: 'metallic-roughness', metallic: 1, baseColor: GOLD });
      expect(s.center[1] - s.radius).toBeCloseTo(0, 6);
    }
    const xs = new Set(spheres.map((s) => s.center[0])), zs = new Set(spheres.map((s) => s.center[2]));
    expect(xs.size).toBe(GOLDEN_GRID.count);
    expect(zs.size).toBe(GOLDEN_GRID.count);
    expectFocusedOnASphere(scene, spheres);
  });

  it('hex-grid: every inner sphere has six neighbours at the spacing; the lens is focused on one sphere', () => {
    const scene = builtinScene('hex-grid');
    const spheres = spheresOf(scene);
    expect(spheres).toHaveLength(HEX_GRID.columns * HEX_GRID.rows);
    const neighbours = spheres.map((s) => spheres.filter((o) => Math.abs(length(sub(o.center, s.center)) - HEX_GRID.spacing) < 1e-5).length);
    expect(Math.max(...neighbours)).toBe(6);
    // Inner spheres (away from the edges) all have six.
    const xs = spheres.map((s) => s.center[0]), zs = spheres.map((s) => s.center[2]);
    const [x0, x1, z0, z1] = [Math.min(...xs), Math.max(...xs), Math.min(...zs), Math.max(...zs)];
    spheres.forEach((s, i) => {
      if (s.center[0] > x0 + 1.01 && s.center[0] < x1 - 1.01 && s.center[2] > z0 + 1 && s.center[2] < z1 - 1) expect(neighbours[i]).toBe(6);
    });
    // No two spheres overlap.
    expect(2 * HEX_GRID.radius).toBeLessThan(HEX_GRID.spacing);
    expectFocusedOnASphere(scene, spheres);
  });

  it('caffeine: the molecule in the studio, in Å', () => {
    const scene = builtinScene('caffeine');
    expect(scene.meshes[0]!.spheres!.radii).toHaveLength(24);
    expect(scene.meshes[0]!.capsules!.radii).toHaveLength(29);
    expect(scene.metersPerUnit).toBe(1e-10);
  });
});

/** A thin lens whose plane in focus passes through a sphere's centre that the camera sees. */
function expectFocusedOnASphere(scene: Scene, spheres: readonly WorldSphere[]): void {
  const lens = scene.camera.lens!;
  expect(lens.apertureRadius).toBeGreaterThan(0);
  const f = normalize(scene.camera.forward);
  // Centres are stored as float32: equal to 1e-5.
  const focused = spheres.filter((s) => Math.abs(dot(sub(s.center, scene.camera.position), f) - lens.focusDistance) < 1e-5);
  expect(focused.length).toBeGreaterThan(0);
  expect(focused.some((s) => inView(scene.camera, s.center, 16 / 9))).toBe(true);
  // Shallow: the nearest and farthest spheres lie well off the plane in focus.
  const depths = spheres.map((s) => dot(sub(s.center, scene.camera.position), f));
  expect(lens.focusDistance - Math.min(...depths)).toBeGreaterThan(2);
  expect(Math.max(...depths) - lens.focusDistance).toBeGreaterThan(2);
}
