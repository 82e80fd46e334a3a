/**
 * Doom's door and lift line specials (vanilla p_spec.c, p_switch.c, p_doors.c, p_plats.c;
 * https://doomwiki.org/wiki/Linedef_type): which lines move which sectors, how, and how they are
 * triggered. Keyed doors are treated as unlocked (there is no inventory). Gun-triggered lines (46)
 * are left out: there is no shooting. Pure data.
 *
 * Trigger letters as on the Doom wiki: D = manual (use on the door's own line; it moves the
 * line's back sector), S = switch (use; moves the sectors tagged like the line), W = walk over
 * (tagged sectors); 1 = once, R = repeatable.
 */
import type { MoverAction } from '../../scene/dynamics-types.ts';

/** Doom's clock: every speed and delay below is per tic. */
export const TICS_PER_SECOND = 35;
/** VDOORSPEED: map units per tic; blazing doors move four times as fast. */
export const DOOR_SPEED = 2;
export const BLAZING_DOOR_SPEED = 4 * DOOR_SPEED;
/** VDOORWAIT: tics an opened door waits before it closes. */
export const DOOR_WAIT = 150;
/** How long a "close, wait 30 s, open" door stays shut. */
export const DOOR_CLOSED_WAIT = 30 * TICS_PER_SECOND;
/** PLATSPEED × 4 (EV_DoPlat's downWaitUpStay): map units per tic; blazing lifts twice that. */
export const LIFT_SPEED = 4;
export const BLAZING_LIFT_SPEED = 8;
/** PLATWAIT × 35: tics a lowered lift waits before it rises. */
export const LIFT_WAIT = 3 * TICS_PER_SECOND;
/** A door opens to the lowest ceiling around it, less this (P_FindLowestCeilingSurrounding − 4). */
export const DOOR_TOP_GAP = 4;

export interface MoverSpecial {
  readonly trigger: 'manual' | 'switch' | 'walk';
  readonly repeatable: boolean;
  readonly action: MoverAction;
  /** Map units per tic. */
  readonly speed: number;
  /** Tics of the action's wait (after opening, after closing, or at the bottom). */
  readonly wait: number;
}

const door = (trigger: MoverSpecial['trigger'], repeatable: boolean, action: MoverAction, blazing = false): MoverSpecial => ({
  trigger, repeatable, action,
  speed: blazing ? BLAZING_DOOR_SPEED : DOOR_SPEED,
  wait: action === 'close-wait-open' ? DOOR_CLOSED_WAIT : action === 'open-wait-close' ? DOOR_WAIT : 0,
});
const lift = (trigger: MoverSpecial['trigger'], repeatable: boolean, blazing = false): MoverSpecial => ({
  trigger, repeatable, action: 'lower-wait-raise', speed: blazing ? BLAZING_LIFT_SPEED : LIFT_SPEED, wait: LIFT_WAIT,
});

/** Every door and lift special by its linedef special number. */
export const MOVER_SPECIALS: ReadonlyMap<number, MoverSpecial> = new Map<number, MoverSpecial>([
  // Manual doors: DR open, wait, close (26–28 blue, yellow, red keys); D1 open and stay (32–34 keyed).
  [1, door('manual', true, 'open-wait-close')],
  [26, door('manual', true, 'open-wait-close')],
  [27, door('manual', true, 'open-wait-close')],
  [28, door('manual', true, 'open-wait-close')],
  [31, door('manual', false, 'open')],
  [32, door('manual', false, 'open')],
  [33, door('manual', false, 'open')],
  [34, door('manual', false, 'open')],
  [117, door('manual', true, 'open-wait-close', true)],
  [118, door('manual', false, 'open', true)],
  // Walk-over doors.
  [2, door('walk', false, 'open')],
  [3, door('walk', false, 'close')],
  [4, door('walk', false, 'open-wait-close')],
  [16, door('walk', false, 'close-wait-open')],
  [75, door('walk', true, 'close')],
  [76, door('walk', true, 'close-wait-open')],
  [86, door('walk', true, 'open')],
  [90, door('walk', true, 'open-wait-close')],
  [105, door('walk', true, 'open-wait-close', true)],
  [106, door('walk', true, 'open', true)],
  [107, door('walk', true, 'close', true)],
  [108, door('walk', false, 'open-wait-close', true)],
  [109, door('walk', false, 'open', true)],
  [110, door('walk', false, 'close', true)],
  // Switched doors (99, 133–137: keyed blazing doors).
  [29, door('switch', false, 'open-wait-close')],
  [42, door('switch', true, 'close')],
  [50, door('switch', false, 'close')],
  [61, door('switch', true, 'open')],
  [63, door('switch', true, 'open-wait-close')],
  [103, door('switch', false, 'open')],
  [111, door('switch', false, 'open-wait-close', true)],
  [112, door('switch', false, 'open', true)],
  [113, door('switch', false, 'close', true)],
  [114, door('switch', true, 'open-wait-close', true)],
  [115, door('switch', true, 'open', true)],
  [116, door('switch', true, 'close', true)],
  [99, door('switch', true, 'open', true)],
  [133, door('switch', false, 'open', true)],
  [134, door('switch', true, 'open', true)],
  [135, door('switch', false, 'open', true)],
  [136, door('switch', true, 'open', true)],
  [137, door('switch', false, 'open', true)],
  // Lifts: lower to the lowest floor around, wait 3 s, rise again.
  [10, lift('walk', false)],
  [88, lift('walk', true)],
  [120, lift('walk', true, true)],
  [121, lift('walk', false, true)],
  [21, lift('switch', false)],
  [62, lift('switch', true)],
  [122, lift('switch', false, true)],
  [123, lift('switch', true, true)],
]);
