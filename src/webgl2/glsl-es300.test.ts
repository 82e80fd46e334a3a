import { describe, expect, it } from 'vitest';
import { esslFixups } from './glsl-es300.ts';

const HEAD = '#version 300 es\n\nprecision highp float;\nprecision highp int;\n';

describe('GLSL ES 3.00 fix-ups of naga output', () => {
  it('leaves a program that calls none of the missing built-ins as it is', () => {
    const glsl = `${HEAD}out vec4 o;\nvoid main() { o = vec4(1.0); }\n`;
    expect(esslFixups(glsl)).toBe(glsl);
  });

  it('defines only what is called, after the precision statements', () => {
    const out = esslFixups(`${HEAD}uint f(uint x) { return uint(bitCount(x)) + bitfieldReverse(x); }\n`);
    expect(out.indexOf('int bitCount(uint x)')).toBeGreaterThan(out.indexOf('precision highp int;'));
    expect(out).toMatch(/uint bitfieldReverse\(uint x\)/);
    expect(out).not.toMatch(/findLSB|findMSB|ivec3 mix/);
    expect(out.endsWith('uint f(uint x) { return uint(bitCount(x)) + bitfieldReverse(x); }\n')).toBe(true);
  });

  it('overloads mix with a bvec selector for integer and boolean vectors', () => {
    const out = esslFixups(`${HEAD}ivec3 f(ivec3 a, bvec3 c) { return mix(a, -a, c); }\n`);
    expect(out).toContain('ivec3 mix(ivec3 a, ivec3 b, bvec3 c) { return ivec3(c.x ? b.x : a.x, c.y ? b.y : a.y, c.z ? b.z : a.z); }');
    expect(out).toContain('uvec4 mix(uvec4 a, uvec4 b, bvec4 c)');
  });

  // The polyfills' arithmetic, run here as JavaScript over the same steps.
  it('computes what the ES 3.10 built-ins compute (checked over sample words)', () => {
    const reverse = (x: number) => {
      x = (((x >>> 1) & 0x55555555) | ((x & 0x55555555) << 1)) >>> 0;
      x = (((x >>> 2) & 0x33333333) | ((x & 0x33333333) << 2)) >>> 0;
      x = (((x >>> 4) & 0x0f0f0f0f) | ((x & 0x0f0f0f0f) << 4)) >>> 0;
      x = (((x >>> 8) & 0x00ff00ff) | ((x & 0x00ff00ff) << 8)) >>> 0;
      return ((x >>> 16) | (x << 16)) >>> 0;
    };
    const count = (x: number) => {
      x = (x - ((x >>> 1) & 0x55555555)) >>> 0;
      x = ((x & 0x33333333) + ((x >>> 2) & 0x33333333)) >>> 0;
      x = ((x + (x >>> 4)) & 0x0f0f0f0f) >>> 0;
      return Math.imul(x, 0x01010101) >>> 24;
    };
    const lsb = (x: number) => (x === 0 ? -1 : Math.round(Math.log2((x & (~x + 1)) >>> 0)));
    for (const x of [0, 1, 2, 3, 0x80000000, 0xffffffff, 0x12345678, 0xdeadbeef]) {
      const bits = x.toString(2).padStart(32, '0');
      expect(reverse(x)).toBe(parseInt([...bits].reverse().join(''), 2));
      expect(count(x)).toBe([...bits].filter((b) => b === '1').length);
      expect(lsb(x)).toBe(x === 0 ? -1 : 31 - bits.lastIndexOf('1'));
    }
  });
});
