/**
 * The colour scale of the scalar debug views and the legend that explains a view: what it shows,
 * and for scalar views the numbers at both ends of the scale and its colours, ready to be drawn as a
 * CSS gradient. Pure (no GPU, no DOM): the page draws the legend, shaders/passes/debug-compose.wgsl
 * colours the pixels from the same stops.
 */
import type { DebugView, RenderSettings } from './settings.ts';

// The scale itself is in math/ so that passes/debug-compose-pass.ts, below the renderer, can use it.
import { COLOR_SCALE_STOPS } from '../math/color-scale.ts';
export { COLOR_SCALE_STOPS, colorScale, legendGradientCss, stopRgb } from '../math/color-scale.ts';

export interface DebugScale {
  /** The value at the left end of the scale (always 0). */
  readonly min: number;
  /** The value at the right end; larger values take the end colour. */
  readonly max: number;
  /** Whether max is the image's own maximum (heatMax 'auto') rather than a fixed number. */
  readonly auto: boolean;
  /** sRGB colours (CSS hex) at evenly spaced positions from min to max. */
  readonly stops: readonly string[];
}

export interface DebugLegend {
  readonly view: DebugView;
  /** One line that says what a pixel shows, e.g. "BVH nodes visited per primary ray". */
  readonly label: string;
  /** Present for the scalar views (heat maps, leaf size, BVH depth). */
  readonly scale?: DebugScale;
}

const LABELS: Record<DebugView, string> = {
  none: 'the rendered image',
  'heat-nodes': 'BVH nodes visited per primary ray',
  'heat-triangles': 'ray/triangle tests per primary ray',
  wireframe: 'BVH boxes at depth {depth}: interior boxes amber, leaves cyan',
  'leaf-size': 'triangles in the BVH leaf hit',
  'bvh-depth': 'depth of the BVH leaf hit (root = 0)',
  normals: 'shading normal: rgb = (n + 1) / 2, world axes',
  albedo: 'surface albedo (sRGB)',
  barycentrics: 'barycentric coordinates: rgb = weights of v0, v1, v2',
  'triangle-id': 'one colour per triangle',
};

/** What the host knows about the scene for the legend. */
export interface LegendFacts {
  readonly maxDepth: number;
  readonly maxLeafSize: number;
  /** The image's maximum of the view's scalar, when heatMax is 'auto'. */
  readonly imageMax: number;
}

/** The value at the top of the colour scale of a scalar view, or undefined for the other views. */
export function scaleMax(settings: Pick<RenderSettings, 'debugView' | 'heatMax'>, facts: LegendFacts): number | undefined {
  switch (settings.debugView) {
    case 'heat-nodes':
    case 'heat-triangles':
      return settings.heatMax === 'auto' ? Math.max(facts.imageMax, 1) : settings.heatMax;
    case 'leaf-size':
      return Math.max(facts.maxLeafSize, 1);
    case 'bvh-depth':
      return Math.max(facts.maxDepth, 1);
    default:
      return undefined;
  }
}

export function debugLegend(settings: Pick<RenderSettings, 'debugView' | 'heatMax' | 'wireframeDepth'>, facts: LegendFacts): DebugLegend {
  const view = settings.debugView;
  const label = LABELS[view].replace('{depth}', `${settings.wireframeDepth} of ${facts.maxDepth}`);
  const max = scaleMax(settings, facts);
  if (max === undefined) return { view, label };
  const auto = (view === 'heat-nodes' || view === 'heat-triangles') && settings.heatMax === 'auto';
  return { view, label, scale: { min: 0, max, auto, stops: COLOR_SCALE_STOPS } };
}
