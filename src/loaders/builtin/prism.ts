/**
 * The prism: Newton's experiment. A narrow beam of white light leaves a black lamp box through a slit
 * (an emissive strip at the box's back), crosses an equilateral prism of dense flint (Schott SF11,
 * ior 1.7847 at 589.3 nm) at the minimum deviation of 589.3 nm, and falls on a screen 20 cm away, which
 * the camera looks at square-on. In spectral mode the screen shows a spectrum, red (bent least) on the
 * image's right, blue on its left, 400–700 nm over ~4 cm; RGB mode, which ignores dispersion, shows one
 * white band where 589.3 nm lands. Units are centimetres; the scene is flat (the plane y = 0 holds
 * every ray that matters) and extruded ±5 cm in y. The prism's base is blackened.
 *
 * Layout (top view, the xz plane; 2D points (u, v) are 3D (x = u, z = v)): prism base from (−3, 0) to
 * (3, 0), apex (0, 3√3); the beam enters the left face at its middle, travels parallel to the base
 * inside (minimum deviation for 589.3 nm) and leaves the right face toward the screen.
 * screenPosition(λ) is where the beam's axis lands, from Snell's law and the Sellmeier law: the oracle
 * of tests/gpu/spectral.test.ts.
 *
 * Convergence aid: the screen scatters only within the scene's plane (DiffuseMaterial.scatterPlaneNormal
 * = +y). A camera path reaches the light only by refraction (no light sample passes through glass), so
 * a Lambertian screen finds the beam only when its random direction falls, in two dimensions, into the
 * slit's small acceptance; in-plane scattering makes that a one-dimensional target, and keeps every
 * ray in the plane, where the prism's deviation is the textbook one (rays tilted out of the plane see
 * a larger effective index and smear the spectrum). Measured (tests/gpu/spectral.test.ts, spectral mode,
 * 48 × 4 pixels across the spectrum, seed 11): the relative standard error of the spectrum's total
 * brightness at 1024 spp is 0.081 with the in-plane screen and 0.267 with a Lambertian one (its 256-spp
 * error scaled to 1024): 3.3× less noise, i.e. the Lambertian screen needs ~11× the samples.
 */
import type { Vec3 } from '../../math/vec3.ts';
import { MeshBuilder } from '../../scene/builder.ts';
import { GLASSES, iorAt } from '../../scene/dispersion.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Camera, type DielectricMaterial, type Scene } from '../../scene/types.ts';

type V2 = readonly [number, number];

const add = (a: V2, b: V2): V2 => [a[0] + b[0], a[1] + b[1]];
const sub = (a: V2, b: V2): V2 => [a[0] - b[0], a[1] - b[1]];
const scale = (a: V2, s: number): V2 => [a[0] * s, a[1] * s];
const dot = (a: V2, b: V2): number => a[0] * b[0] + a[1] * b[1];
const norm = (a: V2): V2 => scale(a, 1 / Math.hypot(a[0], a[1]));
/** Rotated +90° (counter-clockwise in (u, v)). */
const perp = (a: V2): V2 => [-a[1], a[0]];

export const PRISM_GLASS = GLASSES.SF11;
export const PRISM_IOR = 1.78472;
/** Apex angle 60°, side 6 cm. */
export const PRISM_SIDE = 6;
const BASE_LEFT: V2 = [-3, 0];
const BASE_RIGHT: V2 = [3, 0];
const APEX: V2 = [0, 3 * Math.sqrt(3)];
/** Where the beam's axis meets the left face: its middle. */
const ENTRY: V2 = scale(add(BASE_LEFT, APEX), 0.5);

/** Unit normals of the two faces the beam crosses, pointing out of the glass. */
const LEFT_NORMAL: V2 = norm(perp(sub(APEX, BASE_LEFT)));
const RIGHT_NORMAL: V2 = norm(perp(sub(BASE_RIGHT, APEX)));

/** Vector Snell: d refracted at a surface with unit normal n (either side), relative index η = n_from/n_to; undefined at total internal reflection. */
function refract(d: V2, n: V2, eta: number): V2 | undefined {
  const facing = dot(n, d) < 0 ? n : scale(n, -1);
  const cosI = -dot(facing, d);
  const k = 1 - eta * eta * (1 - cosI * cosI);
  if (k < 0) return undefined;
  return norm(add(scale(d, eta), scale(facing, eta * cosI - Math.sqrt(k))));
}

/** Where the ray o + t d meets the line through a and b (t > 0), as t. */
function hitLine(o: V2, d: V2, a: V2, b: V2): number {
  const e = sub(b, a);
  const n = perp(e);
  return dot(sub(a, o), n) / dot(d, n);
}

/** The beam's direction: the incidence of minimum deviation at the left face for n(589.3 nm) = PRISM_IOR. */
export const BEAM_DIRECTION: V2 = (() => {
  // At minimum deviation the ray inside runs parallel to the base: refract (1, 0) back out of the left face.
  const inside: V2 = [1, 0];
  return refract(inside, LEFT_NORMAL, PRISM_IOR)!;
})();

