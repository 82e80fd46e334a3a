/**
 * What moves in a scene, as data (Scene.dynamics): the part of the model that says how instances,
 * meshes, materials and the walk map change with time, with the viewer's position and with the
 * player's actions. A loader describes it (Doom's things, animated textures, doors and lifts; the
 * dungeon's phantom; Wolfenstein's doors and push walls); world/world.ts plays it. Data only (no
 * functions in it; here, besides the types, only moverKindOf and PUSH_DIRECTIONS, conventions of
 * the data), so a scene built in a worker crosses to the page by structured clone. It imports
 * nothing else of scene/ (types.ts imports it). Pure.
 *
 * Each kind of motion is one field, played by one animator of world/:
 * - billboards (world/billboards.ts; their poses and checks: scene/billboards.ts): quads turned
 *   toward the viewer, their texture chosen by the angle between the thing's facing and the view
 *   (Doom's sprites);
 * - materialAnimations (world/material-animation.ts): texture cycles, scrolling textures and
 *   emission patterns (Doom's animated flats and walls, scrolling walls, flickering sectors);
 * - movers (world/movers.ts): doors and lifts, moving a sector's floor or ceiling by mesh morph
 *   weights, opened by the use key or by walking over a line;
 * - paths (world/paths.ts; the curves: scene/paths.ts): instances carried along a closed path (the
 *   dungeon's phantom);
 * - slidingDoors (world/sliding-doors.ts): panels sliding sideways into the wall, opened by the use
 *   key or by standing in front of them (Wolfenstein's doors);
 * - pushWalls (world/push-walls.ts): wall blocks pushed away by the use key (Wolfenstein's secrets).
 * What one step of them changes is a SceneUpdate (scene/dynamics.ts).
 */
import type { Mat4 } from '../math/mat4.ts';
import type { Vec3 } from '../math/vec3.ts';

/** The dynamic parts of a scene. Every field is optional; a scene without `dynamics` is frozen. */
export interface SceneDynamics {
  /** Texture cycles, uv scrolls and emission patterns. */
  readonly materialAnimations?: MaterialAnimations;
  /** Doors and lifts. */
  readonly movers?: MoverSet;
  /** Instances carried along closed paths. */
  readonly paths?: readonly InstancePath[];
  /** Quads turned toward the viewer, showing the image for the angle they are seen from (Doom's things). */
  readonly billboards?: readonly Billboard[];
  /** Wolfenstein's doors. */
  readonly slidingDoors?: SlidingDoorSet;
  /** Wolfenstein's push walls. */
  readonly pushWalls?: PushWallSet;
}

// Material animations (world/material-animation.ts plays them).

/** A material showing the frames of a cycle in turn, `secondsPerFrame` each, wrapping. */
export interface TextureCycle {
  /** Index into Scene.materials (it must have a colour texture: an albedo or base colour texture). */
  readonly material: number;
  /** The colour texture of each frame, indices into Scene.textures (at least two). */
  readonly frames: readonly number[];
  /**
   * The emission texture of each frame (as many as `frames`), for a material that emits through a
   * texture; absent: the emission texture does not change.
   */
  readonly emissionFrames?: readonly number[];
  readonly secondsPerFrame: number;
  /** The frame shown at t = 0 (default 0). */
  readonly firstFrame?: number;
}

/** A material whose textures slide: uv offset = velocity · t (wrapped to [0, 1)). */
export interface UvScroll {
  readonly material: number;
  /** uv units per second (u: one unit is the texture's width). */
  readonly velocity: readonly [number, number];
  /** The offset moves in steps of this many seconds (Doom: one tic, 1/35 s); absent or 0: continuously. */
  readonly stepSeconds?: number;
}

