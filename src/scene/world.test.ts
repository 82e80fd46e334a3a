import { describe, expect, it } from 'vitest';
import { translation } from '../math/mat4.ts';
import { mergeUpdates, World, type Animator, type AnimatorFactory } from './world.ts';
import { diffuse, type Scene } from './types.ts';

const scene: Scene = {
  name: 'moving',
  meshes: [],
  instances: [],
  materials: [diffuse('grey', [0.5, 0.5, 0.5])],
  camera: { position: [0, 0, 0], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 60 },
  dynamics: {},
};
const view = { position: [0, 0, 0] as const, forward: [0, 0, -1] as const };

/** Moves instance 1 along x at 1 unit/s, writing only when the position changed; counts uses and walks. */
function slider(log: string[]): AnimatorFactory {
  return () => {
    let x = NaN;
    const a: Animator = {
      step(t, _dt, _view, out) {
        if (t === x) return;
        x = t;
        out.pose(1, { worldFromObject: translation([t, 0, 0]) });
      },
      use: () => {
        log.push('use');
        return true;
      },
      walked: (x0, _z0, x1) => void log.push(`walk ${x0}->${x1}`),
    };
    return a;
  };
}

describe('World', () => {
  it('exists only for scenes with dynamics and at least one animator', () => {
    expect(World.of({ ...scene, dynamics: undefined }, [slider([])])).toBeUndefined();
    expect(World.of(scene, [() => undefined])).toBeUndefined();
    expect(World.of(scene, [slider([])])).toBeDefined();
  });

  it('advances the clock and reports only what changed', () => {
    const world = World.of(scene, [slider([])])!;
    const first = world.advance(0, view)!;
    expect(first.instances.get(1)?.worldFromObject?.[12]).toBe(0);
    expect(world.advance(0, view)).toBeUndefined();
    expect(world.advance(0.5, view)!.instances.get(1)?.worldFromObject?.[12]).toBe(0.5);
    expect(world.seconds).toBe(0.5);
    expect(() => world.advance(-1, view)).toThrow(RangeError);
  });

  it('advanceTo merges the steps into one update ending at the target time', () => {
    const world = World.of(scene, [slider([])])!;
    const u = world.advanceTo(2, view, 0.1);
    expect(u.instances.get(1)?.worldFromObject?.[12]).toBeCloseTo(2, 12);
    expect(world.seconds).toBeCloseTo(2, 12);
    expect(() => world.advanceTo(1, view)).toThrow(RangeError);
  });

  it('passes the use key and walks to the animators', () => {
    const log: string[] = [];
    const world = World.of(scene, [slider(log)])!;
    expect(world.use(view)).toBe(true);
    world.walked(1, 0, 2, 0);
    expect(log).toEqual(['use', 'walk 1->2']);
  });

  it('mergeUpdates: later updates win, poses and edits merge field by field', () => {
    const a = { instances: new Map([[1, { material: 3 }]]), morphWeights: new Map(), materials: new Map([[0, { roughness: 0.5 }]]), walkHeights: new Map() };
    const b = { instances: new Map([[1, { worldFromObject: translation([1, 2, 3]) }]]), morphWeights: new Map([[0, new Float32Array([1])]]), materials: new Map([[0, { metallic: 1 }]]), walkHeights: new Map([[4, [0, 8] as const]]) };
    const m = mergeUpdates([a, undefined, b]);
    expect(m.instances.get(1)).toEqual({ material: 3, worldFromObject: translation([1, 2, 3]) });
    expect(m.materials.get(0)).toEqual({ roughness: 0.5, metallic: 1 });
    expect(m.walkHeights.get(4)).toEqual([0, 8]);
  });
});
