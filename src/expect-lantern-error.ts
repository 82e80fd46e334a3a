/** Test helper: asserts that `fn` throws a LanternError whose message matches `pattern`, and returns it. */
import { expect } from 'vitest';
import { LanternError } from './errors.ts';

export function expectLanternError(fn: () => unknown, pattern?: RegExp): LanternError {
  let thrown: unknown;
  try {
    fn();
  } catch (e) {
    thrown = e;
  }
  expect(thrown).toBeInstanceOf(LanternError);
  if (pattern) expect((thrown as Error).message).toMatch(pattern);
  return thrown as LanternError;
}
