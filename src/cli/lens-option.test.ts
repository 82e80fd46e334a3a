import { Command } from 'commander';
import { describe, expect, it } from 'vitest';
import { expectLanternError } from '../expect-lantern-error.ts';
import { intersectAll } from '../bvh/traverse.ts';
import { builtinScene } from '../loaders/builtin/index.ts';
import { centreFocusDistance } from '../renderer/focus.ts';
import { prepareScene } from '../renderer/prepare.ts';
import { focalLengthForFov } from '../scene/lens.ts';
import type { Camera } from '../scene/types.ts';
import { cameraFromOptions } from './camera-option.ts';
import { cameraWithLens, withLensOptions, type LensOptions } from './lens-option.ts';

/** Parses lens flags the way `lantern render` does. */
function optionsOf(args: string[]): LensOptions {
  const command = withLensOptions(new Command().exitOverride().configureOutput({ writeErr: () => {} }));
  command.parse(args, { from: 'user' });
  return command.opts();
}

const camera: Camera = { position: [0, 0, 0], forward: [0, 0, 2], up: [0, 1, 0], vfovDegrees: 40 };
const metres = { name: 'metres', metersPerUnit: 1 };
const noCentre = () => undefined;

describe('lens options', () => {
  it('reads the flags and refuses bad values with the option named', () => {
    expect(optionsOf(['--aperture', '0.5', '--focus-distance', '3'])).toEqual({ aperture: 0.5, focusDistance: 3 });
    expect(optionsOf(['--f-number', '2.8', '--focal-length', '50'])).toEqual({ fNumber: 2.8, focalLength: 50 });
    expect(() => optionsOf(['--aperture', '-1'])).toThrow(/--aperture must be a number ≥ 0/);
    expect(() => optionsOf(['--focus-distance', '0'])).toThrow(/--focus-distance must be a number > 0/);
    expect(() => optionsOf(['--f-number', '0'])).toThrow(/--f-number must be a number > 0/);
    expect(() => optionsOf(['--focal-length', 'wide'])).toThrow(/--focal-length must be a number > 0/);
  });

  it('turns an f-number into an aperture radius: f/(2N) millimetres in scene units', () => {
    // 50 mm at f/2: a 25 mm pupil, radius 12.5 mm = 0.0125 m.
    const lens = cameraWithLens(camera, { fNumber: 2, focalLength: 50, focusDistance: 3 }, { scene: metres, centreDistance: noCentre }).lens!;
    expect(lens.apertureRadius).toBeCloseTo(0.0125, 12);
    expect(lens.focusDistance).toBe(3);
    // The same lens in a millimetre scene (the Cornell box's unit): 12.5 units.
    const mm = cameraWithLens(camera, { fNumber: 2, focalLength: 50, focusDistance: 3 }, { scene: { name: 'mm', metersPerUnit: 0.001 }, centreDistance: noCentre }).lens!;
    expect(mm.apertureRadius).toBeCloseTo(12.5, 9);
  });

  it('derives the focal length from the field of view on a 24 mm-high sensor when none is given', () => {
    // A vertical field of view of 2·atan(12/50) is exactly a 50 mm lens on full frame.
    const fov = (2 * Math.atan(12 / 50) * 180) / Math.PI;
    expect(focalLengthForFov(fov)).toBeCloseTo(50, 10);
    const lens = cameraWithLens({ ...camera, vfovDegrees: fov }, { fNumber: 4, focusDistance: 1 }, { scene: metres, centreDistance: noCentre }).lens!;
    expect(lens.apertureRadius).toBeCloseTo(0.05 / 4 / 2, 12);
    // A wider view is a shorter lens: the same f-number opens less.
    const wide = cameraWithLens({ ...camera, vfovDegrees: 90 }, { fNumber: 4, focusDistance: 1 }, { scene: metres, centreDistance: noCentre }).lens!;
    expect(wide.apertureRadius).toBeCloseTo(0.012 / 4 / 2, 12);
  });

  it('focuses on the --camera target, else at the scene lens, else at the image centre, else refuses', () => {
    const look = [1, 2, 3, 4, 6, 3];
    const moved = cameraFromOptions(camera, look);
    const target = [4, 6, 3] as const;
    expect(cameraWithLens(moved, { aperture: 0.1 }, { scene: metres, target, centreDistance: () => 99 }).lens).toEqual({ apertureRadius: 0.1, focusDistance: 5 });
    const lensed = { ...camera, lens: { apertureRadius: 0.2, focusDistance: 7 } };
    expect(cameraWithLens(lensed, { aperture: 0.1 }, { scene: metres, centreDistance: () => 99 }).lens).toEqual({ apertureRadius: 0.1, focusDistance: 7 });
    expect(cameraWithLens(camera, { aperture: 0.1 }, { scene: metres, centreDistance: () => 99 }).lens).toEqual({ apertureRadius: 0.1, focusDistance: 99 });
    expectLanternError(() => cameraWithLens(camera, { aperture: 0.1 }, { scene: metres, centreDistance: noCentre }), /nothing to focus on/);
  });

  it('finds the depth at the image centre with the CPU BVH, as brute force over every triangle does', () => {
    const prepared = prepareScene(builtinScene('cornell'));
    const c = prepared.scene.camera;
    const depth = centreFocusDistance(prepared, c)!;
    const brute = intersectAll(prepared.triangles.positions, { origin: c.position, direction: [0, 0, 1] })!;
    expect(depth).toBeCloseTo(brute.t, 9);
    // Inside the box, 800 units in front of the opening at z = 0.
    expect(depth).toBeGreaterThan(800);
    expect(centreFocusDistance(prepared, { ...c, forward: [0, 0, -1] })).toBeUndefined();
  });

  it('keeps the camera without lens options, refocuses with --focus-distance alone, and makes a pinhole with --aperture 0', () => {
    expect(cameraWithLens(camera, {}, { scene: metres, centreDistance: noCentre })).toBe(camera);
    const lensed = { ...camera, lens: { apertureRadius: 0.2, focusDistance: 7 } };
    expect(cameraWithLens(lensed, { focusDistance: 2 }, { scene: metres, centreDistance: noCentre }).lens).toEqual({ apertureRadius: 0.2, focusDistance: 2 });
    expect(cameraWithLens(lensed, { aperture: 0 }, { scene: metres, centreDistance: noCentre }).lens).toBeUndefined();
  });

  it('refuses contradictory or incomplete lens options', () => {
    const context = { scene: metres, centreDistance: noCentre };
    expectLanternError(() => cameraWithLens(camera, { aperture: 0.1, fNumber: 2 }, context), /--aperture and --f-number both/);
    expectLanternError(() => cameraWithLens(camera, { aperture: 0.1, focalLength: 50 }, context), /--focal-length sets the aperture only with --f-number/);
    expectLanternError(() => cameraWithLens(camera, { focusDistance: 3 }, context), /--focus-distance needs a lens/);
    expectLanternError(() => cameraWithLens(camera, { fNumber: 2, focusDistance: 3 }, { scene: { name: 'bare' }, centreDistance: noCentre }), /'bare' does not say how large its unit is/);
  });
});
