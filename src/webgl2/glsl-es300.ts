/**
 * What naga's GLSL needs before a WebGL2 (GLSL ES 3.00) compiler takes it: naga writes some
 * built-ins that ES 3.00 lacks (they came in ES 3.10): bitfieldReverse, findLSB, findMSB and
 * bitCount for WGSL's reverseBits, firstTrailingBit, firstLeadingBit and countOneBits, and mix()
 * with a boolean selector on integer and boolean vectors for WGSL's select(). ES 3.00 lets a shader
 * declare functions of those names (they are not built-ins there) and overload mix, so each missing
 * one is defined after the precision statements, only where the text calls it. Applied at build
 * time to every translated stage (scripts/glsl-translation.ts); pure.
 */

const BITS: Readonly<Record<string, string>> = {
  bitfieldReverse: `uint bitfieldReverse(uint x) {
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
    x = ((x >> 8u) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8u);
    return (x >> 16u) | (x << 16u);
}
int bitfieldReverse(int x) { return int(bitfieldReverse(uint(x))); }`,
  // The lowest set bit isolated is a power of two, which a float holds exactly.
  findLSB: `int findLSB(uint x) { return x == 0u ? -1 : int(round(log2(float(x & (~x + 1u))))); }
int findLSB(int x) { return findLSB(uint(x)); }`,
  findMSB: `int findMSB(uint x) {
    if (x == 0u) return -1;
    int n = 0;
    if (x >= 0x10000u) { x >>= 16u; n += 16; }
    if (x >= 0x100u) { x >>= 8u; n += 8; }
    if (x >= 0x10u) { x >>= 4u; n += 4; }
    if (x >= 0x4u) { x >>= 2u; n += 2; }
    if (x >= 0x2u) { n += 1; }
    return n;
}
int findMSB(int x) { return x < 0 ? findMSB(uint(~x)) : findMSB(uint(x)); }`,
  bitCount: `int bitCount(uint x) {
    x = x - ((x >> 1u) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2u) & 0x33333333u);
    x = (x + (x >> 4u)) & 0x0f0f0f0fu;
    return int((x * 0x01010101u) >> 24u);
}
int bitCount(int x) { return bitCount(uint(x)); }`,
};

/** mix(a, b, selector) for the integer and boolean types ES 3.00's mix lacks: b where the selector is true. */
function mixOverloads(): string {
  const lines: string[] = [];
  for (const [scalar, prefix] of [['int', 'i'], ['uint', 'u'], ['bool', 'b']] as const) {
    lines.push(`${scalar} mix(${scalar} a, ${scalar} b, bool c) { return c ? b : a; }`);
    for (const n of [2, 3, 4]) {
      const t = `${prefix}vec${n}`;
      const parts = ['x', 'y', 'z', 'w'].slice(0, n).map((k) => `c.${k} ? b.${k} : a.${k}`);
      lines.push(`${t} mix(${t} a, ${t} b, bvec${n} c) { return ${t}(${parts.join(', ')}); }`);
    }
  }
  return lines.join('\n');
}

const PRECISION = 'precision highp int;\n';

/** `glsl` (naga's output, `#version 300 es`) with the missing built-ins defined after its precision statements. */
export function esslFixups(glsl: string): string {
  const needed: string[] = [];
  for (const [name, code] of Object.entries(BITS)) if (new RegExp(`\\b${name}\\(`).test(glsl)) needed.push(code);
  // Only mix calls with a bvec or bool selector need the overloads; defining them all is harmless.
  if (/\bmix\(/.test(glsl)) needed.push(mixOverloads());
  if (needed.length === 0) return glsl;
  const at = glsl.indexOf(PRECISION);
  if (at < 0) throw new Error('GLSL fix-ups: naga\'s output has no "precision highp int;" line to insert after');
  const end = at + PRECISION.length;
  return `${glsl.slice(0, end)}\n// ES 3.10 built-ins naga uses, defined for ES 3.00 (src/webgl2/glsl-es300.ts).\n${needed.join('\n')}\n${glsl.slice(end)}`;
}
