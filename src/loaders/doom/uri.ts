/**
 * Scene URIs for Doom maps: `path/to/iwad.wad#E1M1`, or `iwad.wad+pwad.wad#MAP01` to load PWADs
 * over the IWAD (in that order; later files win). `#map` is optional: without it the caller picks
 * the first map (see WadStack.maps). '+' is reserved as the separator, so a WAD whose path contains
 * '+' cannot be named this way (rename or move it). Pure string work: paths are kept as given.
 */
import { LanternError } from '../../errors.ts';

export interface DoomUri {
  /** The IWAD first, then PWADs in load order. */
  readonly files: readonly string[];
  /** Upper-cased map (marker lump) name, or undefined for "the first map". */
  readonly map?: string;
}

const WAD_EXTENSION = /\.wad$/i;

/** Splits off the `#map` fragment; a '#' inside a path that itself ends in .wad is not one. */
function splitFragment(uri: string): [string, string | undefined] {
  if (WAD_EXTENSION.test(uri)) return [uri, undefined];
  const hash = uri.lastIndexOf('#');
  if (hash < 0) return [uri, undefined];
  return [uri.slice(0, hash), uri.slice(hash + 1)];
}

/** True when the string names a WAD: it ends in .wad (any case), optionally followed by `#map`. */
export function isDoomUri(s: string): boolean {
  return WAD_EXTENSION.test(splitFragment(s)[0]);
}

export function parseDoomUri(uri: string): DoomUri {
  const [path, fragment] = splitFragment(uri);
  const files = path.split('+');
  for (const f of files) {
    if (!WAD_EXTENSION.test(f)) {
      throw new LanternError(
        `'${uri}': '${f}' is not a .wad file`,
        "name WADs as iwad.wad+pwad.wad#MAP01; '+' separates files, so paths must not contain '+'",
      );
    }
  }
  if (fragment === undefined || fragment === '') return { files };
  // Map names are lump names: at most 8 characters, no separators.
  if (fragment.length > 8 || !/^[\x21-\x7e]+$/.test(fragment)) {
    throw new LanternError(`'${uri}': '${fragment}' is not a map name`, 'map names are lump names of up to 8 characters, such as E1M1 or MAP01');
  }
  return { files, map: fragment.toUpperCase() };
}
