import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { builtinSceneNames } from '../loaders/builtin/index.ts';
import { parseSceneArgument } from './scene-source.ts';

function errorOf(arg: string): LanternError {
  try {
    parseSceneArgument(arg);
  } catch (e) {
    if (e instanceof LanternError) return e;
    throw e;
  }
  throw new Error(`'${arg}' was accepted`);
}

describe('an unknown scene argument', () => {
  it('gets one short line that names each built-in scene once and says where the rest is described', () => {
    const line = errorOf('nosuchscene').userMessage;
    expect(line).toMatch(/^unknown scene 'nosuchscene': /);
    expect(line).not.toMatch(/\n/);
    for (const name of builtinSceneNames()) expect(line.split(new RegExp(`\\b${name}\\b`)).length - 1, name).toBe(1);
    expect(line).toMatch(/lantern render --help/);
    // It was 813 characters, the built-ins listed twice among every file format's description.
    expect(line.length).toBeLessThanOrEqual(250);
  });

  it('a name with an extension Lantern does not read says so the same way', () => {
    expect(errorOf('model.obj').userMessage).toMatch(/^unknown scene 'model\.obj': /);
  });
});
