/**
 * Billboards: quads that stand at a point, turn toward the viewer and show one of several images
 * chosen by the angle between the object's facing and the direction it is seen from (Doom's
 * sprites, R_ProjectSprite). The data (`Billboard`, scene/dynamics-types.ts) lives in
 * Scene.dynamics.billboards; this module has its checks and the pose arithmetic, which loaders use for
 * the scene as loaded and world/billboards.ts's animator at every step. Pure.
 *
 * The instance's mesh is a unit quad in object space (BILLBOARD_QUAD): x and y from 0 to 1, z = 0,
 * its front face toward +z, uv (0, 0) at the image's top-left corner. A pose maps it onto the
 * image's rectangle, in the plane that faces the viewer: Doom draws sprites parallel to the view
 * plane, so every quad's normal points against the viewer's forward direction projected onto the
 * horizontal plane, whatever the viewer's position. Only the chosen rotation depends on where the
 * viewer stands. A billboard may animate: a cycle of frames, each with its own images, played in a
 * loop from the world's clock (Doom's spawn states: torches flicker, monsters shuffle).
 */
import type { Mat4 } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Billboard, BillboardImage } from './dynamics-types.ts';
import type { Mesh, Scene } from './types.ts';

/** What is wrong with a scene's billboards, or undefined (validate.ts reports it). */
export function billboardProblem(scene: Scene): string | undefined {
  const moving = new Set(scene.instances.filter((i) => i.moves).map((i) => i.id));
  for (const [k, b] of (scene.dynamics?.billboards ?? []).entries()) {
    const where = `billboard ${k}`;
    if (!moving.has(b.instance)) return `${where} poses instance ${b.instance}, which is not a moving instance of the scene`;
    if (b.frames.length === 0) return `${where} has no frames`;
    if (!b.position.every(Number.isFinite) || !Number.isFinite(b.facing) || !Number.isFinite(b.phase ?? 0)) return `${where} has a non-finite position, facing or phase`;
    if (b.frames.length > 1 && !b.frames.every((f) => f.duration > 0 && Number.isFinite(f.duration))) return `${where} has a frame of no or infinite duration`;
    for (const f of b.frames) if (f.images.length !== 1 && f.images.length !== 8) return `${where} has a frame of ${f.images.length} images (1 or 8)`;
    for (const im of b.frames.flatMap((f) => f.images)) {
      if (!(Number.isInteger(im.material) && im.material >= 0 && im.material < scene.materials.length)) return `${where} shows material ${im.material} of ${scene.materials.length}`;
      if (!(im.width > 0 && im.height > 0) || !Number.isFinite(im.left) || !Number.isFinite(im.top)) return `${where} has an image of invalid size or offsets`;
    }
  }
  return undefined;
}

/** The unit quad every billboard instance places (one shared mesh; the instance's material replaces `material`). */
export function billboardQuad(material: number, name = 'billboard quad'): Mesh {
  return {
    name,
    positions: new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]),
    // Image row 0 is the top: v = 1 − y.
    uvs: new Float32Array([0, 1, 1, 1, 1, 0, 0, 0]),
    // Counter-clockwise seen from +z: the front face looks along +z.
    indices: new Uint32Array([0, 1, 2, 0, 2, 3]),
    materialIds: new Uint32Array([material, material]),
  };
}

const TURN = 2 * Math.PI;
const EIGHTH = TURN / 8;

/**
 * Which of eight rotations shows when the object, facing `facing`, is seen from `viewer` (both in
 * the horizontal plane, angles as Billboard.facing). Doom's rule (R_ProjectSprite):
 * rot = (ang − thing.angle + ANG45/2·9) >> 29, where ang is the direction from the viewer to the
 * thing: eight 45° sectors, each centred on its rotation, rotation 1 (index 0) when the object faces
 * the viewer. Returns the index 0–7 (rotation number − 1).
 */
