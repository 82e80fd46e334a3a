/**
 * `lantern view [scene]`: serves the built page on this machine and prints its address; the page
 * opens with the scene loaded (built-in scenes by name; WAD and PLY files are offered by the server,
 * so files on disk such as Freedoom open in the browser). Runs until interrupted.
 */
import { fileURLToPath } from 'node:url';
import type { Command } from 'commander';
import { formatSceneLocation, type SceneLocation } from '../../loaders/scene-link.ts';
import type { CliContext } from '../context.ts';
import { formatLensLink } from '../../renderer/lens-link.ts';
import { integerOption, pathOption } from '../options.ts';
import { lensNumber } from '../lens-option.ts';
import { checkSceneFiles } from '../scene-precheck.ts';
import { checkSceneOptionsApply, openSceneFiles, parseSceneArgument, sceneHelp } from '../scene-source.ts';
import { startViewServer, type OfferedFile } from '../view-server.ts';

interface ViewOptions {
  port: number;
  host: string;
  app?: string;
  aperture?: number;
  focusDistance?: number;
  skill?: number;
}

/** Where the built page is: dist/app beside the CLI bundle (dist/cli/lantern.mjs). */
function defaultAppDir(): string {
  return fileURLToPath(new URL('../app/', import.meta.url));
}

export function registerView(program: Command, context: CliContext): void {
  program
    .command('view')
    .description('serve the interactive viewer on this machine and print its address')
    .argument('[scene]', sceneHelp(), 'cornell')
    .option('--port <n>', 'port to listen on (0: any free port)', integerOption('--port', 0, 65535), 8080)
    .option('--host <address>', 'address to listen on (127.0.0.1: this machine only)', '127.0.0.1')
    .option('--app <dir>', 'the built page to serve (default: dist/app beside the CLI)', pathOption('--app'))
    .option('--aperture <radius>', 'open the page with a thin lens of this radius (scene units; 0: a pinhole)', lensNumber('--aperture', true))
    .option('--skill <1-5>', "Doom maps: the skill level whose things appear; Wolfenstein 3D maps: whose guards (default 3)", integerOption('--skill', 1, 5))
    .option('--focus-distance <d>', "the lens's focus distance (scene units; default: the scene's, or what lies at the image centre)", lensNumber('--focus-distance', false))
    .action((sceneArg: string, options: ViewOptions) => context.run(() => view(sceneArg, options, context)));
}

/**
 * The files to offer and where the scene is, checked now (the files read and opened, the map
 * found) so that a typo fails here, not in the browser.
 */
async function sceneFiles(arg: string, skill?: number): Promise<{ files: OfferedFile[]; location: (urls: readonly string[]) => SceneLocation }> {
  const argument = parseSceneArgument(arg);
  checkSceneFiles(arg);
  const options = skill !== undefined ? { skill } : {};
  if (argument.kind === 'builtin') {
    checkSceneOptionsApply(options, undefined);
    return { files: [], location: () => ({ kind: 'builtin', name: argument.name }) };
  }
  const { format, files: read, part } = await openSceneFiles(argument);
  checkSceneOptionsApply(options, format);
  // The first file is the main one; only it refers to siblings (a glTF's buffers and textures).
  const files = read.map((file, i) => ({ path: file.path, siblings: i === 0 && format.siblings ? format.siblings(file) : [] }));
  return { files, location: (urls) => ({ kind: 'files', format: format.id, urls, ...(part ? { part } : {}), ...(skill !== undefined ? { skill } : {}) }) };
}

async function view(sceneArg: string, o: ViewOptions, context: CliContext): Promise<void> {
  const { files, location } = await sceneFiles(sceneArg, o.skill);
  const server = await startViewServer({ appDir: o.app ?? defaultAppDir(), files, host: o.host, port: o.port });
  const params = formatSceneLocation(location(server.fileUrls));
  // The page reads the lens from the link (renderer/lens-link.ts); it focuses where the link does not say.
  formatLensLink({ ...(o.aperture !== undefined ? { apertureRadius: o.aperture } : {}), ...(o.focusDistance !== undefined ? { focusDistance: o.focusDistance } : {}) }, params);
  const link = `${server.url}?${params}`;
  context.print(`Lantern viewer: ${link}`);
  if (!server.loopbackOnly) {
    context.warn(`listening on ${o.host}, beyond this machine: anyone who can reach port ${new URL(server.url).port} can open the viewer and download the scene files it serves (use --host 127.0.0.1 to keep it local)`);
  }
  context.note('open it in a browser with WebGPU (Chrome, Edge); Ctrl-C stops the server');
  await new Promise<void>((resolve) => {
    const stop = () => resolve();
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
  });
  await server.close();
}