/** The ray leaving the prism for index n: where it leaves the right face and its direction (undefined at total internal reflection). */
export function prismExit(n: number, offset = 0): { point: V2; direction: V2 } | undefined {
  const origin = add(ENTRY, scale(perp(BEAM_DIRECTION), offset));
  const inside = refract(BEAM_DIRECTION, LEFT_NORMAL, 1 / n);
  if (!inside) return undefined;
  const exitPoint = add(origin, scale(inside, hitLine(origin, inside, APEX, BASE_RIGHT)));
  const out = refract(inside, RIGHT_NORMAL, n);
  return out && { point: exitPoint, direction: out };
}

/** Unpolarized Fresnel reflectance for incidence cosine cosI going from index n1 into n2. */
function fresnel(cosI: number, n1: number, n2: number): number {
  const sinT = (n1 / n2) * Math.sqrt(Math.max(0, 1 - cosI * cosI));
  if (sinT >= 1) return 1;
  const cosT = Math.sqrt(1 - sinT * sinT);
  const rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  const rp = (n1 * cosT - n2 * cosI) / (n1 * cosT + n2 * cosI);
  return 0.5 * (rs * rs + rp * rp);
}

/** The fraction of the beam's axis ray at index n that crosses both faces (Fresnel at each). */
export function prismTransmittance(n: number): number {
  const inside = refract(BEAM_DIRECTION, LEFT_NORMAL, 1 / n);
  if (!inside) return 0;
  const t1 = 1 - fresnel(Math.abs(dot(BEAM_DIRECTION, LEFT_NORMAL)), 1, n);
  const t2 = 1 - fresnel(Math.abs(dot(inside, RIGHT_NORMAL)), n, 1);
  return t1 * t2;
}

/** Deviation (radians) of the beam for index n: the angle from its incoming to its outgoing direction. */
export function prismDeviation(n: number): number {
  const out = prismExit(n)!.direction;
  return Math.acos(Math.min(1, dot(out, BEAM_DIRECTION)));
}

const REFERENCE_EXIT = prismExit(PRISM_IOR)!;
/** The screen: perpendicular to the 589.3 nm ray, 20 cm from where it leaves the prism; 16 × 8 cm. */
export const SCREEN_DISTANCE = 20;
export const SCREEN_CENTER: V2 = add(REFERENCE_EXIT.point, scale(REFERENCE_EXIT.direction, SCREEN_DISTANCE));
/** The screen's right as the camera sees it (camera right = forward × up; forward = the 589.3 nm ray). */
export const SCREEN_RIGHT: V2 = perp(REFERENCE_EXIT.direction);
export const SCREEN_HALF_WIDTH = 8;
const SCREEN_HALF_HEIGHT = 4;
/** The camera: 12 cm in front of the screen, looking at it square-on. */
export const CAMERA_DISTANCE = 12;

/**
 * Where the beam's axis at wavelength `lambdaNm` meets the screen, in cm along SCREEN_RIGHT from its
 * centre (the oracle of the spectrum test).
 */
export function screenPosition(lambdaNm: number, offset = 0): number | undefined {
  const exit = prismExit(iorAt(PRISM_IOR, PRISM_GLASS, lambdaNm), offset);
  if (!exit) return undefined;
  const t = dot(sub(SCREEN_CENTER, exit.point), REFERENCE_EXIT.direction) / dot(exit.direction, REFERENCE_EXIT.direction);
  return dot(sub(add(exit.point, scale(exit.direction, t)), SCREEN_CENTER), SCREEN_RIGHT);
}

/**
 * The lamp: a black box whose front is a slit 0.6 cm wide, 3 cm before the prism face, and whose back,
 * 40 cm behind the slit, holds an emitting strip 1.6 cm wide. The beam through the slit diverges by
 * (1.6 + 0.6)/40 = 0.055 rad at most: on the screen each wavelength's band is ~1.7 cm wide, and the
 * spectrum from 400 to 700 nm spreads over ~5 cm. The strip is as wide as it can be without making the
 * slit's acceptance, seen from the screen, any wider (0.6/23 rad): a camera path from the screen
 * finds the light as often as this resolution allows.
 */
export const SLIT_WIDTH = 0.6;
export const LAMP_LENGTH = 40;
export const EMITTER_WIDTH = 1.6;
const LAMP_HALF_WIDTH = 1.2;
/** Gap between the slit and the prism face, along the beam. */
const SLIT_GAP = 3;
/** Radiance of the emitting strip (equal-energy white). */
export const PRISM_LIGHT_RADIANCE = 400;

const HALF_HEIGHT = 5;

export interface PrismOptions {
  /** false: a Lambertian screen (to measure what the in-plane screen buys). Default true. */
  readonly inPlaneScreen?: boolean;
}

