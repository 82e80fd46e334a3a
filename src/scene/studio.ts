/**
 * A simple photo studio for formats that carry only geometry (PLY, molecules): a floor, a key and a fill area
 * light and a three-quarter camera, all sized from the meshes' bounds so any model, millimetres or
 * kilometres, comes out framed and exposed the same way.
 */
import { LanternError } from '../errors.ts';
import { boundsOfPositions, isEmptyAabb, unionAabb, type Aabb } from '../math/aabb.ts';
import { add, cross, length, normalize, scale, sub, type Vec3 } from '../math/vec3.ts';
import { frameBounds } from './framing.ts';
import { placeEachOnce } from './instances.ts';
import { diffuse, type Material, type Mesh, type Scene } from './types.ts';

export const STUDIO_VFOV_DEGREES = 40;

/**
 * Directions from the object's centre, as (azimuth from +z toward +x, elevation) in degrees. The
 * camera sits at a three-quarter view; the key light comes from above, on the camera's side but
 * swung away from it so shading and a soft shadow show the form; the fill comes from the other side.
 */
const CAMERA_AZIMUTH = 35;
const CAMERA_ELEVATION = 20;
const KEY_DIRECTION = direction(-25, 55);
const FILL_DIRECTION = direction(105, 35);

/**
 * Light sizes and distances are in units of the bounding-sphere radius R, and the emitted radiance
 * is chosen from the solid angle they subtend, which does not depend on R: the same exposure at any
 * scale.
 *
 * Key: a 2R × 2R quad at distance 4R subtends Ω ≈ 4R²/(4R)² = 0.25 sr. A surface facing it at ~45°
 * receives E ≈ L·Ω·cos ≈ 0.18·L, and a diffuse albedo ρ = 0.8 sends back Lo = ρ·E/π ≈ 0.045·L.
 * L = 12 gives Lo ≈ 0.55 on lit surfaces. The floor (ρ = 0.7, ~5R from the key at ~60° incidence)
 * gets Lo ≈ 0.7·(12·0.16·0.8)/π ≈ 0.35, a touch darker than the object so the object reads first.
 * Fill: a 1.5R × 1.5R quad at 4R (Ω ≈ 0.14 sr) at L = 4 adds Lo ≈ 0.8·4·0.14·0.7/π ≈ 0.1, which lifts
 * the shadow side without flattening it. Shadowed and grazing parts sit near 0.1, so the mean over
 * the object is a few tenths: mid-grey under a filmic curve at exposure 0. (Cross-check: integrating
 * both lights over the Stanford dragon's camera-facing triangles, without shadows, gives a mean
 * direct Lo of 0.34; shadows take some away and the floor bounce adds some back.)
 */
const KEY = { distance: 4, size: 2, radiance: 12 };
const FILL = { distance: 4, size: 1.5, radiance: 4 };
/** The floor is large enough that its edge is far outside the frame from the studio camera. */
const FLOOR_HALF_SIZE = 20;
/** Framing margin: the bounds fill at most 1/1.1 of the frame's half-height. */
const MARGIN = 1.1;

export function studioScene(name: string, meshes: readonly Mesh[], materials: readonly Material[]): Scene {
  const bounds = meshes.map(meshBounds).reduce(unionAabb, EMPTY);
  if (isEmptyAabb(bounds)) throw new LanternError(`${name}: there is no geometry to put in the studio`);
  const centre = scale(add(bounds.min, bounds.max), 0.5);
  // A flat or point-like model still needs a non-zero scale for the studio around it.
  const radius = length(sub(bounds.max, centre)) || 1;

  const base = materials.length;
  const studioMaterials: Material[] = [
    diffuse('studio floor', [0.7, 0.7, 0.7]),
    { kind: 'emissive', name: 'studio key light', emission: [KEY.radiance, KEY.radiance, KEY.radiance] },
    { kind: 'emissive', name: 'studio fill light', emission: [FILL.radiance, FILL.radiance, FILL.radiance] },
  ];
  // A hair below the lowest point: no visible gap, and no coplanar fight with a flat-bottomed model.
  const floorY = bounds.min[1] - 1e-4 * radius;
  const floorHalf = FLOOR_HALF_SIZE * radius;
  const floor = quad(
    'studio floor',
    [centre[0], floorY, centre[2]],
    [floorHalf, 0, 0],
    [0, 0, -floorHalf], // right × this = +y: the floor's geometric normal faces up
    base,
  );
  const key = facingLight('studio key light', centre, KEY_DIRECTION, KEY, radius, base + 1);
  const fill = facingLight('studio fill light', centre, FILL_DIRECTION, FILL, radius, base + 2);

  const all = [...meshes, floor, key, fill];
  return {
    name,
    meshes: all,
    instances: placeEachOnce(all),
    materials: [...materials, ...studioMaterials],
    camera: frameBounds(bounds, { vfovDegrees: STUDIO_VFOV_DEGREES, azimuthDegrees: CAMERA_AZIMUTH, elevationDegrees: CAMERA_ELEVATION, margin: MARGIN }),
  };
}

