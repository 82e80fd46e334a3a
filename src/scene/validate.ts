/**
 * Checks the invariants of a Scene after a loader built it, so every later stage (BVH, GPU packing)
 * can rely on them. Throws a LanternError naming the first broken invariant.
 */
import { LanternError } from '../errors.ts';
import { cross, isFiniteVec3, length, type Vec3 } from '../math/vec3.ts';
import { validateDispersion } from './dispersion.ts';
import { lensProblem } from './lens.ts';
import { billboardProblem } from './billboards.ts';
import type { WalkGrid } from './dynamics-types.ts';
import { morphTargetProblem } from './morph.ts';
import type { Material, Scene, TextureRef } from './types.ts';

export function validateScene(scene: Scene): void {
  const fail = (what: string): never => {
    throw new LanternError(`scene '${scene.name}' is invalid: ${what}`);
  };
  if (scene.materials.length === 0) fail('it has no materials');
  const textureCount = scene.textures?.length ?? 0;
  const unit = (x: number) => Number.isFinite(x) && x >= 0 && x <= 1;
  const unitVec = (v: Vec3) => isFiniteVec3(v) && v.every(unit);
  scene.materials.forEach((m, i) => {
    const where = `material ${i} ('${m.name}')`;
    if (!isFiniteVec3(m.emission) || m.emission.some((c) => c < 0)) fail(`${where} has a negative or non-finite emission`);
    for (const ref of [m.emissionTexture, m.normalTexture, ...materialTextures(m)]) {
      if (ref && !(Number.isInteger(ref.texture) && ref.texture >= 0 && ref.texture < textureCount)) fail(`${where} refers to texture ${ref.texture} of ${textureCount}`);
    }
    switch (m.kind) {
      case 'diffuse':
        if (!unitVec(m.albedo)) fail(`${where} has albedo ${m.albedo.join(', ')} outside [0, 1]`);
        if (m.scatterPlaneNormal && !(isFiniteVec3(m.scatterPlaneNormal) && Math.abs(length(m.scatterPlaneNormal) - 1) < 1e-4)) fail(`${where} has a scatter-plane normal that is not a unit vector`);
        break;
      case 'metallic-roughness':
        if (!unitVec(m.baseColor)) fail(`${where} has base colour ${m.baseColor.join(', ')} outside [0, 1]`);
        for (const [name, v] of [['metallic', m.metallic], ['roughness', m.roughness], ['opacity', m.opacity], ['transmission', m.transmission], ['specular', m.specular]] as const) {
          if (!unit(v)) fail(`${where} has ${name} ${v} outside [0, 1]`);
        }
        if (!(m.ior >= 1 && m.ior < 10)) fail(`${where} has an index of refraction ${m.ior} outside [1, 10)`);
        if (m.dispersion) validateDispersion(where, m.ior, m.dispersion);
        if (!isFiniteVec3(m.specularColor) || m.specularColor.some((c) => c < 0)) fail(`${where} has a negative or non-finite specular colour`);
        if (!unitVec(m.attenuationColor) || !(m.attenuationDistance > 0)) fail(`${where} has an invalid volume attenuation`);
        break;
      case 'dielectric':
        if (!(m.ior >= 1 && m.ior < 10)) fail(`${where} has an index of refraction ${m.ior} outside [1, 10)`);
        if (m.dispersion) validateDispersion(where, m.ior, m.dispersion);
        if (!unit(m.roughness)) fail(`${where} has roughness ${m.roughness} outside [0, 1]`);
        if (!unitVec(m.tint)) fail(`${where} has tint ${m.tint.join(', ')} outside [0, 1]`);
        if (!unitVec(m.attenuationColor) || !(m.attenuationDistance > 0)) fail(`${where} has an invalid volume attenuation`);
        break;
      case 'emissive':
        break;
      default:
        fail(`${where} has an unknown kind '${(m as { kind: string }).kind}'`);
    }
  });
  const ids = new Set<number>();
  scene.instances.forEach((inst, i) => {
    if (!(Number.isInteger(inst.mesh) && inst.mesh >= 0 && inst.mesh < scene.meshes.length)) fail(`instance ${i} refers to mesh ${inst.mesh} of ${scene.meshes.length}`);
    if (inst.worldFromObject.length !== 16 || !inst.worldFromObject.every(Number.isFinite)) fail(`instance ${i} has a transform that is not 16 finite numbers`);
    if (ids.has(inst.id)) fail(`two instances have the id ${inst.id}`);
    if (inst.material !== undefined && !(Number.isInteger(inst.material) && inst.material >= 0 && inst.material < scene.materials.length)) fail(`instance ${i} uses material ${inst.material} of ${scene.materials.length}`);
    ids.add(inst.id);
  });
  for (const light of scene.lights ?? []) {
    const power = light.kind === 'directional' ? light.irradiance : light.intensity;
    if (!(Number.isFinite(power) && power >= 0) || !isFiniteVec3(light.color) || light.color.some((c) => c < 0)) fail(`light '${light.name}' has a negative or non-finite intensity or colour`);
  }
  let triangles = 0;
  scene.meshes.forEach((mesh, mi) => {
    const where = `mesh ${mi} ('${mesh.name}')`;
    const vertexCount = mesh.positions.length / 3;
    if (!Number.isInteger(vertexCount)) fail(`${where} has a position array whose length is not a multiple of 3`);
    if (mesh.indices.length % 3 !== 0) fail(`${where} has an index array whose length is not a multiple of 3`);
    const triCount = mesh.indices.length / 3;
    if (mesh.materialIds.length !== triCount) {
      fail(`${where} has ${mesh.materialIds.length} material ids for ${triCount} triangles`);
    }
    if (mesh.normals && mesh.normals.length !== mesh.positions.length) fail(`${where} has ${mesh.normals.length / 3} normals for ${vertexCount} vertices`);
    if (mesh.uvs && mesh.uvs.length !== vertexCount * 2) fail(`${where} has ${mesh.uvs.length / 2} uvs for ${vertexCount} vertices`);
    const morphProblem = morphTargetProblem(mesh);
    if (morphProblem) fail(`${where}: ${morphProblem}`);
    for (let i = 0; i < mesh.positions.length; i++) {
      if (!Number.isFinite(mesh.positions[i]!)) fail(`${where} has a non-finite position at vertex ${Math.floor(i / 3)}`);
    }
    for (let i = 0; i < mesh.indices.length; i++) {
      if (mesh.indices[i]! >= vertexCount) fail(`${where} triangle ${Math.floor(i / 3)} refers to vertex ${mesh.indices[i]} of ${vertexCount}`);
    }
    for (let t = 0; t < triCount; t++) {
      if (mesh.materialIds[t]! >= scene.materials.length) fail(`${where} triangle ${t} uses material ${mesh.materialIds[t]} of ${scene.materials.length}`);
    }
    triangles += triCount;
    for (const [kind, set, floats] of [['sphere', mesh.spheres, 3], ['capsule', mesh.capsules, 6]] as const) {
      if (!set) continue;
      const coords = kind === 'sphere' ? mesh.spheres!.centers : mesh.capsules!.endpoints;
      const n = set.radii.length;
      if (coords.length !== n * floats || set.materialIds.length !== n) fail(`${where} has ${kind} arrays of inconsistent lengths (${n} radii, ${coords.length / floats} positions, ${set.materialIds.length} material ids)`);
      for (let i = 0; i < n; i++) {
        if (!(set.radii[i]! > 0 && set.radii[i]! < Infinity)) fail(`${where} ${kind} ${i} has radius ${set.radii[i]}, not a positive finite number`);
        if (set.materialIds[i]! >= scene.materials.length) fail(`${where} ${kind} ${i} uses material ${set.materialIds[i]} of ${scene.materials.length}`);
      }
      for (let i = 0; i < coords.length; i++) if (!Number.isFinite(coords[i]!)) fail(`${where} ${kind} ${Math.floor(i / floats)} has a non-finite position`);
      triangles += n;
    }
  });
  if (triangles === 0) fail('it has no geometry (no triangles, spheres or capsules)');
  scene.instances.forEach((inst, i) => {
    const mesh = scene.meshes[inst.mesh]!;
    if ((mesh.spheres || mesh.capsules) && !isSimilarity(inst.worldFromObject)) {
      fail(`instance ${i} of mesh '${mesh.name}' has spheres or capsules but a transform that is not a similarity (rotation, uniform scale, translation): a sphere would become an ellipsoid`);
    }
  });
  if (scene.instances.length === 0) fail('it places no mesh (no instances)');
  const c = scene.camera;
  if (!isFiniteVec3(c.position)) fail('the camera position is not finite');
  if (!(length(c.forward) > 0) || !isFiniteVec3(c.forward)) fail('the camera forward vector is zero or not finite');
  const side: Vec3 = cross(c.forward, c.up);
  if (!(length(side) > 1e-9 * length(c.forward) * length(c.up))) fail('the camera up vector is zero or parallel to forward');
  if (!(c.vfovDegrees > 0 && c.vfovDegrees < 180)) fail(`the camera field of view ${c.vfovDegrees}° is outside (0, 180)`);
  if (c.exposureStops !== undefined && !(Math.abs(c.exposureStops) <= 64)) fail(`the camera exposure ${c.exposureStops} stops is outside ±64`);
  const lens = c.lens && lensProblem(c.lens);
  if (lens) fail(lens);
  const billboards = billboardProblem(scene);
  if (billboards) fail(billboards);
  const moving = slidingDoorProblem(scene) ?? pushWallProblem(scene);
  if (moving) fail(moving);
}

