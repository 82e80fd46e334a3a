/** Parsing and checking of numeric command-line options, with messages that name the option. */
import { InvalidArgumentError, type Command } from 'commander';
import { MAX_IMAGE_SIDE } from '../renderer/image.ts';
import { KERNEL_KINDS, type KernelKind } from '../renderer/specialisation-schedule.ts';

export function integerOption(name: string, min: number, max: number): (value: string) => number {
  return (value: string) => {
    const n = Number(value);
    if (!/^[+-]?\d+$/.test(value.trim()) || !Number.isSafeInteger(n)) throw new InvalidArgumentError(`${name} must be a whole number, not '${value}'.`);
    if (n < min || n > max) throw new InvalidArgumentError(`${name} must be from ${min} to ${max}, not ${n}.`);
    return n;
  };
}

export function numberOption(name: string, min: number, max: number): (value: string) => number {
  return (value: string) => {
    const n = Number(value);
    if (value.trim() === '' || !Number.isFinite(n)) throw new InvalidArgumentError(`${name} must be a number, not '${value}'.`);
    if (n < min || n > max) throw new InvalidArgumentError(`${name} must be from ${min} to ${max}, not ${n}.`);
    return n;
  };
}

export function choiceOption<T extends string>(name: string, choices: readonly T[]): (value: string) => T {
  return (value: string) => {
    if (!(choices as readonly string[]).includes(value)) throw new InvalidArgumentError(`${name} must be one of ${choices.join(', ')}, not '${value}'.`);
    return value as T;
  };
}

/** --width and --height, shared by the commands that render (the render settings are in setting-options.ts). */
export function withImageOptions(command: Command, defaults: { width: number; height: number }): Command {
  return command
    .option('-W, --width <pixels>', 'image width', integerOption('--width', 1, MAX_IMAGE_SIDE), defaults.width)
    .option('-H, --height <pixels>', 'image height', integerOption('--height', 1, MAX_IMAGE_SIDE), defaults.height);
}

/**
 * A comma-separated list of exactly `count` finite numbers (e.g. a colour or a point), each at most
 * `limit` in size when given (coordinates: 1e308 is finite, and the sum of two is not).
 */
export function numberListOption(name: string, counts: readonly number[], limit?: number): (value: string) => number[] {
  return (value: string) => {
    const parts = value.split(',').map((p) => p.trim());
    const numbers = parts.map(Number);
    if (!counts.includes(parts.length) || parts.some((p) => p === '') || !numbers.every(Number.isFinite)) {
      throw new InvalidArgumentError(`${name} takes ${counts.join(' or ')} comma-separated numbers, not '${value}'.`);
    }
    const big = limit === undefined ? undefined : numbers.find((n) => Math.abs(n) > limit);
    if (big !== undefined) throw new InvalidArgumentError(`${name} takes numbers from -${limit} to ${limit}, not ${big}.`);
    return numbers;
  };
}

/** A file or folder name: not empty (`--out ''` once meant "the default"), no NUL (no file system takes one). */
export function pathOption(name: string): (value: string) => string {
  return (value: string) => {
    if (value.trim() === '') throw new InvalidArgumentError(`${name} needs a file name, not an empty one.`);
    if (value.includes('\0')) throw new InvalidArgumentError(`${name}: a file name cannot hold a NUL character.`);
    return value;
  };
}

/** --light-table and --skill, for every command that builds a scene. */
export function withSceneOptions(command: Command): Command {
  return command
    .option('--light-table <file.json>', 'Doom maps: JSON overrides of which textures, flats and things emit, and how strongly (see the README)', pathOption('--light-table'))
    .option('--skill <1-5>', "Doom maps: the skill level whose things appear (1: I'm too young to die ... 5: Nightmare!; default 3); Wolfenstein 3D maps: whose guards appear (1-4, 5 counts as 4)", integerOption('--skill', 1, 5));
}

/** The values withSceneOptions parses. */
export interface SceneOptionValues {
  readonly lightTable?: string;
  readonly skill?: number;
}

/** --kernel: the generic tracing kernels, or those specialised to the scene (renderer.ts requestSpecialisation). */
export function withKernelOption(command: Command, defaultKind: KernelKind, help: string): Command {
  return command.option('--kernel <kind>', `${KERNEL_KINDS.join(' | ')}: ${help}`, choiceOption('--kernel', KERNEL_KINDS), defaultKind);
}
