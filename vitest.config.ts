import { defineConfig } from 'vitest/config';

// Three projects, one `npm test`, run one after another (sequence.groupOrder):
// - unit: pure TypeScript beside the code it tests (src/**/*.test.ts, scripts/), no GPU, the fuzz suite (tests/fuzz)
//         and the layering check
//         over src/ (tests/architecture). Two files at a time: they are single-threaded CPU work. In
//         two worker threads that keep their modules from file to file (isolate: false; no unit test
//         mocks a module or a global): 59 s, where a fresh process and module graph per file took 86 s.
// - gpu:  WebGPU through Dawn on SwiftShader (tests/gpu), one file at a time: SwiftShader's threads
//         already use every core. Not isolated: every file runs in one process, so they share one device
//         (tests/gpu/gpu-context.ts), on which a pipeline already compiled by an earlier file costs
//         nothing again; compiling WGSL on SwiftShader is most of many tests.
// - e2e:  the built page in headless Chromium (tests/e2e) and the built CLI as a user runs it
//         (tests/cli), two files at a time: their renders are tiny, and most of their time is shader
//         compiles, one thread each (a page's in Chromium's GPU process, a CLI run's in its own). The
//         page and the CLI are built once for all of them (tests/e2e/global-setup.ts).
export default defineConfig({
  test: {
    projects: [
      {
        extends: true,
        test: { name: 'unit', include: ['src/**/*.test.ts', 'scripts/**/*.test.ts', 'tests/architecture/**/*.test.ts', 'tests/fuzz/**/*.test.ts'], testTimeout: 60_000, maxWorkers: 2, pool: 'threads', isolate: false },
      },
      {
        extends: true,
        test: {
          name: 'gpu',
          include: ['tests/gpu/**/*.test.ts'],
          fileParallelism: false,
          isolate: false,
          sequence: { groupOrder: 1 },
          testTimeout: 300_000,
          hookTimeout: 120_000,
        },
      },
      {
        extends: true,
        test: {
          name: 'e2e',
          include: ['tests/e2e/**/*.test.ts', 'tests/cli/**/*.test.ts'],
          maxWorkers: 2,
          sequence: { groupOrder: 2 },
          globalSetup: ['tests/e2e/global-setup.ts'],
          testTimeout: 300_000,
          hookTimeout: 180_000,
        },
      },
    ],
  },
});