/**
 * A light level stepped once per tic, as the thinkers of Doom's p_lights.c step a sector's light.
 * Levels are Doom's 0–255 (they may leave that range where Doom's do: a flicker's floor is 16 above
 * its darkest neighbour). Every pattern starts at `maxLevel`, the sector's own level.
 * - flash (T_LightFlash, sector special 1): max for (random & maxTime) + 1 tics, then min for
 *   (random & minTime) + 1 tics (Doom: maxTime 64, minTime 7 — a bit mask, not a modulus, so the
 *   bright spells last 1 or 65 tics);
 * - strobe (T_StrobeFlash, specials 2, 3, 4, 12, 13): min for `darkTics`, max for `brightTics`; the
 *   first change after 1 tic (`inSync`) or (random & 7) + 1 tics;
 * - glow (T_Glow, special 8): down by `step` per tic to just above min, then up to just below max,
 *   and back;
 * - flicker (T_FireFlicker, special 17): every 4 tics, level = max − 16·(random & 3), or min where
 *   the current level minus that amount would be below min.
 */
export type LightPattern =
  | { readonly kind: 'flash'; readonly maxLevel: number; readonly minLevel: number; readonly maxTime: number; readonly minTime: number; readonly seed: number }
  | {
      readonly kind: 'strobe';
      readonly maxLevel: number;
      readonly minLevel: number;
      readonly brightTics: number;
      readonly darkTics: number;
      readonly inSync: boolean;
      readonly seed: number;
    }
  | { readonly kind: 'glow'; readonly maxLevel: number; readonly minLevel: number; readonly step: number }
  | { readonly kind: 'flicker'; readonly maxLevel: number; readonly minLevel: number; readonly seed: number };

/** A material whose emission follows a light pattern: emission = `emission` × clamp(level / fullLevel, 0, 1)^exponent. */
export interface EmissionPattern {
  readonly material: number;
  /** The emission at `fullLevel` (linear RGB). */
  readonly emission: Vec3;
  /** The level at which the material emits `emission` (Doom: 255). */
  readonly fullLevel: number;
  /** How emission grows with the level (Doom scenes: 2, light-table.ts sectorLightFactor). */
  readonly exponent: number;
  /** Steps per second (Doom: 35). */
  readonly ticsPerSecond: number;
  readonly pattern: LightPattern;
}

/** Scene.dynamics.materialAnimations. */
export interface MaterialAnimations {
  readonly cycles?: readonly TextureCycle[];
  readonly scrolls?: readonly UvScroll[];
  readonly patterns?: readonly EmissionPattern[];
}

// Movers: Doom's doors and lifts (world/movers.ts plays them; vanilla Doom's p_doors.c and p_plats.c).

/**
 * What a trigger does to its movers:
 * - open-wait-close: the ceiling rises to the door's top, waits, comes down to the floor;
 * - open: the ceiling rises to the top and stays; close: it comes down to the floor and stays;
 * - close-wait-open: down to the floor, wait, back up to where it was;
 * - lower-wait-raise (lifts): the floor goes down to the lift's bottom, waits, rises back.
 */
export type MoverAction = 'open-wait-close' | 'open' | 'close' | 'close-wait-open' | 'lower-wait-raise';

/** What an action moves: a lift's floor ('lower-wait-raise') or a door's ceiling (every other). */
export const moverKindOf = (action: MoverAction): 'door' | 'lift' => (action === 'lower-wait-raise' ? 'lift' : 'door');

/** One moving sector. Heights in world units (y). */
export interface Mover {
  /** Scene.meshes index; morph target 0 moves with the floor, 1 with the ceiling (per unit). */
  readonly mesh: number;
  /** Walk-map sector whose heights follow. */
  readonly sector: number;
  /** 'door', 'lift', or both when triggers of both kinds act on it. */
  readonly kinds: readonly ('door' | 'lift')[];
  readonly restFloor: number;
  readonly restCeiling: number;
  /** Where an opening door's ceiling stops (Doom: the lowest ceiling around − 4). */
  readonly doorTop: number;
  /** Where a lift's floor stops going down (Doom: the lowest floor around, never above its own). */
  readonly liftBottom: number;
  /** The sector's boundary, x0, z0, x1, z1 per line (the walk plane): does the player stand in it? */
  readonly outline: Float32Array;
}

