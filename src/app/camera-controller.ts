/**
 * The viewer's camera: a position, a heading (yaw) and a pitch, moved by keyboard and mouse. Two
 * modes: fly (free movement, up and down included) and walk (on a scene's WalkMap: eye height above
 * the floor of the current sector, stopped by walls and high steps, climbing stairs smoothly). Pure:
 * input arrives as numbers, so the tests drive it without a DOM.
 *
 * Convention: y is up; yaw 0 looks along −z, positive yaw turns right (toward +x); pitch is positive
 * upward. forward = (sin yaw · cos pitch, sin pitch, −cos yaw · cos pitch).
 */
import type { Vec3 } from '../math/vec3.ts';
import type { Camera, ThinLens } from '../scene/types.ts';
import { eyeLevel, moveWalker, NO_SECTOR, sectorAt, type WalkMap, type WalkPosition } from '../scene/walk-map.ts';

export type MoveMode = 'fly' | 'walk';
export const MOVE_MODES: readonly MoveMode[] = ['fly', 'walk'];

/** Held keys as axes in −1..1: forward (W/S), right (D/A), up (Space/C), turn (the arrow keys). */
export interface MoveInput {
  readonly forward: number;
  readonly right: number;
  readonly up: number;
  readonly turn: number;
  readonly run: boolean;
}

export const NO_INPUT: MoveInput = Object.freeze({ forward: 0, right: 0, up: 0, turn: 0, run: false });

/** Input held constant for a time (KeyTimeline.take). */
export interface HeldSpan {
  readonly input: MoveInput;
  readonly seconds: number;
}

export interface Pose {
  readonly position: Vec3;
  readonly yaw: number;
  readonly pitch: number;
}

/** Keyboard turning speed, radians per second. */
const TURN_RATE = (120 * Math.PI) / 180;
/** Mouse look, radians per pixel of movement. */
const LOOK_RATE = 0.0025;
const MAX_PITCH = (89 * Math.PI) / 180;
/** Shift multiplies speed by this (Doom's run is twice the walk). */
const RUN_FACTOR = 2;
/**
 * The longest step of held input (s): longer spans are cut so that turning while moving follows an
 * arc, and walking checks collisions along the way (moveWalker sub-steps further by the radius).
 */
const MAX_STEP = 1 / 30;
/** How fast the eye follows a change of floor height (1/s): Doom-like smooth steps up stairs. */
const STEP_SMOOTHING = 12;

export function poseFromCamera(camera: Camera): Pose {
  const [fx, fy, fz] = camera.forward;
  const len = Math.hypot(fx, fy, fz) || 1;
  return { position: camera.position, yaw: Math.atan2(fx / len, -fz / len), pitch: Math.asin(Math.max(-1, Math.min(1, fy / len))) };
}

export function forwardOf(yaw: number, pitch: number): Vec3 {
  return [Math.sin(yaw) * Math.cos(pitch), Math.sin(pitch), -Math.cos(yaw) * Math.cos(pitch)];
}

export class CameraController {
  private x: number;
  private y: number;
  private z: number;
  yaw: number;
  pitch: number;
  vfovDegrees: number;
  /** The thin lens (depth of field), the scene camera's to begin with; undefined: a pinhole. */
  lens: ThinLens | undefined;
  private walker?: WalkPosition;
  /** The scene's walk map with heights of its own, which doors and lifts change (setSectorHeights). */
  private readonly walkMap?: WalkMap;
  /** The walker's moves since takeWalked(), x0, z0, x1, z1 each (walk-over triggers). */
  private walks: [number, number, number, number][] = [];

  constructor(
    private readonly base: Camera,
    /** Walking speed in scene units per second. */
    readonly speed: number,
    walkMap?: WalkMap,
  ) {
    this.walkMap = walkMap && { ...walkMap, floors: new Float32Array(walkMap.floors), ceilings: new Float32Array(walkMap.ceilings) };
    const pose = poseFromCamera(base);
    [this.x, this.y, this.z] = pose.position;
    this.yaw = pose.yaw;
    this.pitch = pose.pitch;
    this.vfovDegrees = base.vfovDegrees;
    this.lens = base.lens;
  }

  get mode(): MoveMode {
    return this.walker ? 'walk' : 'fly';
  }

  get canWalk(): boolean {
    return this.walkMap !== undefined;
  }

  /** Switches mode; walking needs a walk map and a position inside it (returns false otherwise). */
  setMode(mode: MoveMode): boolean {
    if (mode === 'fly') {
      this.walker = undefined;
      return true;
    }
    if (!this.walkMap) return false;
    const sector = sectorAt(this.walkMap, this.x, this.z);
    if (sector === NO_SECTOR) return false;
    this.walker = { x: this.x, z: this.z, sector };
    return true;
  }

  get pose(): Pose {
    return { position: [this.x, this.y, this.z], yaw: this.yaw, pitch: this.pitch };
  }

  setPose(pose: Pose): void {
    [this.x, this.y, this.z] = pose.position;
    this.yaw = pose.yaw;
    this.pitch = Math.max(-MAX_PITCH, Math.min(MAX_PITCH, pose.pitch));
    if (this.walker && !this.setMode('walk')) this.walker = undefined;
  }

