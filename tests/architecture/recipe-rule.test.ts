/**
 * Issue #28: what a frame is gets decided in one place (renderer/recipes/recipe.ts recipeFor), and
 * the front ends reach it through their own inputs: the CLI from its command line, the page from its
 * link. Given the same switches, both must arrive at the same recipe (they once differed: --restir
 * alone started frames in the CLI and not on the page).
 */
import { Command } from 'commander';
import { describe, expect, it } from 'vitest';
import { linkedRenderSettings, parseViewParams } from '../../src/app/view-params.ts';
import { recipeOf } from '../../src/cli/commands/render-frames.ts';
import { withSettingOptions } from '../../src/cli/setting-options.ts';
import { recipeFor } from '../../src/renderer/recipes/recipe.ts';
import { DEFAULT_SETTINGS } from '../../src/renderer/settings.ts';

/** The recipe `lantern render <args>` runs: its command line parsed as the render command parses it. */
function cliRecipe(args: string[]) {
  const command = withSettingOptions(new Command().exitOverride().configureOutput({ writeErr: () => {} }))
    .option('--frames <n>', '', Number)
    .option('--path <file>');
  command.parse(args, { from: 'user' });
  return recipeOf(command.opts());
}

/** The recipe the page runs when opened on `?<query>`: the link's settings over the viewer's defaults, as main.ts applies them. */
function pageRecipe(query: string) {
  const { view, problems } = parseViewParams(new URLSearchParams(query));
  expect(problems).toEqual([]);
  return recipeFor({ ...DEFAULT_SETTINGS, ...linkedRenderSettings(view) });
}

describe('one rule for what a frame is', () => {
  it('gives the CLI and the page the same recipe for every combination of switches', () => {
    const switches = [['--temporal', 'temporal'], ['--denoise', 'denoise'], ['--restir', 'restir']] as const;
    let compared = 0;
    for (let bits = 0; bits < 1 << switches.length; bits++)
      for (const mode of ['path', 'hybrid'] as const)
        for (const debug of [undefined, ['heat-nodes', 'replace'], ['normals', 'side-by-side']] as const) {
          const on = switches.filter((_, i) => (bits & (1 << i)) !== 0);
          // A CLI switch not given is off; the page's defaults have the chain on, so its link says each one.
          const args = [...on.map(([flag]) => flag), '--mode', mode, ...(debug ? ['--debug', debug[0], '--debug-layout', debug[1]] : [])];
          const query = [...switches.map(([flag, link]) => `${link}=${on.some(([f]) => f === flag) ? 1 : 0}`), `recipe=${mode}`, ...(debug ? [`debug=${debug[0]}`, `layout=${debug[1]}`] : [])].join('&');
          expect(cliRecipe(args), `${args.join(' ')} vs ?${query}`).toBe(pageRecipe(query));
          compared++;
        }
    expect(compared).toBe(48);
  });

  it('runs frames for --frames and --path with every filter off, which the page (never asked for frames in time) accumulates', () => {
    expect(cliRecipe(['--frames', '3'])).toBe('real-time');
    expect(cliRecipe(['--path', 'p.json'])).toBe('real-time');
    expect(cliRecipe([])).toBe('progressive');
    expect(pageRecipe('temporal=0&denoise=0')).toBe('progressive');
  });
});