/** A line that starts movers. */
export interface MoverTrigger {
  /** x0, z0, x1, z1 in the walk plane. */
  readonly line: readonly [number, number, number, number];
  /**
   * 'use': the use key, from the line's front side only, where cross((x1−x0, z1−z0), (px−x0,
   * pz−z0)) > 0 (the walk map's first side); 'walk': the player's centre crossing it either way.
   */
  readonly activation: 'use' | 'walk';
  readonly repeatable: boolean;
  /** Indices into MoverSet.movers. */
  readonly movers: readonly number[];
  readonly action: MoverAction;
  /** World units per second. */
  readonly speed: number;
  /** Seconds of the action's wait. */
  readonly wait: number;
  /**
   * Doom's manual (DR) doors: using the line of a door already moving sends it back (a closing door
   * reopens, an opening or waiting one closes). Other triggers leave a moving sector alone.
   */
  readonly reverses: boolean;
}

/** Scene.dynamics.movers. */
export interface MoverSet {
  readonly movers: readonly Mover[];
  readonly triggers: readonly MoverTrigger[];
  /** How far the use key reaches from the player's centre (Doom: 64 units). */
  readonly useRange: number;
  /** The player's body: a closing door that would come lower than `height` over it reopens. */
  readonly body: { readonly radius: number; readonly height: number };
}

// Paths (scene/paths.ts compiles them; world/paths.ts plays them).

/** One instance carried around a closed loop. Data only (crosses to the page by structured clone). */
export interface InstancePath {
  /** Instance.id of what is carried; the instance must be created with `moves: true`. */
  readonly instance: number;
  /** The loop's points in world space (at least 3; the last joins the first; no two consecutive equal). */
  readonly points: readonly Vec3[];
  /** 'catmull-rom' (default): a smooth curve through every point; 'polyline': straight segments. */
  readonly curve?: 'catmull-rom' | 'polyline';
  /** Scene units per second along the curve (> 0), constant. */
  readonly speed: number;
  /** Distance along the loop (scene units) at t = 0, from `points[0]`. Default 0. */
  readonly offset?: number;
  /** The world's up (default +y): object +y follows it. */
  readonly up?: Vec3;
  /** Turn object +z toward the direction of motion (perpendicular to up). Default true. */
  readonly faceMotion?: boolean;
  /**
   * A bob along up: `amplitude` scene units, `perLap` cycles per lap (a whole number ≥ 1, so that a lap
   * is a period of the whole pose).
   */
  readonly bob?: { readonly amplitude: number; readonly perLap: number };
  /** Applied to the object before it is carried (a scale, the model's own offset). Default identity. */
  readonly pathFromObject?: Mat4;
}

// Billboards (scene/billboards.ts poses them; world/billboards.ts plays them).

/** One image of a billboard: what it shows and where it sits relative to the billboard's anchor. */
export interface BillboardImage {
  /** Index into Scene.materials (the instance's material override while this image shows). */
  readonly material: number;
  /** Size in scene units. */
  readonly width: number;
  readonly height: number;
  /**
   * Where the anchor lies in the image, from its top-left corner, in scene units, x to the right and
   * y down (Doom's left and top offsets: the image's top edge is `top` above the anchor).
   */
  readonly left: number;
  readonly top: number;
  /** Shown mirrored left to right, over the same extent (Doom's flipped rotations). */
  readonly mirrored: boolean;
}

export interface Billboard {
  /** The Instance.id this billboard poses (an instance of BILLBOARD_QUAD created with `moves: true`). */
  readonly instance: number;
  /** World position of the anchor (Doom: the thing's feet, or its top less its height when it hangs). */
  readonly position: Vec3;
  /**
   * The way the object faces, in radians about +y: 0 along +x, π/2 along −z (so that Doom's map
   * angles, counter-clockwise from east, are these angles: coordinates.ts maps north to −z).
   */
  readonly facing: number;
  /** The animation's frames, played in a loop (one frame: a still billboard). */
  readonly frames: readonly BillboardFrame[];
  /** Seconds into the cycle at time 0 (so that a room's torches do not flicker in step). Default 0. */
  readonly phase?: number;
}

