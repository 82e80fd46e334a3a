import { defineConfig } from 'vitest/config';

// Three projects, one `npm test`:
// - unit: pure TypeScript beside the code it tests (src/**/*.test.ts), no GPU, and the layering check
//         over src/ (tests/architecture).
// - gpu:  WebGPU through Dawn on SwiftShader (tests/gpu), one file at a time: SwiftShader already
//         uses every core, so running GPU files in parallel only makes each one slower.
// - e2e:  the built page in headless Chromium (tests/e2e) and the built CLI as a user runs it (tests/cli).
export default defineConfig({
  test: {
    projects: [
      {
        extends: true,
        test: { name: 'unit', include: ['src/**/*.test.ts', 'tests/architecture/**/*.test.ts'], testTimeout: 60_000 },
      },
      {
        extends: true,
        test: {
          name: 'gpu',
          include: ['tests/gpu/**/*.test.ts'],
          fileParallelism: false,
          testTimeout: 300_000,
          hookTimeout: 120_000,
        },
      },
      {
        extends: true,
        test: {
          name: 'e2e',
          include: ['tests/e2e/**/*.test.ts', 'tests/cli/**/*.test.ts'],
          fileParallelism: false,
          testTimeout: 300_000,
          hookTimeout: 180_000,
        },
      },
    ],
  },
});