export function rotationIndex(facing: number, viewer: Vec3, position: Vec3): number {
  // Direction from the viewer to the object, as an angle of the same kind as `facing`.
  const ang = Math.atan2(-(position[2] - viewer[2]), position[0] - viewer[0]);
  let a = (ang - facing + 9 * (EIGHTH / 2)) % TURN;
  if (a < 0) a += TURN;
  // A hair's breadth below a boundary can round to 8 · EIGHTH; it belongs to sector 7's neighbour 0.
  return Math.floor(a / EIGHTH) % 8;
}

/** The frame shown `t` seconds after the world started. */
export function frameAt(b: Billboard, t: number): number {
  if (b.frames.length === 1) return 0;
  const cycle = b.frames.reduce((s, f) => s + f.duration, 0);
  let at = ((t + (b.phase ?? 0)) % cycle + cycle) % cycle;
  for (let i = 0; i < b.frames.length; i++) {
    at -= b.frames[i]!.duration;
    if (at < 0) return i;
  }
  return b.frames.length - 1;
}

/** The rotation index (0–7) a frame shows seen from `viewer` (0 for a frame of one image). */
export function rotationOf(b: Billboard, frame: number, viewer: Vec3): number {
  return b.frames[frame]!.images.length === 1 ? 0 : rotationIndex(b.facing, viewer, b.position);
}

/** The image shown of a frame at a rotation index (a one-image frame shows its image at every angle). */
export function imageAt(b: Billboard, frame: number, rotation: number): BillboardImage {
  const images = b.frames[frame]!.images;
  return images.length === 1 ? images[0]! : images[rotation]!;
}

/**
 * The yaw (radians about +y) of a quad facing a viewer who looks along `forward`: the quad's normal
 * (object +z) is −forward projected onto the horizontal plane. Undefined when the viewer looks
 * straight up or down (no horizontal direction to face).
 */
export function facingYaw(forward: Vec3): number | undefined {
  const [fx, fz] = [forward[0], forward[2]];
  if (Math.hypot(fx, fz) < 1e-9) return undefined;
  // Object +z goes to n = −f (horizontal); object +x to r = (−fz, 0, fx) / |f|, the viewer's right.
  return Math.atan2(-fx, -fz);
}

/**
 * The world-from-object transform of BILLBOARD_QUAD showing `image` at `position`, turned to `yaw`
 * (facingYaw): the quad spans [−left, width − left] along the viewer's right and
 * [top − height, top] above the anchor; mirrored images scale x by −width over the same span.
 */
export function billboardPose(position: Vec3, image: BillboardImage, yaw: number): Mat4 {
  // Rotation about +y by yaw: object +z -> (sin yaw, 0, cos yaw) = n, object +x -> (cos yaw, 0, −sin yaw) = r.
  const c = Math.cos(yaw);
  const s = Math.sin(yaw);
  const r: Vec3 = [c, 0, -s];
  const n: Vec3 = [s, 0, c];
  const sx = image.mirrored ? -image.width : image.width;
  const x0 = image.mirrored ? image.width - image.left : -image.left;
  const y0 = image.top - image.height;
  return [
    r[0] * sx, r[1] * sx, r[2] * sx, 0,
    0, image.height, 0, 0,
    n[0], n[1], n[2], 0,
    position[0] + r[0] * x0, position[1] + y0, position[2] + r[2] * x0, 1,
  ];
}

/** The poses of every billboard seen from `view` at time 0 (what a loader uses for the scene as loaded). */
export function billboardPoses(billboards: readonly Billboard[], view: { readonly position: Vec3; readonly forward: Vec3 }): Map<number, { worldFromObject: Mat4; material: number }> {
  const poses = new Map<number, { worldFromObject: Mat4; material: number }>();
  const yaw = facingYaw(view.forward) ?? 0;
  for (const b of billboards) {
    const frame = frameAt(b, 0);
    const image = imageAt(b, frame, rotationOf(b, frame, view.position));
    poses.set(b.instance, { worldFromObject: billboardPose(b.position, image, yaw), material: image.material });
  }
  return poses;
}
