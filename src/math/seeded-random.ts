/**
 * mulberry32 (Tommy Ettinger): a tiny, fast, well-mixed 32-bit PRNG for tests and generated
 * fixtures. The same seed gives the same sequence everywhere, so failures reproduce.
 */
export function seededRandom(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
