/**
 * `lantern view [scene]`: serves the built page on this machine and prints its address; the page
 * opens with the scene loaded (built-in scenes by name; WAD and PLY files are offered by the server,
 * so files on disk such as Freedoom open in the browser). Runs until interrupted.
 */
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import type { Command } from 'commander';
import { LanternError } from '../../errors.ts';
import { builtinSceneNames, isBuiltinScene } from '../../loaders/builtin/index.ts';
import { isDoomUri, parseDoomUri } from '../../loaders/doom/uri.ts';
import { formatViewParams, type SceneLocation } from '../../app/view-params.ts';
import type { CliContext } from '../context.ts';
import { integerOption } from '../options.ts';
import { dragonPath, DRAGON_ALIAS, sceneHelp } from '../scene-source.ts';
import { startViewServer } from '../view-server.ts';
import { openWads } from '../wad-files.ts';

interface ViewOptions {
  port: number;
  host: string;
  app?: string;
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
    .option('--app <dir>', 'the built page to serve (default: dist/app beside the CLI)')
    .action((sceneArg: string, options: ViewOptions) => context.run(() => view(sceneArg, options, context)));
}

/** The files to offer and where the scene is, checked now so that a typo fails here, not in the browser. */
function sceneFiles(arg: string): { files: string[]; location: (urls: readonly string[]) => SceneLocation } {
  if (isBuiltinScene(arg)) return { files: [], location: () => ({ kind: 'builtin', name: arg }) };
  if (isDoomUri(arg)) {
    const { files, map } = parseDoomUri(arg);
    const { stack } = openWads(arg);
    if (map && !stack.maps().some((m) => m.name === map)) {
      throw new LanternError(`${stack.describe()} has no map '${map}'`, `Its maps are: ${stack.maps().map((m) => m.name).join(', ')}`);
    }
    return { files: [...files], location: (urls) => ({ kind: 'wad', urls, ...(map ? { map } : {}) }) };
  }
  const path = arg === DRAGON_ALIAS ? dragonPath() : arg;
  if (!path) throw new LanternError('the Stanford Dragon is not installed', 'Run `npm ci` (it comes with the development dependencies)');
  if (!/\.ply(\.gz)?$/i.test(path)) throw new LanternError(`unknown scene '${arg}'`, `Give ${sceneHelp()}; built-in scenes are ${builtinSceneNames().join(', ')}`);
  if (!existsSync(path)) throw new LanternError(`cannot read '${path}': no such file`);
  return { files: [path], location: (urls) => ({ kind: 'ply', url: urls[0]! }) };
}

async function view(sceneArg: string, o: ViewOptions, context: CliContext): Promise<void> {
  const { files, location } = sceneFiles(sceneArg);
  const server = await startViewServer({ appDir: o.app ?? defaultAppDir(), files, host: o.host, port: o.port });
  const link = `${server.url}?${formatViewParams({ scene: location(server.fileUrls) })}`;
  context.print(`Lantern viewer: ${link}`);
  context.note('open it in a browser with WebGPU (Chrome, Edge); Ctrl-C stops the server');
  await new Promise<void>((resolve) => {
    const stop = () => resolve();
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
  });
  await server.close();
}
