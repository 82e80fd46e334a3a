import { describe, expect, it } from 'vitest';
import { reflectModule } from '../gpu/wgsl/reflect.ts';
import { colorScale, COLOR_SCALE_STOPS, debugLegend, legendGradientCss, stopRgb } from './debug-legend.ts';
import { DEFAULT_SETTINGS } from './settings.ts';

const facts = { maxDepth: 15, maxLeafSize: 4, imageMax: 37 };
const luminance = ([r, g, b]: [number, number, number]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

describe('colour scale', () => {
  it('has as many stops as debug-compose.wgsl reads', () => {
    const params = reflectModule('passes/debug-compose').defs.uniforms.params!;
    const stops = (params.typeDefinition as unknown as { fields: Record<string, { type: { numElements: number } }> }).fields.scale_stops!;
    expect(stops.type.numElements).toBe(COLOR_SCALE_STOPS.length);
  });

  it('runs from the first stop to the last and passes through every stop', () => {
    expect(colorScale(0)).toEqual(stopRgb(COLOR_SCALE_STOPS[0]!));
    expect(colorScale(1)).toEqual(stopRgb(COLOR_SCALE_STOPS.at(-1)!));
    expect(colorScale(-3)).toEqual(colorScale(0));
    expect(colorScale(7)).toEqual(colorScale(1));
    COLOR_SCALE_STOPS.forEach((hex, i) => {
      const c = colorScale(i / (COLOR_SCALE_STOPS.length - 1));
      stopRgb(hex).forEach((v, k) => expect(c[k]).toBeCloseTo(v, 12));
    });
    expect(stopRgb('#fde725')).toEqual([253 / 255, 231 / 255, 37 / 255]);
  });

  it('is perceptually ordered: lightness rises monotonically from min to max', () => {
    let previous = -1;
    for (let t = 0; t <= 1; t += 1 / 64) {
      const l = luminance(colorScale(t));
      expect(l).toBeGreaterThan(previous);
      previous = l;
    }
  });

  it('is a CSS gradient with the same stops, evenly spaced', () => {
    expect(legendGradientCss()).toBe(
      'linear-gradient(to right, #440154 0.0%, #482878 12.5%, #3e4989 25.0%, #31688e 37.5%, #26828e 50.0%, #1f9e89 62.5%, #35b779 75.0%, #6ece58 87.5%, #fde725 100.0%)',
    );
  });
});

describe('debugLegend', () => {
  const legend = (changes: Partial<typeof DEFAULT_SETTINGS>) => debugLegend({ ...DEFAULT_SETTINGS, ...changes }, facts);

  it('gives the numbers of the scalar views: image maximum, fixed maximum, leaf size, depth', () => {
    expect(legend({ debugView: 'heat-nodes' })).toEqual({ view: 'heat-nodes', label: 'BVH nodes visited per primary ray', scale: { min: 0, max: 37, auto: true, stops: COLOR_SCALE_STOPS } });
    expect(legend({ debugView: 'heat-triangles', heatMax: 100 }).scale).toMatchObject({ min: 0, max: 100, auto: false });
    expect(legend({ debugView: 'leaf-size', heatMax: 100 }).scale).toMatchObject({ max: 4, auto: false });
    expect(legend({ debugView: 'bvh-depth' }).scale).toMatchObject({ max: 15, auto: false });
  });

  it('labels the other views without a scale', () => {
    expect(legend({ debugView: 'wireframe', wireframeDepth: 3 })).toEqual({ view: 'wireframe', label: 'BVH boxes at depth 3 of 15: interior boxes amber, leaves cyan' });
    for (const debugView of ['none', 'normals', 'albedo', 'barycentrics', 'triangle-id'] as const) expect(legend({ debugView }).scale).toBeUndefined();
  });
});
