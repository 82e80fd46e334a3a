/**
 * The header's status line, fitted to its width: a line of parts ("12 spp · 5.2 fps · 640×400 ·
 * google swiftshader · budget: …"), each with shorter forms, each with an importance. Where the line
 * is too narrow, the least important part takes its shorter forms and then goes, and the next one
 * after it: the line is never cut mid-figure with "…", and it never wraps (a taller header would
 * resize the canvas and restart the image). The whole reading stays in the tooltip. Pure: the page
 * says what fits (its element's scrollWidth against its clientWidth).
 */

export interface StatusPart {
  /** The part as written, longest first: a narrower line takes a later form. */
  readonly forms: readonly string[];
  /** Higher is kept longer; the most important part is never dropped (it ends at its shortest form). */
  readonly importance: number;
}

export const STATUS_SEPARATOR = ' · ';

/** A part with its forms, leaving out empty ones (a part with no text is no part). */
export function part(importance: number, ...forms: readonly (string | undefined)[]): StatusPart | undefined {
  const written = forms.filter((f): f is string => f !== undefined && f !== '');
  return written.length > 0 ? { forms: written, importance } : undefined;
}

/** The parts joined, each in the form chosen (index into its forms; -1: left out). */
function join(parts: readonly StatusPart[], chosen: readonly number[]): string {
  return parts.flatMap((p, i) => (chosen[i]! >= 0 ? [p.forms[chosen[i]!]!] : [])).join(STATUS_SEPARATOR);
}

/**
 * The longest line of `parts` that `fits`: every part in its first form if that fits; else the parts
 * other than the most important take their shorter forms, least important first (ties: the later
 * part first), then go in the same order; the most important part is shortened last, alone.
 */
export function fitStatus(given: readonly (StatusPart | undefined)[], fits: (text: string) => boolean): string {
  const parts = given.filter((p): p is StatusPart => p !== undefined);
  const chosen = parts.map(() => 0);
  let text = join(parts, chosen);
  if (fits(text)) return text;
  const order = parts.map((_, i) => i).sort((a, b) => parts[a]!.importance - parts[b]!.importance || b - a);
  const first = order.pop();
  if (first === undefined) return text;
  const attempt = (i: number, form: number) => {
    chosen[i] = form;
    text = join(parts, chosen);
    return fits(text);
  };
  const shorten = (i: number) => {
    for (let form = 1; form < parts[i]!.forms.length; form++) if (attempt(i, form)) return true;
    return false;
  };
  for (const i of order) if (shorten(i)) return text;
  for (const i of order) if (attempt(i, -1)) return text;
  shorten(first);
  return text;
}
