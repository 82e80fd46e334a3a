/**
 * The e2e project's global setup: the page and the CLI bundle are built once for every e2e and CLI
 * test file (each used to build its own: a page build per browser test file, a CLI build per CLI
 * test file), and removed at the end. Test files read the paths with `inject('lanternPage')` and
 * `inject('lanternCli')`.
 */
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { build } from 'vite';
import type { TestProject } from 'vitest/node';

declare module 'vitest' {
  export interface ProvidedContext {
    /** The production page, built into a temporary folder. */
    lanternPage: string;
    /** The built `lantern` command (lantern.mjs), inside node_modules/.cache so that it resolves `webgpu` as an installed CLI does. */
    lanternCli: string;
  }
}

export default async function setup(project: TestProject): Promise<() => void> {
  const pageDir = mkdtempSync(join(tmpdir(), 'lantern-page-'));
  mkdirSync(join('node_modules', '.cache'), { recursive: true });
  const cliDir = mkdtempSync(join('node_modules', '.cache', 'lantern-cli-test-'));
  const cleanUp = () => {
    rmSync(pageDir, { recursive: true, force: true });
    rmSync(cliDir, { recursive: true, force: true });
  };
  try {
    await build({ logLevel: 'warn', build: { outDir: pageDir, emptyOutDir: true } });
    await build({ configFile: 'vite.cli.config.ts', logLevel: 'error', build: { outDir: cliDir, sourcemap: false } });
  } catch (e) {
    cleanUp();
    throw e;
  }
  project.provide('lanternPage', pageDir);
  project.provide('lanternCli', join(cliDir, 'lantern.mjs'));
  return cleanUp;
}