/** What is wrong with a walk grid, or undefined. */
function gridProblem(grid: WalkGrid): string | undefined {
  return Number.isFinite(grid.originX) && Number.isFinite(grid.originZ) && grid.size > 0 && Number.isFinite(grid.size) ? undefined : 'a grid of no or infinite cell size, or a non-finite origin';
}

/** What is wrong with a scene's sliding doors, or undefined. */
function slidingDoorProblem(scene: Scene): string | undefined {
  const set = scene.dynamics?.slidingDoors;
  if (!set) return undefined;
  const grid = gridProblem(set.grid);
  if (grid) return `sliding doors: ${grid}`;
  if (!(set.travelSeconds > 0 && Number.isFinite(set.travelSeconds)) || !(set.waitSeconds >= 0 && Number.isFinite(set.waitSeconds))) return 'sliding doors: travel time must be > 0 and wait ≥ 0, both finite';
  if (!(set.proximity >= 0 && set.bodyRadius >= 0)) return 'sliding doors: proximity and body radius must be ≥ 0';
  const moving = new Set(scene.instances.filter((i) => i.moves).map((i) => i.id));
  const sectors = scene.walkMap?.floors.length ?? 0;
  for (const [k, d] of set.doors.entries()) {
    if (!moving.has(d.instance)) return `sliding door ${k} moves instance ${d.instance}, which is not a moving instance of the scene`;
    if (!(Number.isInteger(d.sector) && d.sector >= 0 && d.sector < sectors)) return `sliding door ${k} names walk-map sector ${d.sector} of ${sectors}`;
    if (![...d.slide, ...d.across, d.floor, d.ceiling].every(Number.isFinite)) return `sliding door ${k} has a non-finite slide, direction or height`;
  }
  return undefined;
}

