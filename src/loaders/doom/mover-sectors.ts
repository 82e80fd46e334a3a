/**
 * Which sectors of a Doom map can move, and how far: the doors and lifts that the line specials of
 * specials.ts act on (manual doors: the line's back sector; the others: the sectors tagged like the
 * line), their heights when open or lowered (p_spec.c P_FindLowestCeilingSurrounding,
 * P_FindLowestFloorSurrounding), and the trigger lines in world coordinates. Pure.
 */
import { toWorld } from './coordinates.ts';
import { NO_SIDEDEF, type DoomMap } from './map-types.ts';
import { DOOR_TOP_GAP, MOVER_SPECIALS, TICS_PER_SECOND } from './specials.ts';
import type { SectorMotionRange } from './walls.ts';
import { moverKindOf, type MoverAction, type MoverTrigger } from '../../scene/dynamics-types.ts';

export interface MovingSector {
  readonly sector: number;
  readonly kinds: readonly ('door' | 'lift')[];
  readonly doorTop: number;
  readonly liftBottom: number;
  readonly range: SectorMotionRange;
  /** The sector's boundary lines in the walk plane, x0, z0, x1, z1 each. */
  readonly outline: Float32Array;
}

/** A MoverTrigger as the map has it: its linedef, and the sectors it moves (sector indices) in place of movers. */
export interface MoverTriggerLine extends Omit<MoverTrigger, 'movers'> {
  readonly linedef: number;
  readonly sectors: readonly number[];
}

export interface MapMovers {
  /** In sector order. */
  readonly sectors: readonly MovingSector[];
  readonly triggers: readonly MoverTriggerLine[];
}

/** Doom's manual raise doors, which a second use sends back (EV_VerticalDoor). */
const REVERSING = new Set([1, 26, 27, 28, 117]);

export function findMovers(map: DoomMap, warn: (message: string) => void = () => {}): MapMovers {
  const sectorOfSide = (side: number) => (side === NO_SIDEDEF ? undefined : map.sidedefs[side]?.sector);
  const triggers: MoverTriggerLine[] = [];
  const actions = new Map<number, Set<MoverAction>>();
  const untagged: number[] = [];
  map.linedefs.forEach((line, index) => {
    const special = MOVER_SPECIALS.get(line.special);
    const a = map.vertices[line.v1], b = map.vertices[line.v2];
    if (!special || !a || !b) return;
    let sectors: number[];
    if (special.trigger === 'manual') {
      const back = sectorOfSide(line.back);
      sectors = back === undefined || back >= map.sectors.length ? [] : [back];
    } else if (line.tag === 0) {
      // Vanilla would move every untagged sector: a mapping error, left alone.
      untagged.push(index);
      return;
    } else sectors = map.sectors.flatMap((s, i) => (s.tag === line.tag ? [i] : []));
    if (sectors.length === 0) return;
    for (const s of sectors) {
      if (!actions.has(s)) actions.set(s, new Set());
      actions.get(s)!.add(special.action);
    }
    const [x0, , z0] = toWorld(a.x, a.y, 0);
    const [x1, , z1] = toWorld(b.x, b.y, 0);
    triggers.push({
      linedef: index, line: [x0, z0, x1, z1],
      activation: special.trigger === 'walk' ? 'walk' : 'use',
      repeatable: special.repeatable,
      sectors, action: special.action,
      speed: special.speed * TICS_PER_SECOND,
      wait: special.wait / TICS_PER_SECOND,
      reverses: REVERSING.has(line.special),
    });
  });
  if (untagged.length > 0) warn(`${untagged.length} door or lift line${untagged.length > 1 ? 's have' : ' has'} no tag (linedef ${untagged[0]}${untagged.length > 1 ? ', ...' : ''}); left inert`);

  const sectors: MovingSector[] = [...actions.keys()].sort((x, y) => x - y).map((sector) => {
    const own = map.sectors[sector]!;
    let lowestCeiling = Infinity, lowestFloor = own.floorHeight;
    const outline: number[] = [];
    for (const line of map.linedefs) {
      const front = sectorOfSide(line.front), back = sectorOfSide(line.back);
      if (front !== sector && back !== sector) continue;
      const a = map.vertices[line.v1], b = map.vertices[line.v2];
      if (a && b) outline.push(a.x, -a.y, b.x, -b.y);
      const other = front === sector ? back : front;
      const o = other === undefined ? undefined : map.sectors[other];
      if (!o || other === sector) continue;
      lowestCeiling = Math.min(lowestCeiling, o.ceilingHeight);
      lowestFloor = Math.min(lowestFloor, o.floorHeight);
    }
    // A sector with no neighbours: a door opens to its own ceiling.
    const doorTop = Number.isFinite(lowestCeiling) ? lowestCeiling - DOOR_TOP_GAP : own.ceilingHeight;
    const done = actions.get(sector)!;
    const kinds = [...new Set([...done].map(moverKindOf))].sort();
    const ceiling: [number, number] = [0, 0];
    const floor: [number, number] = [0, 0];
    for (const action of done) {
      if (action === 'lower-wait-raise') floor[0] = Math.min(floor[0], lowestFloor - own.floorHeight);
      else {
        if (action !== 'open') ceiling[0] = Math.min(ceiling[0], own.floorHeight - own.ceilingHeight);
        if (action === 'open' || action === 'open-wait-close') ceiling[1] = Math.max(ceiling[1], doorTop - own.ceilingHeight);
        ceiling[0] = Math.min(ceiling[0], doorTop - own.ceilingHeight);
      }
    }
    // A door that closes onto a lowered floor goes lower still.
    if (kinds.length > 1) ceiling[0] += floor[0];
    return { sector, kinds, doorTop, liftBottom: lowestFloor, range: { floor, ceiling }, outline: new Float32Array(outline) };
  });
  return { sectors, triggers };
}