export function prismScene(options: PrismOptions = {}): Scene {
  const b = new MeshBuilder('prism');
  const at = (p: V2, y: number): Vec3 => [p[0], y, p[1]];
  const glass: DielectricMaterial = {
    kind: 'dielectric', name: 'SF11 glass', emission: [0, 0, 0], ior: PRISM_IOR, dispersion: PRISM_GLASS, roughness: 0, tint: [1, 1, 1],
    attenuationDistance: Infinity, attenuationColor: [1, 1, 1],
  };
  const glassId = b.material(glass);
  const black = b.material(diffuse('black', [0, 0, 0]));
  const light = b.material(diffuse('light', [0, 0, 0], [PRISM_LIGHT_RADIANCE, PRISM_LIGHT_RADIANCE, PRISM_LIGHT_RADIANCE]));
  const screen = b.material(diffuse('screen', [0.8, 0.8, 0.8], [0, 0, 0], options.inPlaneScreen === false ? {} : { scatterPlaneNormal: [0, 1, 0] }));

  // The prism, closed, faces wound so that their normals point out of the glass.
  const h = HALF_HEIGHT;
  const tri = [BASE_LEFT, BASE_RIGHT, APEX] as const;
  // (The triangle runs counter-clockwise in (u, v); a quad's normal is (v1 − v0) × (v2 − v0).)
  b.triangle(glassId, at(tri[0], -h), at(tri[1], -h), at(tri[2], -h));
  b.triangle(glassId, at(tri[0], h), at(tri[2], h), at(tri[1], h));
  for (let i = 0; i < 3; i++) {
    const p = tri[i]!, q = tri[(i + 1) % 3]!;
    // The base (i = 0) is blackened, as in spectroscopes: light reflected inside leaves no ghost spectra.
    b.quad(i === 0 ? black : glassId, at(p, -h), at(p, h), at(q, h), at(q, -h));
  }

  // The lamp: the strip emits toward the slit from the back of a closed black box.
  const across = perp(BEAM_DIRECTION);
  const slit = sub(ENTRY, scale(BEAM_DIRECTION, SLIT_GAP));
  const back = sub(slit, scale(BEAM_DIRECTION, LAMP_LENGTH));
  const side = (p: V2, t: number): V2 => add(p, scale(across, t));
  const wall = (a: V2, c: V2) => b.quad(black, at(a, -h), at(c, -h), at(c, h), at(a, h));
  const H = LAMP_HALF_WIDTH;
  wall(side(slit, SLIT_WIDTH / 2), side(slit, H));
  wall(side(slit, -SLIT_WIDTH / 2), side(slit, -H));
  wall(side(slit, H), side(back, H));
  wall(side(slit, -H), side(back, -H));
  wall(side(back, -H), side(back, H));
  // The strip, just in front of the back wall; its emitting side, (v1 − v0) × (v2 − v0), along the beam.
  const e = add(back, scale(BEAM_DIRECTION, 0.01));
  const emitter = [at(side(e, EMITTER_WIDTH / 2), -h), at(side(e, -EMITTER_WIDTH / 2), -h), at(side(e, -EMITTER_WIDTH / 2), h), at(side(e, EMITTER_WIDTH / 2), h)] as const;
  const n = cross3(sub3(emitter[1], emitter[0]), sub3(emitter[2], emitter[0]));
  if (n[0] * BEAM_DIRECTION[0] + n[2] * BEAM_DIRECTION[1] > 0) b.quad(light, ...emitter);
  else b.quad(light, emitter[0], emitter[3], emitter[2], emitter[1]);

  // The screen.
  const sw = SCREEN_HALF_WIDTH, sh = SCREEN_HALF_HEIGHT;
  const s0 = add(SCREEN_CENTER, scale(SCREEN_RIGHT, -sw)), s1 = add(SCREEN_CENTER, scale(SCREEN_RIGHT, sw));
  b.quad(screen, at(s0, -sh), at(s1, -sh), at(s1, sh), at(s0, sh));

  const meshes = [b.build()];
  return {
    name: 'prism',
    meshes,
    instances: placeEachOnce(meshes),
    materials: b.materials,
    // The spectrum's middle (≈ 530 nm) in the middle of a 2:1 image 10 cm across.
    camera: prismCamera(screenPosition(530)!, 5, 2),
  };
}

/**
 * A camera square-on to the screen, CAMERA_DISTANCE in front of it, centred on screen position `center`
 * (cm along SCREEN_RIGHT) and seeing `halfWidth` cm either side across an image of this aspect: pixel
 * column x of a w-wide image then sees screen position center + ((x + ½)/w · 2 − 1) · halfWidth.
 */
export function prismCamera(center: number, halfWidth: number, aspect: number): Camera {
  const forward = REFERENCE_EXIT.direction;
  const target = add(SCREEN_CENTER, scale(SCREEN_RIGHT, center));
  const eye = sub(target, scale(forward, CAMERA_DISTANCE));
  const halfHeight = halfWidth / aspect;
  return { position: [eye[0], 0, eye[1]], forward: [forward[0], 0, forward[1]], up: [0, 1, 0], vfovDegrees: (2 * Math.atan(halfHeight / CAMERA_DISTANCE) * 180) / Math.PI };
}

const sub3 = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross3 = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
