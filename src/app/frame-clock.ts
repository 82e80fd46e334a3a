/**
 * One frame's motion in the viewer: the camera moved by the keys held since the last frame (however
 * long the frame took: key-timeline.ts) and the world advanced by that same time, taking turns in
 * slices of at most SLICE_SECONDS, what one frame does at 30 fps. A long frame plays as a run of
 * short ones: a door opened during it lets the walker through when it would at 30 fps, a lift
 * carries them down, a walk-over line fires where it is crossed, a closing door reopens on them.
 * The world itself steps in fixed ticks (world/world.ts), so how the frames fall changes nothing in
 * it. Pure: the tests drive it with a controller, a world and spans of held keys.
 */
import type { SceneUpdate } from '../scene/dynamics.ts';
import { mergeUpdates, type World } from '../world/world.ts';
import type { CameraController, HeldSpan } from './camera-controller.ts';

/** The longest turn of the camera or the world within a frame: one frame at 30 fps. */
export const SLICE_SECONDS = 1 / 30;

/**
 * The most world time one frame plays. Hidden time never reaches a frame (the page starts the clock
 * again when the tab shows: viewer.ts), but a machine that slept with the page open, or a debugger
 * that held it, makes a frame of minutes or hours that is not play. Frames of play on a CPU adapter
 * are long too: in the page on the loaded 2-core test machine (SwiftShader, the budget's resolution
 * floor), Cornell took 12–18 s a frame and E1M1 64–90 s; those are followed exactly. A longer frame
 * plays the world this long, spread over the frame (held keys still move the camera by their whole
 * time). Catching up costs about 65 µs of world per 1/30 s slice on E1M1: a quarter of a second at
 * the bound (the camera's own steps cost what they cost at any frame rate).
 */
export const MAX_WORLD_SECONDS = 120;

export interface PlayedFrame {
  /** Whether the camera moved or turned. */
  readonly moved: boolean;
  /** What the world changed over the frame, merged (undefined: nothing). */
  readonly update?: SceneUpdate;
}

/**
 * Plays a frame of `held` spans (their seconds are the frame's time): the camera and, with `animate`,
 * the world in turns; without it the world only sees the view (billboards turn; the clock holds).
 * The walker's moves go to the world's walk-over lines, the world's heights to the walker.
 */
export function playFrame(c: CameraController, world: World | undefined, held: readonly HeldSpan[], animate: boolean): PlayedFrame {
  if (!world) return { moved: c.advance(held) };
  const total = held.reduce((sum, h) => sum + h.seconds, 0);
  const worldSeconds = animate ? Math.min(total, MAX_WORLD_SECONDS) : 0;
  // Past the bound the slices grow instead of multiplying (an hour's frame costs what two minutes do).
  const slices = Math.max(1, Math.ceil(worldSeconds / SLICE_SECONDS - 1e-9));
  const worldSlice = worldSeconds / slices;
  const updates: SceneUpdate[] = [];
  let moved = false;
  // Where the slices have got to in `held`: span index and seconds of it taken.
  let span = 0;
  let taken = 0;
  for (let i = 0; i < slices; i++) {
    const last = i === slices - 1;
    const piece: HeldSpan[] = [];
    for (let want = total / slices; span < held.length && (want > 0 || last); ) {
      const h = held[span]!;
      const rest = h.seconds - taken;
      const take = last ? rest : Math.min(rest, want);
      if (take > 0) piece.push({ input: h.input, seconds: take });
      if (take < rest) {
        taken += take;
        break;
      }
      want -= take;
      span++;
      taken = 0;
    }
    moved = c.advance(piece) || moved;
    for (const [x0, z0, x1, z1] of c.takeWalked()) world.walked(x0, z0, x1, z1);
    const camera = c.camera();
    const update = world.advance(worldSlice, { position: camera.position, forward: camera.forward, walking: c.mode === 'walk' });
    if (!update) continue;
    c.setSectorHeights(update.walkHeights);
    updates.push(update);
  }
  return updates.length > 0 ? { moved, update: mergeUpdates(updates) } : { moved };
}
