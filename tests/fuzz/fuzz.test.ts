/**
 * The fuzz suite's short run, inside the normal tests: a fixed seed, a couple of hundred
 * structure-aware mutations per loader, each case bounded. A case fails when it throws anything
 * but a LanternError, takes more than CASE_SECONDS, or grows the process by more than CASE_GROWTH.
 * The long run (`npm run fuzz -- --minutes N`, scripts/fuzz.ts) uses the same targets in workers,
 * with hangs cut off and reproducers saved.
 */
import { describe, expect, it } from 'vitest';
import { caseSeed, Rng } from './mutate.ts';
import { runInput, TARGETS } from './targets.ts';

const SEED = 17;
const CASES: Readonly<Record<string, number>> = { wad: 200, ply: 300, gltf: 150, exr: 300, hdr: 300, png: 300, wolf3d: 200, molecule: 300 };
const CASE_SECONDS = 3;
const CASE_GROWTH = 512 * 2 ** 20;

describe('fuzz (fixed seed)', () => {
  for (const target of TARGETS.filter((t) => t.count === undefined)) {
    it(`${target.label}: ${CASES[target.id] ?? 100} cases load or are refused cleanly, each bounded`, async () => {
      const problems: string[] = [];
      const outcomes = { ok: 0, clean: 0 };
      for (let i = 0; i < (CASES[target.id] ?? 100); i++) {
        const rng = new Rng(caseSeed(SEED, i));
        const files = target.input(rng, i);
        const rss = process.memoryUsage().rss;
        const start = performance.now();
        const outcome = await runInput(target, files);
        const seconds = (performance.now() - start) / 1000;
        const growth = process.memoryUsage().rss - rss;
        const name = `${target.id} seed ${SEED} case ${i}`;
        if (outcome.kind === 'crash') problems.push(`${name}: ${outcome.message}`);
        else outcomes[outcome.kind]++;
        if (seconds > CASE_SECONDS) problems.push(`${name}: took ${seconds.toFixed(1)} s`);
        if (growth > CASE_GROWTH) problems.push(`${name}: grew the process by ${(growth / 2 ** 20).toFixed(0)} MB`);
      }
      expect(problems).toEqual([]);
      // Mutations that never load anything would test only the first check of each parser.
      expect(outcomes.ok).toBeGreaterThan(0);
      expect(outcomes.clean).toBeGreaterThan(0);
    });
  }
});
