/**
 * What a glTF load had to work around, each said once: a model with forty materials that all name
 * the same missing texture should produce one line for the user, not forty.
 */
import { SIBLING_RULE } from '../sibling-uri.ts';

export class Warnings {
  private readonly seen = new Set<string>();
  private readonly refusals = new Map<string, string>();
  readonly list: string[] = [];

  add(message: string): void {
    if (this.seen.has(message)) return;
    this.seen.add(message);
    this.list.push(message);
  }

  /** A file the model names but that is not read (sibling-uri.ts says why): `missingFile` then gives the reason. */
  refuse(uri: string, reason: string): void {
    this.refusals.set(uri, reason);
  }

  /** Why a URI was not read, if it was refused rather than missing. */
  refusal(uri: string): string | undefined {
    return this.refusals.get(uri);
  }

  /** A file the model names but the resolver could not supply: one warning per file, whatever uses it. */
  missingFile(uri: string, consequence: string): void {
    const key = `missing:${uri}`;
    if (this.seen.has(key)) return;
    this.seen.add(key);
    const refused = this.refusals.get(uri);
    this.list.push(refused ? `${uri} is not read (${refused}; ${SIBLING_RULE}): ${consequence}` : `${uri} is missing: ${consequence}`);
  }
}