/** What is wrong with a scene's push walls, or undefined. */
function pushWallProblem(scene: Scene): string | undefined {
  const set = scene.dynamics?.pushWalls;
  if (!set) return undefined;
  const grid = gridProblem(set.grid);
  if (grid) return `push walls: ${grid}`;
  if (!(set.secondsPerCell > 0 && Number.isFinite(set.secondsPerCell)) || !(Number.isInteger(set.reach) && set.reach >= 0)) return 'push walls: seconds per cell must be finite and > 0, reach a whole number ≥ 0';
  const moving = new Set(scene.instances.filter((i) => i.moves).map((i) => i.id));
  const sectors = scene.walkMap?.floors.length ?? 0;
  const valid = (s: number) => Number.isInteger(s) && s >= 0 && s < sectors;
  for (const [k, w] of set.walls.entries()) {
    if (!moving.has(w.instance)) return `push wall ${k} moves instance ${w.instance}, which is not a moving instance of the scene`;
    if (w.paths.length !== 4) return `push wall ${k} has ${w.paths.length} paths, not 4`;
    if (!valid(w.sector) || !w.paths.every((p) => p.every((c) => valid(c.sector)))) return `push wall ${k} names a walk-map sector outside the ${sectors} there are`;
  }
  return undefined;
}

/** Whether the linear part of m is a rotation (or reflection) times a uniform scale, to 1e-4 relative. */
function isSimilarity(m: readonly number[] | Float32Array | Float64Array): boolean {
  const cols = [0, 4, 8].map((o) => [m[o]!, m[o + 1]!, m[o + 2]!] as Vec3);
  const lengths = cols.map(length);
  const s = lengths[0]!;
  if (!(s > 0)) return false;
  const tol = 1e-4;
  if (lengths.some((l) => Math.abs(l - s) > tol * s)) return false;
  const dot = (a: Vec3, b: Vec3) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return Math.abs(dot(cols[0]!, cols[1]!)) <= tol * s * s && Math.abs(dot(cols[0]!, cols[2]!)) <= tol * s * s && Math.abs(dot(cols[1]!, cols[2]!)) <= tol * s * s;
}

function materialTextures(m: Material): (TextureRef | undefined)[] {
  switch (m.kind) {
    case 'diffuse':
      return [m.albedoTexture];
    case 'metallic-roughness':
      return [m.baseColorTexture, m.metallicRoughnessTexture, m.specularTexture, m.specularColorTexture, m.transmissionTexture];
    case 'dielectric':
    case 'emissive':
      return [];
  }
}
