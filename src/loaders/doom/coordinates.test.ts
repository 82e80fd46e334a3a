import { describe, expect, it } from 'vitest';
import { cross, sub } from '../../math/vec3.ts';
import { directionFromAngle, flatUv, toWorld } from './coordinates.ts';

/** Without the sign of zero, which toEqual would tell apart. */
const clean = (v: readonly number[]) => v.map((c) => c + 0);

describe('Doom to Lantern coordinates', () => {
  it('puts heights on +y and north on −z, keeping the scale', () => {
    expect(toWorld(10, 20, 30)).toEqual([10, 30, -20]);
  });

  it('is a rotation: a counter-clockwise map triangle faces up', () => {
    const [a, b, c] = [toWorld(0, 0, 5), toWorld(1, 0, 5), toWorld(0, 1, 5)];
    expect(clean(cross(sub(b, a), sub(c, a)))).toEqual([0, 1, 0]);
    // The images of Doom's x, y and up axes form a right-handed frame like the originals.
    const [x, y, up] = [toWorld(1, 0, 0), toWorld(0, 1, 0), toWorld(0, 0, 1)];
    expect(clean(cross(x, y))).toEqual(clean(up));
  });

  it('turns map angles into horizontal directions', () => {
    expect(directionFromAngle(0)).toEqual([1, 0, 0]);
    const north = directionFromAngle(90);
    expect(north[0]).toBeCloseTo(0, 12);
    expect(north[2]).toBeCloseTo(-1, 12);
    const west = directionFromAngle(180);
    expect(west[0]).toBeCloseTo(-1, 12);
  });

  it('maps flats to texel (x mod 64, −y mod 64)', () => {
    expect(clean(flatUv(64, 0))).toEqual([1, 0]);
    const [u, v] = flatUv(70, 10);
    expect(u * 64).toBeCloseTo(70, 12);
    expect(v * 64).toBeCloseTo(-10, 12); // row 54 after wrapping: rows run south
    expect(flatUv(70, 10, 1, -1)).toEqual([u - 1, v + 1]);
  });
});
