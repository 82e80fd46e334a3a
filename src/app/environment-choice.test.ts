import { describe, expect, it } from 'vitest';
import { IDENTITY } from '../math/mat4.ts';
import { withDefaultLight } from '../scene/default-light.ts';
import type { EnvironmentImage } from '../scene/environment.ts';
import { withEnvironment } from '../scene/environment-override.ts';
import { diffuse } from '../scene/types.ts';
import { choiceOfEnvironment, DEFAULT_ENVIRONMENT_CHOICE, environmentOfChoice, environmentOfLink, lightingNoteOf, linkOfEnvironment } from './environment-choice.ts';
import { formatViewParams, parseViewParams } from './view-params.ts';

const image: EnvironmentImage = { name: 'studio.hdr', width: 2, height: 1, rgb: new Float32Array(6).fill(1) };

describe('environment choice', () => {
  it('gives the scene its own environment, or the sky, map or darkness asked for', () => {
    const base = { ...DEFAULT_ENVIRONMENT_CHOICE, elevation: 20, azimuth: 90, turbidity: 5, skyIntensity: 0.5, mapIntensity: 2, rotation: 30 };
    expect(environmentOfChoice({ ...base, kind: 'scene' }, image)).toBeUndefined();
    expect(environmentOfChoice({ ...base, kind: 'none' }, image)).toEqual({ kind: 'none' });
    expect(environmentOfChoice({ ...base, kind: 'sky' }, undefined)).toMatchObject({ kind: 'sky', sunElevationDeg: 20, sunAzimuthDeg: 90, turbidity: 5, intensity: 0.5 });
    expect(environmentOfChoice({ ...base, kind: 'map' }, image)).toEqual({ kind: 'map', image, rotationDeg: 30, intensity: 2 });
    // A map with no file opened yet changes nothing.
    expect(environmentOfChoice({ ...base, kind: 'map' }, undefined)).toBeUndefined();
  });

  it('reads back what it made, keeping the parameters of the kinds not shown', () => {
    const sky = { ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'sky' as const, elevation: 10, azimuth: -30, turbidity: 2, skyIntensity: 3, rotation: 77 };
    expect(choiceOfEnvironment(environmentOfChoice(sky, undefined), DEFAULT_ENVIRONMENT_CHOICE)).toEqual({ ...sky, rotation: DEFAULT_ENVIRONMENT_CHOICE.rotation });
    const map = { ...sky, kind: 'map' as const, mapIntensity: 4, rotation: -90 };
    expect(choiceOfEnvironment(environmentOfChoice(map, image), sky)).toEqual(map);
    expect(choiceOfEnvironment(undefined, sky).kind).toBe('scene');
  });

  it('carries the sky through a link and back, but not a map', () => {
    const sky = environmentOfChoice({ ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'sky', elevation: 15, azimuth: 200, turbidity: 6, skyIntensity: 0.3 }, undefined);
    const { view } = parseViewParams(formatViewParams(linkOfEnvironment(sky)));
    expect(environmentOfLink(view)).toEqual(sky);
    expect(linkOfEnvironment(environmentOfChoice({ ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'map' }, image))).toEqual({});
    expect(environmentOfLink({ envIntensity: 2 })).toBeUndefined();
  });

  it('overrides the default sky a model got: none leaves it dark, and the page then says nothing of the sky', () => {
    // A model without light: the loader gives it the default sky and a note (scene/default-light.ts).
    const mesh = { name: 'tri', positions: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), indices: new Uint32Array([0, 1, 2]), materialIds: new Uint32Array([0]) };
    const model = withDefaultLight({ name: 'model', meshes: [mesh], instances: [{ id: 0, mesh: 0, worldFromObject: IDENTITY }], materials: [diffuse('white', [0.8, 0.8, 0.8])], camera: { position: [0, 0, 3], forward: [0, 0, -1], up: [0, 1, 0], vfovDegrees: 40 } });
    expect(model.environment?.kind).toBe('sky');
    expect(lightingNoteOf(model, environmentOfChoice({ ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'scene' }, image))).toBe('model: the model has no light of its own; a default sky lights it');
    const none = environmentOfChoice({ ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'none' }, image)!;
    expect(lightingNoteOf(model, none)).toBeUndefined();
    expect(lightingNoteOf(model, environmentOfChoice({ ...DEFAULT_ENVIRONMENT_CHOICE, kind: 'sky' }, undefined))).toBeUndefined();
    // What the viewer shows under the choice (renderer/prepare.ts withPreparedEnvironment): no sky, and the daylight exposure gone with it.
    const dark = withEnvironment(model, none);
    expect(dark.environment).toEqual({ kind: 'none' });
    expect(dark.camera.exposureStops).toBeCloseTo(0, 12);
    expect(lightingNoteOf(dark, undefined)).toBeUndefined();
  });
});
