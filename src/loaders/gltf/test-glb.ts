/**
 * A writer of GLB containers for tests and the fuzz suite (as loaders/doom/test-wad.ts writes WADs):
 * glTF 2.0 §4.4, a 12-byte header, the JSON chunk and the BIN chunk, each 4-byte aligned.
 */
/** A GLB container of a JSON chunk (padded with spaces) and a binary chunk (padded with zeros), as the specification lays them out. */
export function glbOf(json: unknown, bin: Uint8Array): Uint8Array {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jsonLength = (text.length + 3) & ~3;
  const binLength = (bin.length + 3) & ~3;
  const out = new Uint8Array(12 + 8 + jsonLength + 8 + binLength);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, out.length, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.fill(0x20, 20, 20 + jsonLength);
  out.set(text, 20);
  view.setUint32(20 + jsonLength, binLength, true);
  view.setUint32(24 + jsonLength, 0x004e4942, true);
  out.set(bin, 28 + jsonLength);
  return out;
}
