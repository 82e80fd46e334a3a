/**
 * Held keys over time. The viewer moves the camera by how long each key was really held between two
 * frames, not by what is held when a frame starts: at 0.1 fps a 3 s press of W falls between frames
 * and would otherwise move nothing, and at 0.7 fps a frame would see only a fraction of a turn.
 *
 * Every press or release closes a span of constant input; take() hands the spans since the last take
 * (they cover that time exactly, idle time included) to CameraController.advance. Pure: times are
 * passed in (milliseconds, performance.now()), so tests drive it without a DOM.
 */
import { NO_INPUT, type HeldSpan, type MoveInput } from './camera-controller.ts';

const AXES: Record<string, [keyof Omit<MoveInput, 'run'>, number]> = {
  KeyW: ['forward', 1],
  ArrowUp: ['forward', 1],
  KeyS: ['forward', -1],
  ArrowDown: ['forward', -1],
  KeyD: ['right', 1],
  KeyA: ['right', -1],
  ArrowRight: ['turn', 1],
  ArrowLeft: ['turn', -1],
  Space: ['up', 1],
  KeyR: ['up', 1],
  KeyC: ['up', -1],
  KeyF: ['up', -1],
};

/** Whether a key code moves or turns the camera (or is a Shift, which makes it run). */
export function isMovementKey(code: string): boolean {
  return code in AXES || code.startsWith('Shift');
}

/** The axes of a set of held key codes. */
export function moveOf(held: ReadonlySet<string>): MoveInput {
  const axes = { forward: 0, right: 0, up: 0, turn: 0 };
  for (const code of held) {
    const axis = AXES[code];
    if (axis) axes[axis[0]] += axis[1];
  }
  const clamp = (v: number) => Math.max(-1, Math.min(1, v));
  const run = held.has('ShiftLeft') || held.has('ShiftRight');
  if (axes.forward === 0 && axes.right === 0 && axes.up === 0 && axes.turn === 0) return NO_INPUT;
  return { forward: clamp(axes.forward), right: clamp(axes.right), up: clamp(axes.up), turn: clamp(axes.turn), run };
}

function sameInput(a: MoveInput, b: MoveInput): boolean {
  return a.forward === b.forward && a.right === b.right && a.up === b.up && a.turn === b.turn && a.run === b.run;
}

export class KeyTimeline {
  private readonly held = new Set<string>();
  private spans: HeldSpan[] = [];
  /** The start of the open span (ms). */
  private since: number;

  constructor(now = 0) {
    this.since = now;
  }

  /** A movement key went down at `at` (auto-repeats of a held key change nothing). */
  press(code: string, at: number): void {
    if (!isMovementKey(code) || this.held.has(code)) return;
    this.close(at);
    this.held.add(code);
  }

  release(code: string, at: number): void {
    if (!this.held.has(code)) return;
    this.close(at);
    this.held.delete(code);
  }

  /** Every key let go (the window lost focus: its key-ups never arrive). */
  releaseAll(at: number): void {
    this.close(at);
    this.held.clear();
  }

  /** What is held now, as axes. */
  get move(): MoveInput {
    return moveOf(this.held);
  }

  get active(): boolean {
    return this.held.size > 0;
  }

  /** The spans of constant input since the last take (or restart), up to `now`; their seconds sum to that time. */
  take(now: number): HeldSpan[] {
    this.close(now);
    const spans = this.spans;
    this.spans = [];
    return spans;
  }

  /**
   * Forgets the time before `now` (the viewer was paused or hidden: keys held then move nothing), and
   * keeps what is held.
   */
  restart(now: number): void {
    this.spans = [];
    this.since = now;
  }

  private close(at: number): void {
    const end = Math.max(at, this.since);
    const seconds = (end - this.since) / 1000;
    this.since = end;
    if (seconds <= 0) return;
    const input = this.move;
    const last = this.spans[this.spans.length - 1];
    if (last && sameInput(last.input, input)) this.spans[this.spans.length - 1] = { input, seconds: last.seconds + seconds };
    else this.spans.push({ input, seconds });
  }
}