export interface BillboardFrame {
  /** How long the frame shows, in seconds (> 0; ignored for a still billboard's one frame). */
  readonly duration: number;
  /**
   * One image for every angle (Doom's rotation 0), or eight, Doom's rotations 1–8: image k shows the
   * object seen from 45°·k counter-clockwise (from above) of the way it faces, so image 0 is the
   * object facing the viewer, image 2 its left side, image 4 its back.
   */
  readonly images: readonly BillboardImage[];
}

// Sliding doors: Wolfenstein's doors (world/sliding-doors.ts plays them).

/** A square grid in the walk plane (x, z): cell (i, j) covers [ox + i·size, ox + (i+1)·size) × [oz + j·size, …). */
export interface WalkGrid {
  readonly originX: number;
  readonly originZ: number;
  readonly size: number;
}

export interface SlidingDoor {
  /** The Instance.id of the panel (an instance created with `moves: true`). */
  readonly instance: number;
  /** The panel's world-from-object transform while closed. */
  readonly closedPose: Mat4;
  /** World displacement of the panel when fully open (it moves along it linearly). */
  readonly slide: Vec3;
  /** The door's cell of SlidingDoorSet.grid: [i, j]. */
  readonly cell: readonly [number, number];
  /** The unit direction in the walk plane (x, z) one goes through the door (across the panel). */
  readonly across: readonly [number, number];
  /** Walk-map sector of the doorway: [floor, floor] while the door is not fully open, [floor, ceiling] when it is. */
  readonly sector: number;
  readonly floor: number;
  readonly ceiling: number;
}

export interface SlidingDoorSet {
  readonly doors: readonly SlidingDoor[];
  readonly grid: WalkGrid;
  /** 'use': the use key only; 'proximity': the use key, and standing in front of a door opens it. */
  readonly trigger: 'use' | 'proximity';
  /** How far in front of a door's panel (across it, world units) the viewer opens it. */
  readonly proximity: number;
  /** Seconds to slide fully open, and fully closed. */
  readonly travelSeconds: number;
  /** Seconds an open door waits before it closes. */
  readonly waitSeconds: number;
  /** The player's body radius: a door does not close on a body that overlaps its cell. */
  readonly bodyRadius: number;
}

// Push walls: Wolfenstein's secret doors (world/push-walls.ts plays them).

/** A cell a push wall may enter, with its walk-map sector. */
export interface PushWallCell {
  readonly cell: readonly [number, number];
  readonly sector: number;
}

export interface PushWall {
  /** The Instance.id of the block (created with `moves: true`). */
  readonly instance: number;
  /** Its world-from-object transform where the level starts it. */
  readonly restPose: Mat4;
  /** Where it starts, a cell of PushWallSet.grid, and that cell's walk-map sector. */
  readonly cell: readonly [number, number];
  readonly sector: number;
  /**
   * The free cells in each direction, nearest first, at most PushWallSet.reach: east (+x), north
   * (−z), west (−x), south (+z).
   */
  readonly paths: readonly [readonly PushWallCell[], readonly PushWallCell[], readonly PushWallCell[], readonly PushWallCell[]];
  /** Walk-map heights of an open cell. */
  readonly floor: number;
  readonly ceiling: number;
}

export interface PushWallSet {
  readonly walls: readonly PushWall[];
  readonly grid: WalkGrid;
  /** Seconds to move one cell (the game: 128 tics at 70 Hz). */
  readonly secondsPerCell: number;
  /** The most cells a block moves (the game: 2). */
  readonly reach: number;
}

/** Unit steps of the four directions, in the order of PushWall.paths. */
export const PUSH_DIRECTIONS: readonly (readonly [number, number])[] = [[1, 0], [0, -1], [-1, 0], [0, 1]];
