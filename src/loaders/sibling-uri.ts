/**
 * What a model may refer to: the one rule for the URIs a glTF (or any format with siblings) names,
 * shared by the loader (which refuses before asking for the file), the CLI's resolver (which reads
 * the file) and `lantern view`'s file set (which serves it). Pure.
 *
 * A model names files in its own folder and below, by relative references: `model.bin`,
 * `textures/wood.png`, `textures/../model.bin`. Refused, each with its reason: a reference that
 * climbs out of the folder (`../../etc/hostname`, also percent-encoded or with backslashes), an
 * absolute path (`/etc/hostname`, `C:\…`, `//server/share`), and any URI with a scheme (`file:`,
 * `http:`, `https:`): a model is a set of files that travel together, and opening one must not
 * read other files of the machine or reach the network. `data:` URIs are the loader's own business
 * (their bytes are in the model) and never reach this rule.
 */

export type SiblingPath = { readonly ok: true; readonly path: string } | { readonly ok: false; readonly reason: string };

/** Where a model may look, for messages. */
export const SIBLING_RULE = "a model may name only files in its own folder and below";

/**
 * The file a relative URI names, as a '/'-separated path relative to the model's folder
 * (percent-escapes decoded, backslashes read as slashes, `.` and empty segments dropped, `a/..`
 * folded), or the reason it is refused.
 */
export function siblingPath(uri: string): SiblingPath {
  if (uri.trim() === '') return { ok: false, reason: 'it is empty' };
  const scheme = /^([a-zA-Z][a-zA-Z0-9+.-]*):/.exec(uri);
  // One letter before the colon is a Windows drive (C:\models\a.bin), not a scheme.
  if (scheme && scheme[1]!.length === 1) return { ok: false, reason: 'it is an absolute path' };
  if (scheme) return { ok: false, reason: `it is a URL (${scheme[1]!.toLowerCase()}:), not a path beside the model` };
  let decoded = uri;
  try {
    decoded = decodeURIComponent(uri);
  } catch {
    // A lone '%' is a literal character of a file name.
  }
  if (decoded.includes('\0')) return { ok: false, reason: 'it holds a NUL character' };
  const slashed = decoded.replace(/\\/g, '/');
  if (slashed.startsWith('/') || /^[a-zA-Z]:/.test(slashed)) return { ok: false, reason: 'it is an absolute path' };
  const out: string[] = [];
  for (const part of slashed.split('/')) {
    if (part === '' || part === '.') continue;
    if (part !== '..') out.push(part);
    else if (out.length > 0) out.pop();
    else return { ok: false, reason: "it leads out of the model's folder" };
  }
  if (out.length === 0) return { ok: false, reason: 'it names the folder, not a file' };
  return { ok: true, path: out.join('/') };
}