  /** Mouse look by a movement of (dx, dy) pixels (dy positive downward). */
  look(dx: number, dy: number): void {
    this.yaw += dx * LOOK_RATE;
    this.pitch = Math.max(-MAX_PITCH, Math.min(MAX_PITCH, this.pitch - dy * LOOK_RATE));
  }

  /**
   * Advances through spans of held input (the time since the last frame, however long it was); true
   * when the camera moved or turned. A slow frame never eats input: each span moves by its own time.
   */
  advance(spans: readonly HeldSpan[]): boolean {
    let moved = false;
    for (const { input, seconds } of spans) {
      const idle = input.forward === 0 && input.right === 0 && input.up === 0 && input.turn === 0;
      const steps = idle ? 1 : Math.ceil(seconds / MAX_STEP);
      for (let i = 0; i < steps; i++) moved = this.update(seconds / steps, input) || moved;
    }
    return moved;
  }

  /** Advances by `dt` seconds of held input; true when the camera moved or turned. */
  update(dt: number, input: MoveInput): boolean {
    const before = [this.x, this.y, this.z, this.yaw];
    this.yaw += input.turn * TURN_RATE * dt;
    const speed = this.speed * (input.run ? RUN_FACTOR : 1) * dt;
    const right: Vec3 = [Math.cos(this.yaw), 0, Math.sin(this.yaw)];
    if (this.walker && this.walkMap) {
      // Walking: horizontal heading only, whatever the pitch.
      const ahead: Vec3 = [Math.sin(this.yaw), 0, -Math.cos(this.yaw)];
      let dx = input.forward * ahead[0] + input.right * right[0];
      let dz = input.forward * ahead[2] + input.right * right[2];
      const n = Math.hypot(dx, dz);
      if (n > 1) [dx, dz] = [dx / n, dz / n];
      if (dx !== 0 || dz !== 0) {
        const from = this.walker;
        this.walker = moveWalker(this.walkMap, from, dx * speed, dz * speed);
        if (this.walker.x !== from.x || this.walker.z !== from.z) this.walks.push([from.x, from.z, this.walker.x, this.walker.z]);
      }
      this.x = this.walker.x;
      this.z = this.walker.z;
      const eye = eyeLevel(this.walkMap, this.walker.sector);
      if (eye !== undefined) {
        const follow = 1 - Math.exp(-STEP_SMOOTHING * dt);
        this.y = Math.abs(eye - this.y) < 0.05 ? eye : this.y + (eye - this.y) * follow;
      }
    } else {
      const ahead = forwardOf(this.yaw, this.pitch);
      this.x += (input.forward * ahead[0] + input.right * right[0]) * speed;
      this.y += (input.forward * ahead[1] + input.up) * speed;
      this.z += (input.forward * ahead[2] + input.right * right[2]) * speed;
    }
    return [this.x, this.y, this.z, this.yaw].some((v, i) => v !== before[i]);
  }

  /**
   * New floor and ceiling heights of walk-map sectors (SceneUpdate.walkHeights: a door opened, a lift
   * went down); the walker's rules see them from the next update on, and its eye follows its floor.
   */
  setSectorHeights(heights: ReadonlyMap<number, readonly [number, number]>): void {
    const map = this.walkMap;
    if (!map) return;
    for (const [sector, [floor, ceiling]] of heights) {
      if (!(sector >= 0 && sector < map.floors.length)) continue;
      map.floors[sector] = floor;
      map.ceilings[sector] = ceiling;
    }
  }

  /** Floor and ceiling of a walk-map sector now, or undefined (tests, the page's hooks). */
  sectorHeights(sector: number): [number, number] | undefined {
    const map = this.walkMap;
    return map && sector >= 0 && sector < map.floors.length ? [map.floors[sector]!, map.ceilings[sector]!] : undefined;
  }

  /** The walker's moves since the last call, from → to in the walk plane (for World.walked), oldest first. */
  takeWalked(): [number, number, number, number][] {
    const walks = this.walks;
    this.walks = [];
    return walks;
  }

  camera(): Camera {
    const { lens: _, ...base } = this.base;
    return { ...base, position: [this.x, this.y, this.z], forward: forwardOf(this.yaw, this.pitch), up: [0, 1, 0], vfovDegrees: this.vfovDegrees, ...(this.lens ? { lens: this.lens } : {}) };
  }
}

/** Doom's walking speed, about 8.3 map units per tic at 35 tics per second. */
export const DOOM_WALK_SPEED = 290;

/**
 * A walking speed that suits the scene's size: a quarter of its bounding box's diagonal per second,
 * and at most 1.5 m/s where the scene says how large its unit is; Doom's own speed on a walk map.
 */
export function sceneSpeed(boundsDiagonal: number, metersPerUnit: number | undefined, walkMap: WalkMap | undefined): number {
  if (walkMap) return DOOM_WALK_SPEED;
  const bySize = Math.max(boundsDiagonal, 1e-6) / 4;
  return metersPerUnit ? Math.min(bySize, 1.5 / metersPerUnit) : bySize;
}
