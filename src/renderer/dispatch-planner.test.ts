import { describe, expect, it } from 'vitest';
import { bandTiles, DispatchPlanner } from './dispatch-planner.ts';

describe('bandTiles', () => {
  it.each([
    [100, 37, 1],
    [100, 37, 4],
    [7, 5, 9],
  ])('covers a %i×%i image exactly with %i bands', (w, h, bands) => {
    const tiles = bandTiles(w, h, bands);
    let y = 0;
    for (const t of tiles) {
      expect(t.x).toBe(0);
      expect(t.width).toBe(w);
      expect(t.y).toBe(y);
      expect(t.height).toBeGreaterThan(0);
      y += t.height;
    }
    expect(y).toBe(h);
  });
});

describe('DispatchPlanner', () => {
  it('grows samples per dispatch while submits are short, never past what remains', () => {
    const p = new DispatchPlanner(64, 64, { targetMs: 50, maxSamplesPerDispatch: 16, maxBands: 8 });
    for (let i = 0; i < 10; i++) p.observe(1);
    expect(p.state.samplesPerDispatch).toBe(16);
    expect(p.next(3).samples).toBe(3);
  });

  it('splits the image into bands when one sample of the whole image is too slow, and merges them back', () => {
    const p = new DispatchPlanner(64, 64, { targetMs: 50, maxSamplesPerDispatch: 16, maxBands: 8 });
    for (let i = 0; i < 10; i++) p.observe(1000);
    expect(p.state).toEqual({ samplesPerDispatch: 1, bands: 8 });
    expect(p.next(100).tiles).toHaveLength(8);
    p.observe(1);
    expect(p.state.bands).toBe(4);
  });

  it('keeps a batch that lands near the target', () => {
    const p = new DispatchPlanner(64, 64, { targetMs: 50, maxSamplesPerDispatch: 16, maxBands: 8 });
    p.observe(1);
    p.observe(60);
    expect(p.state).toEqual({ samplesPerDispatch: 2, bands: 1 });
  });
});

describe('DispatchPlanner with fixed samples per dispatch (render --chunk)', () => {
  it('keeps the samples per dispatch whatever the timing and adapts only the bands', () => {
    const planner = new DispatchPlanner(64, 64, { targetMs: 60, maxSamplesPerDispatch: 64, maxBands: 64, fixedSamples: 8 });
    expect(planner.next(100).samples).toBe(8);
    planner.observe(1);
    expect(planner.next(100).samples).toBe(8);
    planner.observe(1000);
    expect(planner.next(100)).toMatchObject({ samples: 8 });
    expect(planner.next(100).tiles.length).toBe(2);
    expect(planner.next(5).samples).toBe(5);
  });
});
