/**
 * The lens half of the page's URL contract, below both front ends: `lantern view` writes it and the
 * page reads and writes it (app/view-params.ts). `aperture=<radius>` (≥ 0) and `focus=<distance>`
 * (> 0), scene units, six significant digits (lens sizes span millimetre and metre scenes). Pure.
 */

export const LENS_LINK = { aperture: 'aperture', focus: 'focus' } as const;

export interface LinkedLens {
  readonly apertureRadius?: number;
  readonly focusDistance?: number;
}

const text = (v: number) => String(Number(v.toPrecision(6)));

export function formatLensLink(lens: LinkedLens, params: URLSearchParams): void {
  if (lens.apertureRadius !== undefined) params.set(LENS_LINK.aperture, text(lens.apertureRadius));
  if (lens.focusDistance !== undefined) params.set(LENS_LINK.focus, text(lens.focusDistance));
}

/** The lens a link gives (only what it names); what is malformed or out of range goes to `problems`. */
export function parseLensLink(params: URLSearchParams, problems: string[]): LinkedLens {
  const read = (name: string, allowZero: boolean): number | undefined => {
    const raw = params.get(name);
    if (raw === null) return undefined;
    const v = Number(raw);
    if (raw.trim() === '' || !Number.isFinite(v)) problems.push(`${name}=${raw} is not 1 number`);
    else if (allowZero ? v >= 0 : v > 0) return v;
    else problems.push(`${name}=${v} is not ${allowZero ? '≥' : '>'} 0`);
    return undefined;
  };
  const apertureRadius = read(LENS_LINK.aperture, true);
  const focusDistance = read(LENS_LINK.focus, false);
  return { ...(apertureRadius !== undefined ? { apertureRadius } : {}), ...(focusDistance !== undefined ? { focusDistance } : {}) };
}
