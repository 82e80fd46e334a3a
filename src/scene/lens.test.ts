import { describe, expect, it } from 'vitest';
import { apertureRadiusForFNumber, blurDiameterPixels, fNumberForAperture, focalLengthForFov, lensProblem } from './lens.ts';
import { expectLanternError } from '../expect-lantern-error.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import type { Camera } from './types.ts';
import { validateScene } from './validate.ts';

const camera: Camera = { position: [0, 0, 0], forward: [0, 0, 1], up: [0, 1, 0], vfovDegrees: 60 };

describe('thin lens arithmetic', () => {
  it('accepts a closed or open aperture and a positive focus distance, and names what is wrong otherwise', () => {
    expect(lensProblem({ apertureRadius: 0, focusDistance: 1 })).toBeUndefined();
    expect(lensProblem({ apertureRadius: 0.3, focusDistance: 1e-3 })).toBeUndefined();
    expect(lensProblem({ apertureRadius: -0.1, focusDistance: 1 })).toMatch(/aperture radius -0.1/);
    expect(lensProblem({ apertureRadius: Number.NaN, focusDistance: 1 })).toMatch(/aperture radius NaN/);
    expect(lensProblem({ apertureRadius: 0.1, focusDistance: 0 })).toMatch(/focus distance 0/);
    expect(lensProblem({ apertureRadius: 0.1, focusDistance: Infinity })).toMatch(/focus distance Infinity/);
  });

  it('is checked with the scene: a bad lens makes the scene invalid', () => {
    const cornell = builtinScene('cornell');
    validateScene({ ...cornell, camera: { ...cornell.camera, lens: { apertureRadius: 10, focusDistance: 800 } } });
    expectLanternError(() => validateScene({ ...cornell, camera: { ...cornell.camera, lens: { apertureRadius: 10, focusDistance: -1 } } }), /scene 'cornell' is invalid: the lens focus distance -1/);
  });

  it('gives the full-frame focal length of a field of view and the pupil of an f-number', () => {
    // 90° vertically: a focal length of half the sensor height, 12 mm.
    expect(focalLengthForFov(90)).toBeCloseTo(12, 12);
    expect(focalLengthForFov((2 * Math.atan(12 / 35) * 180) / Math.PI)).toBeCloseTo(35, 10);
    // 35 mm at f/1.4 in a scene of centimetres: pupil 25 mm, radius 1.25 cm.
    expect(apertureRadiusForFNumber(1.4, 0.01, 60, 35)).toBeCloseTo(1.25, 12);
    expect(fNumberForAperture(1.25, 0.01, 60, 35)).toBeCloseTo(1.4, 12);
    expect(fNumberForAperture(apertureRadiusForFNumber(5.6, 0.001, 39.3), 0.001, 39.3)).toBeCloseTo(5.6, 12);
  });

  it('spreads a point by 2A·|d − F|/d on the plane of focus, in pixels of that plane', () => {
    const lensed = { ...camera, lens: { apertureRadius: 0.5, focusDistance: 4 } };
    const pixel = (2 * 4 * Math.tan(Math.PI / 6)) / 100;
    expect(blurDiameterPixels(lensed, 4, 100)).toBe(0);
    expect(blurDiameterPixels(lensed, 8, 100)).toBeCloseTo(0.5 / pixel, 10);
    expect(blurDiameterPixels(lensed, 2, 100)).toBeCloseTo(1 / pixel, 10);
    // Far away the blur tends to the aperture's own diameter on the plane of focus.
    expect(blurDiameterPixels(lensed, 1e12, 100)).toBeCloseTo(1 / pixel, 6);
    expect(blurDiameterPixels(camera, 8, 100)).toBe(0);
  });
});
