/**
 * What a glTF load had to work around, each said once: a model with forty materials that all name
 * the same missing texture should produce one line for the user, not forty.
 */
export class Warnings {
  private readonly seen = new Set<string>();
  readonly list: string[] = [];

  add(message: string): void {
    if (this.seen.has(message)) return;
    this.seen.add(message);
    this.list.push(message);
  }

  /** A file the model names but the resolver could not supply: one warning per file, whatever uses it. */
  missingFile(uri: string, consequence: string): void {
    const key = `missing:${uri}`;
    if (this.seen.has(key)) return;
    this.seen.add(key);
    this.list.push(`${uri} is missing: ${consequence}`);
  }
}
