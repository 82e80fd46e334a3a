import { describe, expect, it } from 'vitest';
import { ALLOWED, checkCycles, checkLayers, findCycles, folderOf, readSources, SRC_DIR, type SourceFile } from './layers.ts';

const format = (v: { file: string; rule: string; detail: string }) => `${v.file}: [${v.rule}] ${v.detail}`;

describe('the layering of docs/architecture.md', () => {
  it('holds in src/', () => {
    const files = readSources(SRC_DIR);
    // Guards against the checker silently reading nothing (a wrong path would pass every rule).
    expect(files.length).toBeGreaterThan(100);
    expect(new Set(files.map((f) => folderOf(f.path)))).toEqual(new Set([...Object.keys(ALLOWED), 'errors.ts', 'budgets.ts', 'expect-lantern-error.ts']));
    expect(checkLayers(files).map(format)).toEqual([]);
  });

  it('has no import cycle in src/ (issue #28 broke the last one: scene/ and its animators, now world/)', () => {
    expect(checkCycles(readSources(SRC_DIR)).map(format)).toEqual([]);
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

  it('catches a recipe importing the Renderer, which recipes never see', () => {
    const v = checkLayers([
      file('renderer/recipes/a.ts', "import type { Renderer } from '../renderer.ts';"),
      file('renderer/recipes/b.ts', "import { pathDispatch } from '../frame.ts';"),
      file('renderer/viewerish.ts', "import { Renderer } from './renderer.ts';"),
      file('renderer/recipes/c.test.ts', "import { Renderer } from '../renderer.ts';"),
    ]);
    expect(v.map((x) => `${x.file} ${x.rule}`)).toEqual(['renderer/recipes/a.ts layer']);
    expect(v[0]!.detail).toMatch(/^renderer\/recipes\/ -> renderer\/renderer\.ts .*FrameContext/);
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

  it('catches a cycle of two files and one of three, naming the files in import order, type-only imports and re-exports included', () => {
    const v = checkCycles([
      file('scene/a.ts', "import type { B } from './b.ts';"),
      file('scene/b.ts', "import { a } from './a.ts';"),
      file('world/z.ts', "import { x } from './x.ts';"),
      file('world/x.ts', "import { y } from './sub/y.ts';"),
      file('world/sub/y.ts', "export { z } from '../z.ts';"),
      file('scene/c.ts', "import { a } from './a.ts';"),
    ]);
    expect(v.map(format)).toEqual([
      'scene/a.ts: [cycle] import cycle: scene/a.ts -> scene/b.ts -> scene/a.ts',
      'world/sub/y.ts: [cycle] import cycle: world/sub/y.ts -> world/z.ts -> world/x.ts -> world/sub/y.ts',
    ]);
  });

  it('allows a DAG, dynamic import() and imports of files outside the set; a file importing itself is a cycle', () => {
    const dag = [
      file('scene/types.ts', "import type { D } from './dynamics-types.ts';"),
      file('scene/dynamics-types.ts', "import type { Vec3 } from '../math/vec3.ts';"),
      file('math/vec3.ts', ''),
      file('scene/billboards.ts', "import type { D } from './dynamics-types.ts';\nimport type { Scene } from './types.ts';"),
      file('world/world.ts', "import { b } from '../scene/billboards.ts';\nimport type { Scene } from '../scene/types.ts';"),
      file('world/billboards.ts', "import type { W } from './world.ts';\nimport { b } from '../scene/billboards.ts';"),
      file('world/lazy.ts', "import type { W } from './world.ts';\nexport const m = () => import('./lazy-user.ts');"),
      file('world/lazy-user.ts', "import { m } from './lazy.ts';\nimport { q } from './not-listed.ts';"),
    ];
    expect(checkCycles(dag)).toEqual([]);
    expect(findCycles([file('scene/self.ts', "export * from './self.ts';")])).toEqual([{ cycle: ['scene/self.ts'], component: ['scene/self.ts'] }]);
  });

  it('names the rest of a component that has more than its shortest cycle', () => {
    const [c, ...rest] = findCycles([
      file('a.ts', "import './b.ts';"),
      file('b.ts', "import './a.ts';\nimport './c.ts';"),
      file('c.ts', "import './b.ts';"),
    ]);
    expect(rest).toEqual([]);
    expect(c).toEqual({ cycle: ['a.ts', 'b.ts'], component: ['a.ts', 'b.ts', 'c.ts'] });
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
