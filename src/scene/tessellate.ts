/**
 * Triangles for the analytic primitives (Mesh.spheres, Mesh.capsules), for what needs triangles:
 * exporting to glTF (`lantern convert`), which has no spheres. Both are surfaces of revolution, so one
 * routine revolves a profile (radius and height along the axis, with the profile's normal) around
 * the axis. uvs follow the analytic ones (scene/types.ts): u around the axis, v along it.
 */
import { orthonormalFrame } from '../math/vec3.ts';
import type { Mesh } from './types.ts';

/** Segments around the axis; the profile has about half as many steps over a half circle. */
export const TESSELLATION_SEGMENTS = 48;

interface ProfilePoint {
  /** Distance from the axis. */
  readonly radius: number;
  /** Position along the axis, from the primitive's start. */
  readonly height: number;
  /** Unit normal in the (radial, axial) plane. */
  readonly normal: readonly [number, number];
  /** v of the uv. */
  readonly v: number;
}

/**
 * The triangles of a mesh's spheres and capsules, in the mesh's object space, with normals and uvs,
 * or undefined when it has none. Material ids follow each primitive's.
 */
export function tessellateAnalytic(mesh: Mesh, segments = TESSELLATION_SEGMENTS): Mesh | undefined {
  const sphereCount = mesh.spheres?.radii.length ?? 0, capsuleCount = mesh.capsules?.radii.length ?? 0;
  if (sphereCount + capsuleCount === 0) return undefined;
  const positions: number[] = [], normals: number[] = [], uvs: number[] = [], indices: number[] = [], materialIds: number[] = [];
  const rings = Math.max(4, Math.round(segments / 2));
  const arc = (r: number, from: number, to: number, base: number, steps: number, v: (k: number) => number): ProfilePoint[] =>
    Array.from({ length: steps + 1 }, (_, k) => {
      // Angle from the +axis: 0 at the top pole, π at the bottom one.
      const theta = from + ((to - from) * k) / steps;
      // Exactly 0 at the poles (sin π is 1e-16, not 0), so their collapsed triangles are skipped.
      const atPole = theta === 0 || theta === Math.PI;
      return { radius: atPole ? 0 : r * Math.sin(theta), height: base + r * Math.cos(theta), normal: [Math.sin(theta), Math.cos(theta)] as const, v: v(k) };
    });
  const revolve = (origin: readonly number[], axis: readonly [number, number, number], profile: ProfilePoint[], material: number, sphereFrame: boolean) => {
    // u measured as the GPU's: for a sphere around +y from +z toward +x; for a capsule in the frame of its axis.
    const [t1, t2]: readonly [readonly number[], readonly number[]] = sphereFrame ? [[0, 0, 1], [1, 0, 0]] : orthonormalFrame(axis);
    const first = positions.length / 3;
    for (const p of profile) {
      for (let s = 0; s <= segments; s++) {
        const phi = (2 * Math.PI * s) / segments;
        const c = Math.cos(phi), sn = Math.sin(phi);
        const radial = [0, 1, 2].map((k) => c * t1[k]! + sn * t2[k]!);
        for (let k = 0; k < 3; k++) {
          positions.push(origin[k]! + p.radius * radial[k]! + p.height * axis[k]!);
          normals.push(p.normal[0] * radial[k]! + p.normal[1] * axis[k]!);
        }
        uvs.push(s / segments, p.v);
      }
    }
    const row = segments + 1;
    for (let r = 0; r + 1 < profile.length; r++) {
      for (let s = 0; s < segments; s++) {
        const a = first + r * row + s, b = a + row, c = b + 1, d = a + 1;
        // Skip the triangles that collapse at a pole (zero radius).
        if (profile[r]!.radius > 0) indices.push(a, b, d);
        if (profile[r + 1]!.radius > 0) indices.push(d, b, c);
        for (let k = (profile[r]!.radius > 0 ? 1 : 0) + (profile[r + 1]!.radius > 0 ? 1 : 0); k > 0; k--) materialIds.push(material);
      }
    }
  };
  for (let i = 0; i < sphereCount; i++) {
    const { centers, radii, materialIds: ids } = mesh.spheres!;
    const r = radii[i]!;
    revolve([centers[i * 3]!, centers[i * 3 + 1]!, centers[i * 3 + 2]!], [0, 1, 0], arc(r, 0, Math.PI, 0, rings, (k) => k / rings), ids[i]!, true);
  }
  for (let i = 0; i < capsuleCount; i++) {
    const { endpoints: e, radii, materialIds: ids } = mesh.capsules!;
    const a = [e[i * 6]!, e[i * 6 + 1]!, e[i * 6 + 2]!], b = [e[i * 6 + 3]!, e[i * 6 + 4]!, e[i * 6 + 5]!];
    const len = Math.hypot(b[0]! - a[0]!, b[1]! - a[1]!, b[2]! - a[2]!);
    const axis: [number, number, number] = len > 0 ? [(b[0]! - a[0]!) / len, (b[1]! - a[1]!) / len, (b[2]! - a[2]!) / len] : [0, 1, 0];
    const r = radii[i]!, half = Math.max(2, Math.round(rings / 2));
    // From the pole beyond b down to the pole beyond a: v runs from 1 (at b) to 0 (at a), clamped on the caps as the GPU's is.
    const profile = [...arc(r, 0, Math.PI / 2, len, half, () => 1), ...arc(r, Math.PI / 2, Math.PI, 0, half, () => 0)];
    revolve(a, axis, profile, ids[i]!, false);
  }
  return {
    name: `${mesh.name} (tessellated spheres and capsules)`,
    positions: new Float32Array(positions),
    normals: new Float32Array(normals),
    uvs: new Float32Array(uvs),
    indices: new Uint32Array(indices),
    materialIds: new Uint32Array(materialIds),
  };
}
