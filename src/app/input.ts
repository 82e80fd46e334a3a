/**
 * Keyboard and mouse for the viewer: held keys become MoveInput axes, mouse movement under pointer
 * lock (drag on the canvas to start it; Esc releases) becomes look deltas. Keys: WASD (or the up
 * and down arrows) move, the left and right arrows turn, Space or R up, C or F down, Shift run; E is
 * the use key (doors, lifts), and so is Space while walking (onUse says which key: the page decides).
 * Keys typed into form fields (the settings panel) are not movement. A click that is not the end of a drag, outside pointer lock, is reported (select;
 * with Alt, focus); Esc outside pointer lock is reported too (deselect).
 */
import type { HeldSpan, MoveInput } from './camera-controller.ts';
import { isMovementKey, KeyTimeline } from './key-timeline.ts';

/** A click on the canvas: where (CSS pixels from its top-left corner) and whether Alt was held. */
export interface CanvasClick {
  readonly x: number;
  readonly y: number;
  readonly alt: boolean;
}

/** The keys that may mean "use": E always, Space only while walking (where it moves nothing). */
export type UseKey = 'KeyE' | 'Space';

export interface InputHandlers {
  onClick?(click: CanvasClick): void;
  /** A use key went down (not its auto-repeat). */
  onUse?(key: UseKey): void;
  onEscape?(): void;
}

/** A press that moves this far (CSS pixels) before release is a drag (mouse look), not a click. */
const DRAG_THRESHOLD = 4;

/**
 * When a key event happened (performance.now() time base): its timeStamp, taken when the browser
 * received the input, not when the page's busy main thread got round to handling it; a key pressed
 * during a long task is timed from the press. Never later than now (a clock of another origin is not
 * trusted).
 */
function eventTime(e: Event): number {
  const now = performance.now();
  return e.timeStamp > 0 && e.timeStamp <= now ? e.timeStamp : now;
}

export class Input {
  /** Held movement keys over time: the camera moves by how long each was held. */
  private readonly keys = new KeyTimeline(performance.now());
  private lookX = 0;
  private lookY = 0;
  private readonly cleanup: (() => void)[] = [];

  /** Where the primary button went down on the canvas, while it is held. */
  private press?: { x: number; y: number };
  /** Whether the current or last press became a drag (its click is not a selection). */
  private dragged = false;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    handlers: InputHandlers = {},
  ) {
    const isTyping = (e: Event) => {
      const t = e.target as HTMLElement | null;
      return !!t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA' || t.isContentEditable);
    };
    const locked = () => document.pointerLockElement === canvas;
    this.listen(window, 'keydown', (e) => {
      const k = e as KeyboardEvent;
      if (k.code === 'Escape' && !locked() && !isTyping(k)) handlers.onEscape?.();
      if (isTyping(k) || k.ctrlKey || k.metaKey || k.altKey) return;
      if ((k.code === 'KeyE' || k.code === 'Space') && !k.repeat) handlers.onUse?.(k.code);
      if (k.code === 'KeyE') k.preventDefault();
      if (isMovementKey(k.code)) {
        this.keys.press(k.code, eventTime(k));
        k.preventDefault();
      }
    });
    this.listen(window, 'keyup', (e) => this.keys.release((e as KeyboardEvent).code, eventTime(e)));
    // Keys released while the window had no focus never send keyup.
    this.listen(window, 'blur', () => this.keys.releaseAll(performance.now()));
    this.listen(canvas, 'mousedown', (e) => {
      const m = e as MouseEvent;
      if (m.button !== 0 || locked()) return;
      this.press = { x: m.clientX, y: m.clientY };
      this.dragged = false;
    });
    this.listen(window, 'mouseup', () => (this.press = undefined));
    this.listen(canvas, 'click', (e) => {
      const m = e as MouseEvent;
      if (this.dragged || locked()) return;
      handlers.onClick?.({ x: m.offsetX, y: m.offsetY, alt: m.altKey });
    });
    this.listen(document, 'mousemove', (e) => {
      const m = e as MouseEvent;
      // A drag from the canvas starts mouse look (the press is the user gesture pointer lock needs).
      if (this.press && !locked() && Math.hypot(m.clientX - this.press.x, m.clientY - this.press.y) > DRAG_THRESHOLD) {
        this.dragged = true;
        this.press = undefined;
        canvas.requestPointerLock?.()?.catch?.(() => {});
      }
      if (!locked()) return;
      this.lookX += (e as MouseEvent).movementX;
      this.lookY += (e as MouseEvent).movementY;
    });
  }

  /** The held keys as axes. */
  get move(): MoveInput {
    return this.keys.move;
  }

  /** The spans of held input since the last call (or restart), up to `now` (performance.now()). */
  takeHeld(now: number): HeldSpan[] {
    return this.keys.take(now);
  }

  /** Forgets held time before `now` (the viewer starts or resumes playing). */
  restartClock(now: number): void {
    this.keys.restart(now);
  }

  /** Mouse movement since the last call, in pixels. */
  takeLook(): [number, number] {
    const look: [number, number] = [this.lookX, this.lookY];
    this.lookX = this.lookY = 0;
    return look;
  }

  get active(): boolean {
    return this.keys.active;
  }

  destroy(): void {
    for (const c of this.cleanup) c();
    if (document.pointerLockElement === this.canvas) document.exitPointerLock();
  }

  private listen(target: EventTarget, type: string, handler: (e: Event) => void): void {
    target.addEventListener(type, handler);
    this.cleanup.push(() => target.removeEventListener(type, handler));
  }
}
