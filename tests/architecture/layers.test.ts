import { describe, expect, it } from 'vitest';
import { ALLOWED, checkLayers, folderOf, readSources, SRC_DIR, type SourceFile } from './layers.ts';

const format = (v: { file: string; rule: string; detail: string }) => `${v.file}: [${v.rule}] ${v.detail}`;

describe('the layering of docs/architecture.md', () => {
  it('holds in src/', () => {
    const files = readSources(SRC_DIR);
    // Guards against the checker silently reading nothing (a wrong path would pass every rule).
    expect(files.length).toBeGreaterThan(100);
    expect(new Set(files.map((f) => folderOf(f.path)))).toEqual(new Set([...Object.keys(ALLOWED), 'errors.ts', 'budgets.ts', 'expect-lantern-error.ts']));
    expect(checkLayers(files).map(format)).toEqual([]);
  });
});

describe('the checker', () => {
  const file = (path: string, text: string): SourceFile => ({ path, text });

  it('catches a pass importing the renderer, whatever the form of the import', () => {
    const v = checkLayers([
      file('passes/a-pass.ts', "import { Renderer } from '../renderer/renderer.ts';"),
      file('passes/b-pass.ts', "import type { RenderSettings } from '../renderer/settings.ts';"),
      file('passes/c-pass.ts', "export { DEFAULT_SETTINGS } from '../renderer/settings.ts';"),
      file('passes/d-pass.ts', "export * from '../renderer/settings.ts';"),
      file('passes/e-pass.ts', "const m = await import('../renderer/settings.ts');"),
    ]);
    expect(v.map((x) => x.file)).toEqual(['passes/a-pass.ts', 'passes/b-pass.ts', 'passes/c-pass.ts', 'passes/d-pass.ts', 'passes/e-pass.ts']);
    expect(v[0]).toMatchObject({ rule: 'layer', detail: expect.stringMatching(/^passes -> renderer/) });
  });

  it('catches the CLI importing the page, and loaders importing the GPU or the renderer', () => {
    const v = checkLayers([
      file('cli/commands/view.ts', "import { formatViewParams } from '../../app/view-params.ts';"),
      file('loaders/doom/x.ts', "import { GpuContext } from '../../gpu/device.ts';"),
      file('loaders/ply/y.ts', "import { prepareScene } from '../../renderer/prepare.ts';"),
      file('gpu/pack/z.ts', "import { GpuContext } from '../device.ts';"),
    ]);
    expect(v.map((x) => x.detail.split(' (')[0])).toEqual(['cli -> app', 'loaders -> gpu', 'loaders -> renderer', 'gpu/pack -> gpu']);
  });

  it('allows what the arrows allow', () => {
    expect(
      checkLayers([
        file('renderer/r.ts', "import { TonemapPass } from '../passes/tonemap-pass.ts';\nimport { LanternError } from '../errors.ts';"),
        file('cli/c.ts', "import { readFileSync } from 'node:fs';\nimport { FORMATS } from '../loaders/registry.ts';"),
        file('app/a.ts', "document.title = 'x'; const c: HTMLCanvasElement = document.createElement('canvas');"),
        file('loaders/l.test.ts', "import { readFileSync } from 'node:fs';\nimport { expectLanternError } from '../expect-lantern-error.ts';"),
        file('scene/s.ts', "// import { x } from '../renderer/renderer.ts'\nconst text = \"from '../gpu/device.ts'\"; const o = { window: 1 }; o.window;"),
        file('image/e.ts', 'let window: number[] | undefined; window = [1];'),
        file('loaders/p.ts', 'interface Element { name: string }\nexport const e: Element = { name: "x" };'),
        file('scene/walk.test.ts', "import { loadDoomMap } from '../loaders/doom/load.ts';"),
      ]),
    ).toEqual([]);
  });

  it('keeps node:* in the CLI and the DOM in the page', () => {
    const v = checkLayers([
      file('loaders/l.ts', "import { readFileSync } from 'node:fs';"),
      file('renderer/r.ts', "import path from 'path';"),
      file('renderer/v.ts', 'export const w = window.innerWidth;'),
      file('gpu/g.ts', 'export function f(c: HTMLCanvasElement) { return c; }'),
      file('scene/t.ts', "import { expectLanternError } from '../expect-lantern-error.ts';"),
    ]);
    expect(v.map((x) => `${x.file} ${x.rule}`)).toEqual(['loaders/l.ts node', 'renderer/r.ts node', 'renderer/v.ts dom', 'gpu/g.ts dom', 'scene/t.ts test-helper']);
  });
});
