/**
 * Runs the built `lantern` command (tests/e2e/global-setup.ts builds it once) as a user runs it, on
 * SwiftShader unless `env` says otherwise (a variable given as undefined is removed), and returns its
 * exit code and both streams whole.
 */
import { spawnSync } from 'node:child_process';
import { inject } from 'vitest';

export const SWIFTSHADER = { VK_ICD_FILENAMES: '/usr/lib/chromium/vk_swiftshader_icd.json' };

export function runLantern(args: readonly string[], env: Record<string, string | undefined> = SWIFTSHADER, timeoutMs = 120_000): { code: number | null; stdout: string; stderr: string; ms: number } {
  const merged: Record<string, string | undefined> = { ...process.env, ...env };
  for (const [key, value] of Object.entries(merged)) if (value === undefined) delete merged[key];
  const t0 = performance.now();
  const r = spawnSync(process.execPath, [inject('lanternCli'), ...args], { encoding: 'utf8', env: merged, timeout: timeoutMs });
  return { code: r.status, stdout: r.stdout, stderr: r.stderr, ms: performance.now() - t0 };
}
