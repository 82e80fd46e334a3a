/** `lantern textures <wad> -o dir/`: every composed wall texture and flat as PNG, to check the composer. */
import { join } from 'node:path';
import type { Command } from 'commander';
import { DoomGraphics } from '../../loaders/doom/textures.ts';
import { encodePng } from '../../image/png.ts';
import type { CliContext } from '../context.ts';
import { checkOutputPath, writeFile } from '../output-files.ts';
import { pathOption } from '../options.ts';
import { openWads } from '../wad-files.ts';

/** Lump names may hold characters a file system dislikes ('\\', '[', ...): keep them readable and unique. */
export function safeFileName(name: string): string {
  return name.replace(/[^A-Za-z0-9_-]/g, (c) => `%${c.charCodeAt(0).toString(16).toUpperCase().padStart(2, '0')}`);
}

export function registerTextures(program: Command, context: CliContext): void {
  program
    .command('textures')
    .description('write every wall texture and flat of a WAD (or iwad.wad+pwad.wad) as PNG files')
    .argument('<wad>', 'a .wad file, or several joined by +')
    .requiredOption('-o, --out <dir>', 'folder to write textures/ and flats/ into', pathOption('--out'))
    .action((wad: string, o: { out: string }) =>
      context.run(async () => {
        checkOutputPath('--out', o.out, 'folder');
        const { stack } = openWads(wad);
        const graphics = new DoomGraphics(stack, { onWarning: context.warn });
        let count = 0;
        for (const [kind, names, get] of [
          ['textures', graphics.textureNames(), (n: string) => graphics.texture(n)],
          ['flats', graphics.flatNames(), (n: string) => graphics.flat(n)],
        ] as const) {
          for (const name of names) {
            const image = get(name);
            if (!image) continue;
            writeFile(join(o.out, kind, `${safeFileName(name)}.png`), encodePng(image.width, image.height, image.rgba));
            count++;
          }
        }
        context.print(`${stack.describe()}: ${graphics.textureNames().length} textures and ${graphics.flatNames().length} flats -> ${count} PNG files in ${o.out}`);
      }),
    );
}