const EMPTY: Aabb = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };

/**
 * The object-space bounds of everything a mesh draws: its triangles' vertices, each sphere (centre ±
 * radius) and each capsule (both end points ± radius: a capsule is the union of the spheres along its
 * segment, so the box of its two end spheres holds it). Empty for a mesh with nothing.
 */
export function meshBounds(mesh: Mesh): Aabb {
  let bounds = boundsOfPositions(mesh.positions);
  const around = (x: number, y: number, z: number, r: number) => {
    bounds = unionAabb(bounds, { min: [x - r, y - r, z - r], max: [x + r, y + r, z + r] });
  };
  const spheres = mesh.spheres;
  if (spheres) {
    for (let i = 0; i < spheres.radii.length; i++) around(spheres.centers[3 * i]!, spheres.centers[3 * i + 1]!, spheres.centers[3 * i + 2]!, spheres.radii[i]!);
  }
  const capsules = mesh.capsules;
  if (capsules) {
    for (let i = 0; i < capsules.radii.length; i++) {
      const e = capsules.endpoints, r = capsules.radii[i]!;
      around(e[6 * i]!, e[6 * i + 1]!, e[6 * i + 2]!, r);
      around(e[6 * i + 3]!, e[6 * i + 4]!, e[6 * i + 5]!, r);
    }
  }
  return bounds;
}

function direction(azimuthDegrees: number, elevationDegrees: number): Vec3 {
  const a = (azimuthDegrees * Math.PI) / 180, e = (elevationDegrees * Math.PI) / 180;
  return [Math.sin(a) * Math.cos(e), Math.sin(e), Math.cos(a) * Math.cos(e)];
}

/** A square light at `distance`·R from the centre along `dir`, its emitting side facing the centre. */
function facingLight(
  name: string,
  centre: Vec3,
  dir: Vec3,
  spec: { distance: number; size: number },
  radius: number,
  materialId: number,
): Mesh {
  const position = add(centre, scale(dir, spec.distance * radius));
  const half = (spec.size * radius) / 2;
  // Build the quad's frame from its normal n = -dir: u is horizontal, v = n × u, so u × v ∥ n.
  const n = scale(dir, -1);
  const u = normalize(cross([0, 1, 0], n));
  const v = cross(n, u);
  return quad(name, position, scale(u, half), scale(v, half), materialId);
}

/**
 * Two triangles around `centre` spanning ±a and ±b. Geometric normal (v1-v0)×(v2-v0) is along a × b
 * for both triangles, which is the side an emissive quad lights.
 */
function quad(name: string, centre: Vec3, a: Vec3, b: Vec3, materialId: number): Mesh {
  const corners = [
    sub(sub(centre, a), b),
    sub(add(centre, a), b),
    add(add(centre, a), b),
    add(sub(centre, a), b),
  ];
  return {
    name,
    positions: new Float32Array(corners.flat()),
    indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
    materialIds: new Uint32Array([materialId, materialId]),
  };
}


/** The meshes studioScene adds after the model's, in order. */
const STUDIO_MESH_NAMES = ['studio floor', 'studio key light', 'studio fill light'];

/**
 * The model alone, without the studio's floor and lights (the camera kept): what a benchmark that
 * measures the bare mesh traces. Undefined when `scene` is not a studio scene.
 */
export function withoutStudio(scene: Scene): Scene | undefined {
  const n = scene.meshes.length - STUDIO_MESH_NAMES.length;
  if (n < 1 || !STUDIO_MESH_NAMES.every((name, k) => scene.meshes[n + k]!.name === name)) return undefined;
  return {
    ...scene,
    meshes: scene.meshes.slice(0, n),
    instances: scene.instances.filter((inst) => inst.mesh < n),
    materials: scene.materials.slice(0, scene.materials.length - STUDIO_MESH_NAMES.length),
  };
}
