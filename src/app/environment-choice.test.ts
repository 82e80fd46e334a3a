import { describe, expect, it } from 'vitest';
import type { EnvironmentImage } from '../scene/environment.ts';
import { choiceOfEnvironment, DEFAULT_ENVIRONMENT_CHOICE, environmentOfChoice, environmentOfLink, linkOfEnvironment } from './environment-choice.ts';
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
});
