/** data: URIs (RFC 2397), which glTF files use to embed buffers and images in the JSON. */

/** RFC 2397: data:[<mediatype>][;base64],<data>. Undecodable data counts as missing. */
export function decodeDataUri(uri: string): Uint8Array | undefined {
  const comma = uri.indexOf(',');
  if (comma < 0) return undefined;
  const header = uri.slice(5, comma);
  const data = uri.slice(comma + 1);
  try {
    if (header.endsWith(';base64')) {
      const text = atob(data);
      const out = new Uint8Array(text.length);
      for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i);
      return out;
    }
    return new TextEncoder().encode(decodeURIComponent(data));
  } catch {
    return undefined;
  }
}
