/**
 * The Doom WAD entry of the loader registry: a stack of WADs (IWAD first, PWADs over it) is one
 * file set, and its maps are the parts a `#MAP01` fragment or the page's map picker selects.
 */
import { LanternError } from '../../errors.ts';
import type { FileHead, OpenedScene, SceneFormat } from '../format.ts';
import { WarningCap } from '../../budgets.ts';
import { loadDoomMap, summarizeMaps } from './load.ts';
import { SpriteSet } from './sprites.ts';
import { DoomGraphics } from './textures.ts';
import { DEFAULT_SKILL } from './thing-types.ts';
import { isDoomUri, parseDoomUri } from './uri.ts';
import { readWad, WadStack } from './wad.ts';

const magic = (head: Uint8Array) => String.fromCharCode(head[0] ?? 0, head[1] ?? 0, head[2] ?? 0, head[3] ?? 0);

export const WAD_FORMAT: SceneFormat = {
  id: 'doom-wad',
  kind: 'scene',
  description: 'Doom WADs',
  extensions: ['.wad'],
  sniff: (head) => magic(head) === 'IWAD' || magic(head) === 'PWAD',
  linkParam: 'wad',
  stacks: true,
  example: 'iwad.wad+pwad.wad#MAP01',
  part: { noun: 'map', linkParam: 'map', normalize: (name) => name.toUpperCase() },
  parseReference(argument) {
    if (!isDoomUri(argument)) return undefined;
    const { files, map } = parseDoomUri(argument);
    return { paths: files, ...(map ? { part: map } : {}) };
  },
  // IWADs first (the base game), then PWADs in the order given: PWADs override what comes before.
  arrange: <T extends FileHead>(files: readonly T[]) =>
    files.map((f, i) => ({ f, i, iwad: magic(f.head) === 'IWAD' })).sort((a, b) => Number(b.iwad) - Number(a.iwad) || a.i - b.i).map((x) => x.f),
  // async so that a bad file rejects the promise instead of throwing before there is one.
  async open(set) {
    if (set.files.length === 0) throw new LanternError('no WAD file was given');
    return openStack(new WadStack(set.files.map((f) => readWad(f.bytes, f.name))));
  },
};

function openStack(stack: WadStack): OpenedScene {
  const maps = stack.maps();
  if (maps.length === 0) throw new LanternError(`${stack.describe()} has no maps`, 'Open an IWAD (such as freedoom1.wad) or a PWAD that contains maps');
  // Composed once per stack and reused by every map: most textures are shared between maps.
  let graphics: DoomGraphics | undefined;
  let sprites: SpriteSet | undefined;
  // The shared graphics report through whichever load is running, capped per kind like its own warnings.
  let current: ((message: string) => void) | undefined;
  const relay = (message: string) => current?.(message);
  return {
    description: stack.describe(),
    parts: maps.map((m) => ({ name: m.name, loadable: m.format === 'doom', ...(m.format === 'doom' ? {} : { note: `${m.format} format: not supported` }) })),
    async scene(part, options = {}) {
      const cap = options.onWarning ? new WarningCap(options.onWarning) : undefined;
      const onWarning = cap?.warn;
      current = onWarning;
      try {
        graphics ??= new DoomGraphics(stack, { onWarning: relay });
        sprites ??= new SpriteSet(stack, graphics.palette, relay, graphics.texels);
        // Without a part: the first map Lantern can build, not a Hexen map that happens to come first.
        const map = part ?? maps.find((m) => m.format === 'doom')?.name;
        const things = options.skill !== undefined ? { things: { skill: options.skill } } : {};
        const loaded = loadDoomMap(stack, map, { graphics, sprites, ...things, ...(onWarning ? { onWarning } : {}), ...(options.lightTable ? { lightTable: options.lightTable } : {}) });
        const failed = loaded.failures;
        if (failed.length > 0) {
          const listed = failed.slice(0, 20).map((f) => `#${f.sector}`).join(', ') + (failed.length > 20 ? ` and ${failed.length - 20} more` : '');
          onWarning?.(`${failed.length} sector(s) of ${loaded.map.name} could not be triangulated: ${listed}`);
        }
        return loaded.scene;
      } finally {
        current = undefined;
        cap?.finish();
      }
    },
    inventory(options = {}) {
      const skill = options.skill ?? DEFAULT_SKILL;
      const summaries = summarizeMaps(stack, { skill });
      const n = (x: number | undefined) => (x ?? 0).toLocaleString('en-US').padStart(7);
      const lines = [`${stack.describe()}: ${summaries.length} maps (sprites drawn and emitting at skill ${skill})`, '  map        things  lines  sectors  triangles  textures  sprites  emitting'];
      for (const m of summaries) {
        if (m.error) lines.push(`  ${m.name.padEnd(8)}  ${m.error}`);
        else {
          const failed = m.failures && m.failures.length > 0 ? `  (${m.failures.length} sectors not triangulated)` : '';
          lines.push(`  ${m.name.padEnd(8)} ${n(m.things)}${n(m.linedefs)}  ${n(m.sectors)}  ${n(m.triangles).padStart(9)}  ${n(m.textures).padStart(8)}  ${n(m.sprites)}  ${n(m.emittingSprites).padStart(8)}${failed}`);
        }
      }
      return { lines, json: { wads: stack.files.map((f) => f.name), skill, maps: summaries } };
    },
  };
}
