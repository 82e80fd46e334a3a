/** `lantern diff a.exr b.exr`: RMSE, relative MSE and SSIM of an image against a reference, and a heat map. */
import type { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { compareImages, errorHeatmap, type LinearRgbImage } from '../../image/compare.ts';
import { decodeExrRgb } from '../../image/exr.ts';
import { encodePng } from '../../image/png.ts';
import type { CliContext } from '../context.ts';
import { numberOption, pathOption } from '../options.ts';
import { checkOutputPath, writeFile } from '../output-files.ts';
import { readUserFile } from '../user-files.ts';

interface DiffOptions {
  heatmap?: string;
  heatmapScale: number;
  json?: boolean;
}

export function registerDiff(program: Command, context: CliContext): void {
  program
    .command('diff')
    .description('compare a linear EXR image with a reference EXR: RMSE, relative MSE, SSIM')
    .argument('<image.exr>', 'the image to judge')
    .argument('<reference.exr>', 'the reference (relative MSE divides by it)')
    .option('--heatmap <file.png>', 'write the per-pixel relative luminance error as a PNG heat map (black 0, red, yellow, white at --heatmap-scale)', pathOption('--heatmap'))
    .option('--heatmap-scale <ratio>', 'relative error shown as white', numberOption('--heatmap-scale', 1e-6, 1e6), 1)
    .option('--json', 'print the figures as JSON')
    .action((a: string, b: string, options: DiffOptions, command: Command) =>
      context.run(async () => {
        // Checked before the images are decoded: a large pair takes a while.
        if (options.heatmap === undefined && command.getOptionValueSource('heatmapScale') === 'cli') throw new LanternError('--heatmap-scale goes with --heatmap');
        if (options.heatmap !== undefined) checkOutputPath('--heatmap', options.heatmap, 'file');
        diff(a, b, options, context);
      }),
    );
}

function readExr(path: string): LinearRgbImage {
  return decodeExrRgb(readUserFile(path), path);
}

function diff(imagePath: string, referencePath: string, o: DiffOptions, context: CliContext): void {
  const image = readExr(imagePath), reference = readExr(referencePath);
  if (image.width !== reference.width || image.height !== reference.height) {
    throw new LanternError(`'${imagePath}' is ${image.width}×${image.height} but '${referencePath}' is ${reference.width}×${reference.height}`, 'Compare images of the same size.');
  }
  const d = compareImages(image, reference);
  if (o.heatmap) writeFile(o.heatmap, encodePng(image.width, image.height, errorHeatmap(image, reference, o.heatmapScale)));
  if (o.json) {
    context.print(JSON.stringify({ image: imagePath, reference: referencePath, width: image.width, height: image.height, ...d, ...(o.heatmap ? { heatmap: o.heatmap } : {}) }, null, 2));
  } else {
    context.print(`RMSE ${d.rmse.toPrecision(4)}  relMSE ${d.relMse.toPrecision(4)}  SSIM ${d.ssim.toFixed(4)}  (${image.width}×${image.height})`);
  }
}
