/**
 * How the page writes its measurements: with significant figures that fit the magnitude, so that a
 * software GPU's 0.05 frames per second reads "0.05 fps" (not "0.0 fps") and 20,000 rays per second
 * reads "20 k rays/s" (not "0.0 M"). Pure: no DOM, so that unit tests hold every case.
 */

/**
 * `value` with `digits` significant figures, in plain decimal notation (never exponent notation),
 * without trailing zeros after the point: 0.0512 → "0.0512", 20.06 → "20.1", 1234 → "1234"
 * (integer digits are never rounded away: 1234 stays 1234, not "1.23e+3").
 */
export function significant(value: number, digits = 3): string {
  if (!Number.isFinite(value)) return String(value);
  if (value === 0) return '0';
  const magnitude = Math.floor(Math.log10(Math.abs(value)));
  const decimals = Math.max(0, digits - 1 - magnitude);
  // toFixed rounds 9.996 to "10.00" with 2 decimals: a carry into a new digit keeps one decimal too many, trimmed below.
  const text = value.toFixed(Math.min(decimals, 20));
  return text.includes('.') ? text.replace(/\.?0+$/, '') : text;
}

const PREFIXES = [
  { factor: 1e12, prefix: 'T' },
  { factor: 1e9, prefix: 'G' },
  { factor: 1e6, prefix: 'M' },
  { factor: 1e3, prefix: 'k' },
] as const;

/**
 * A quantity with an SI prefix and three significant figures, then its unit: (20000, 'rays/s') →
 * "20 k rays/s", (1.234e6, 'rays/s') → "1.23 M rays/s", (999, 'rays/s') → "999 rays/s", (0.5, 'rays/s') → "0.5 rays/s".
 */
export function withUnit(value: number, unit: string): string {
  const a = Math.abs(value);
  for (const { factor, prefix } of PREFIXES) {
    // 999,960 would round to "1000 k" at three figures: it is written "1 M" instead.
    if (a >= factor * 0.9995) return `${significant(value / factor)} ${prefix} ${unit}`;
  }
  return `${significant(value)} ${unit}`;
}

/** A duration given in milliseconds: "0.42 ms", "16.7 ms", "850 ms", "20.1 s", "2.5 min", "1.2 h". */
export function duration(ms: number): string {
  if (!Number.isFinite(ms)) return '–';
  if (ms < 1000) return `${significant(ms)} ms`;
  const s = ms / 1000;
  if (s < 120) return `${significant(s)} s`;
  const min = s / 60;
  if (min < 120) return `${significant(min, 2)} min`;
  return `${significant(min / 60, 2)} h`;
}

/**
 * A frame rate as the status line writes it: "60 fps" and "12.5 fps" at interactive rates; below one
 * frame a second, also the time a frame takes, which is what a user waits for: "0.05 fps (20 s a frame)".
 * No frame timed yet (0): "–".
 */
export function frameRate(fps: number): string {
  if (!(fps > 0) || !Number.isFinite(fps)) return '– fps';
  if (fps >= 1) return `${significant(fps)} fps`;
  return `${significant(fps, 2)} fps (${duration(1000 / fps)} a frame)`;
}
