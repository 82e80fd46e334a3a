/**
 * Values for testing every setting of the schema by its type and range alone, so that a setting
 * added to the table is tested by the round-trip and refusal tests without writing a test for it.
 * Used by tests only.
 */
import type { SettingSpec } from './settings-schema.ts';

const nearMin = (spec: { min: number; above?: boolean }, whole: boolean) => (spec.above ? spec.min + (whole ? 1 : 0.25) : spec.min);
const finiteMax = (max: number, min: number) => (Number.isFinite(max) ? max : Math.max(min, 0) + 1e6);

/** Valid values: the bounds, something between, every choice and word. */
export function validValues(spec: SettingSpec): unknown[] {
  switch (spec.type) {
    case 'integer':
    case 'integer-or-unlimited': {
      const lo = nearMin(spec, true);
      const hi = finiteMax(spec.max, spec.min);
      const values = [lo, hi, Math.floor((lo + hi) / 2)];
      return spec.type === 'integer' ? values : [...values, 'unlimited'];
    }
    case 'number':
    case 'number-or-auto': {
      const lo = nearMin(spec, false);
      const hi = finiteMax(spec.max, spec.min);
      const values = [lo, hi, lo + (hi - lo) * 0.375];
      return spec.type === 'number' ? values : [...values, 'auto'];
    }
    case 'color': {
      const lo = nearMin(spec, false);
      const hi = finiteMax(spec.max, spec.min);
      return [[lo, hi, lo + (hi - lo) / 2], [hi, hi, hi]];
    }
    case 'boolean':
      return [false, true];
    case 'choice':
      return [...spec.values];
    case 'numbers': {
      const lows = spec.components.map((c) => nearMin(c, false));
      const highs = spec.components.map((c) => finiteMax(c.max, c.min));
      return [lows, highs, highs.slice(0, spec.required)];
    }
    case 'text':
      return [String(spec.default ?? 'value'), 'a file name with spaces.hdr'].filter((t) => !spec.pattern || spec.pattern.test(t));
  }
}

/** Values of the right type outside the range (what validation, the CLI and links must all refuse). */
export function outOfRangeValues(spec: SettingSpec): unknown[] {
  switch (spec.type) {
    case 'integer':
    case 'integer-or-unlimited':
      return [spec.above ? spec.min : spec.min - 1, ...(Number.isFinite(spec.max) ? [spec.max + 1] : []), nearMin(spec, true) + 0.5];
    case 'number':
    case 'number-or-auto':
      return [spec.above ? spec.min : spec.min - 0.5, ...(Number.isFinite(spec.max) ? [spec.max * 1.5 + 1] : [])];
    case 'color':
      return [[spec.above ? spec.min : spec.min - 0.5, 0.5, 0.5], ...(Number.isFinite(spec.max) ? [[0.5, spec.max + 1, 0.5]] : [])];
    case 'numbers': {
      const mid = spec.components.map((c) => nearMin(c, false));
      // Each component below its range, then above it where it has a top.
      return spec.components.flatMap((c, i) => [
        mid.map((v, j) => (j === i ? (c.above ? c.min : c.min - 1) : v)),
        ...(Number.isFinite(c.max) ? [mid.map((v, j) => (j === i ? c.max + 1 : v))] : []),
      ]);
    }
    case 'boolean':
    case 'choice':
    case 'text':
      return [];
  }
}

/** Text that is no value of the setting at all. */
export function malformedTexts(spec: SettingSpec): string[] {
  switch (spec.type) {
    case 'integer':
    case 'number':
      return ['', 'abc', '1,2', '0x10', 'Infinity'];
    case 'number-or-auto':
    case 'integer-or-unlimited':
      return ['', 'abc', 'Auto!', 'NaN'];
    case 'color':
      return ['', '1,1', '1,1,1,1', 'a,b,c', '0.5,,0.5'];
    case 'boolean':
      return ['maybe', '2', ''];
    case 'choice':
      return ['no-such-value', '', spec.values[0]!.toUpperCase() + '!'];
    case 'numbers':
      return ['', 'a', Array(spec.required).fill('1').join(',').replace(/1$/, ''), Array(spec.components.length + 1).fill('0').join(',')];
    case 'text':
      return ['', '  '];
  }
}
