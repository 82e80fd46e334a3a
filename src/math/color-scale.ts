/**
 * The colour scale of the scalar debug views, shared by the pass that colours pixels
 * (passes/debug-compose-pass.ts, shaders/passes/debug-compose.wgsl) and the legend the page draws
 * (renderer/debug-legend.ts). Pure numbers and one CSS string.
 */

/**
 * Viridis (van der Walt & Smith, matplotlib 2.0's default, 2015): perceptually uniform, readable in
 * grey and by colour-blind viewers. Nine evenly spaced samples of the published table (matplotlib
 * `_cm_listed._viridis_data` at 0, 1/8, ..., 1), sRGB-encoded; between them the scale is linear in
 * sRGB, as a CSS linear-gradient is, so the page's legend and the image agree.
 */
export const COLOR_SCALE_STOPS: readonly string[] = Object.freeze(['#440154', '#482878', '#3e4989', '#31688e', '#26828e', '#1f9e89', '#35b779', '#6ece58', '#fde725']);

/** A stop as sRGB-encoded [r, g, b] in [0, 1]. */
export function stopRgb(hex: string): [number, number, number] {
  const n = Number.parseInt(hex.slice(1), 16);
  return [((n >> 16) & 255) / 255, ((n >> 8) & 255) / 255, (n & 255) / 255];
}

/** The colour scale at t in [0, 1] (clamped), sRGB-encoded: what debug-compose.wgsl computes. */
export function colorScale(t: number): [number, number, number] {
  const x = Math.min(Math.max(t, 0), 1) * (COLOR_SCALE_STOPS.length - 1);
  const i = Math.min(Math.floor(x), COLOR_SCALE_STOPS.length - 2);
  const a = stopRgb(COLOR_SCALE_STOPS[i]!), b = stopRgb(COLOR_SCALE_STOPS[i + 1]!);
  const f = x - i;
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

/** The scale as a CSS gradient, left (min) to right (max): `element.style.background = legendGradientCss()`. */
export function legendGradientCss(direction = 'to right'): string {
  const last = COLOR_SCALE_STOPS.length - 1;
  return `linear-gradient(${direction}, ${COLOR_SCALE_STOPS.map((c, i) => `${c} ${((100 * i) / last).toFixed(1)}%`).join(', ')})`;
}
