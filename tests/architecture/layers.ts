/**
 * The dependency arrows of docs/architecture.md as data, and a checker over the import graph of
 * src/: each top-level folder (gpu/pack and gpu/wgsl apart from the rest of gpu/) may import only
 * the folders listed for it (tests beside the code may import fixtures from anywhere); node:* only
 * in cli/ and tests; DOM-only globals only in app/; the test helper only in tests; and no cycle of
 * static imports (`import type` and re-exports included) among the files of src/ (findCycles).
 * Imports are read from the syntax tree (vite's parseAst: oxc, TypeScript-aware), so type-only
 * imports, re-exports and dynamic import() count, and strings or comments that look like imports
 * do not. dependency-cruiser was the first choice; it parses TypeScript with the `typescript`
 * package's JS API, which TypeScript 7 (a native binary) no longer ships.
 */
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { builtinModules } from 'node:module';
import { dirname, join, posix, relative, sep } from 'node:path';
import { parseAst } from 'vite';

const PURE_CORE = ['math', 'scene'];
const GPU_BELOW = [...PURE_CORE, 'bvh', 'shaders', 'gpu/wgsl', 'gpu/pack'];

/** Folder -> the folders it may import (besides itself, src/errors.ts and src/types). */
export const ALLOWED: Readonly<Record<string, readonly string[]>> = {
  math: [],
  scene: ['math'],
  // The world plays Scene.dynamics (scene/dynamics-types.ts) over time; scene/ never imports it.
  world: ['math', 'scene'],
  image: ['math'],
  // Loaders decode the images inside the files they read (PNG in glTF, HDR and EXR maps).
  loaders: [...PURE_CORE, 'image'],
  exporters: [...PURE_CORE, 'image'],
  bvh: [...PURE_CORE],
  shaders: [],
  'gpu/wgsl': ['shaders'],
  'gpu/pack': [...PURE_CORE, 'bvh', 'shaders', 'gpu/wgsl'],
  gpu: GPU_BELOW,
  passes: [...GPU_BELOW, 'gpu'],
  renderer: [...GPU_BELOW, 'gpu', 'passes'],
  // The WebGL2 backend (fragment path tracer, GLSL translated at build time): beside the renderer,
  // reading its settings and prepared scenes; nothing below imports it.
  webgl2: [...GPU_BELOW, 'gpu', 'passes', 'renderer'],
  // The farm's jobs, chunks and shards as data (pure); the CLI runs them (cli/farm).
  farm: [],
  // The two front ends: everything below the renderer and the pure libraries, never each other.
  app: [...GPU_BELOW, 'gpu', 'passes', 'renderer', 'webgl2', 'loaders', 'image', 'exporters', 'world'],
  cli: [...GPU_BELOW, 'gpu', 'passes', 'renderer', 'loaders', 'image', 'exporters', 'world', 'farm'],
};

/**
 * Arrows forbidden inside a folder: no file under `from` (a prefix of paths relative to src/) may
 * import `to`, tests beside the code excepted.
 */
export const FORBIDDEN_INSIDE: readonly { readonly from: string; readonly to: string; readonly why: string }[] = [
  // Issue #28: a trial split that handed recipes the Renderer closed a nine-file cycle.
  { from: 'renderer/recipes/', to: 'renderer/renderer.ts', why: 'recipes take a FrameContext (renderer/frame.ts), never the Renderer' },
];

/** Files at src/ that every folder may import (budgets.ts: the size limits every reader of files checks). */
const SHARED = new Set(['errors.ts', 'budgets.ts', 'types']);
/** Imported by tests only. */
const TEST_HELPERS = new Set(['expect-lantern-error.ts']);

/** Globals that exist on a page's main thread but not in Node or a Worker: only app/ may use them. */
const DOM_ONLY = /^(document|window|localStorage|sessionStorage|ResizeObserver|IntersectionObserver|MutationObserver|requestAnimationFrame|cancelAnimationFrame|DOMParser|HTML\w*Element|HTMLCollection|Element|NodeList|DragEvent|PointerEvent|KeyboardEvent|MouseEvent)$/;

const NODE_BUILTINS = new Set(builtinModules);

export interface SourceFile {
  /** Relative to src/, '/'-separated: 'passes/tonemap-pass.ts'. */
  readonly path: string;
  readonly text: string;
}

export interface Violation {
  readonly file: string;
  readonly rule: 'layer' | 'node' | 'dom' | 'test-helper' | 'cycle';
  readonly detail: string;
}

/** The folder a file belongs to for the rules: 'gpu/pack', 'gpu', 'errors.ts'. */
export function folderOf(path: string): string {
  const parts = path.split('/');
  if (parts.length === 1) return parts[0]!;
  if (parts[0] === 'gpu' && (parts[1] === 'pack' || parts[1] === 'wgsl') && parts.length > 2) return `gpu/${parts[1]}`;
  return parts[0]!;
}

const isTest = (path: string) => /\.test\.ts$/.test(path);

type Node = { type: string; [key: string]: unknown };

/** Every import specifier of a module (static, re-export, dynamic with a literal) and every DOM-only identifier it references. */
export function scan(text: string, path: string): { imports: string[]; staticImports: string[]; domNames: string[] } {
  const ast = parseAst(text, { lang: 'ts' }, path) as unknown as Node;
  const imports: string[] = [];
  /** The same without dynamic import(): what a module needs before it runs (the edges of a cycle). */
  const staticImports: string[] = [];
  const domNames = new Set<string>();
  /** Names the file declares itself (a local `window`, an `interface Element`): those are not the globals. File-wide, not per scope: a shadowing name anywhere in the file excuses it. */
  const declared = new Set<string>();
  const visit = (node: unknown, parent?: Node, key?: string): void => {
    if (Array.isArray(node)) {
      for (const n of node) visit(n, parent, key);
      return;
    }
    if (!node || typeof node !== 'object' || typeof (node as Node).type !== 'string') return;
    const n = node as Node;
    const source = n.source as Node | undefined;
    if ((n.type === 'ImportDeclaration' || n.type === 'ExportNamedDeclaration' || n.type === 'ExportAllDeclaration' || n.type === 'ImportExpression') && source?.type === 'Literal' && typeof source.value === 'string') {
      imports.push(source.value);
      if (n.type !== 'ImportExpression') staticImports.push(source.value);
    }
    if (n.type === 'Identifier' && typeof n.name === 'string' && DOM_ONLY.test(n.name) && (key === 'id' || key === 'params' || (key === 'local' && parent?.type?.startsWith('Import')))) declared.add(n.name);
    else if (n.type === 'Identifier' && typeof n.name === 'string' && DOM_ONLY.test(n.name)) {
      // `x.document` and `{ window: 1 }` name properties, not the global.
      const isProperty = (parent?.type === 'MemberExpression' && key === 'property' && !parent.computed) || (parent?.type === 'Property' && key === 'key') || (parent?.type === 'TSPropertySignature' && key === 'key');
      if (!isProperty) domNames.add(n.name);
    }
    for (const [k, v] of Object.entries(n)) if (k !== 'type' && v && typeof v === 'object') visit(v, n, k);
  };
  visit(ast);
  return { imports, staticImports, domNames: [...domNames].filter((name) => !declared.has(name)) };
}

/** The violations of the arrows in `files` (paths relative to src/). */
export function checkLayers(files: readonly SourceFile[]): Violation[] {
  const violations: Violation[] = [];
  for (const file of files) {
    const from = folderOf(file.path);
    const { imports, domNames } = scan(file.text, file.path);
    for (const specifier of imports) {
      const bare = specifier.replace(/^node:/, '').split('/')[0]!;
      if (specifier.startsWith('node:') || NODE_BUILTINS.has(bare)) {
        if (from !== 'cli' && !isTest(file.path)) violations.push({ file: file.path, rule: 'node', detail: `imports ${specifier}: only cli/ (and tests) may touch Node` });
        continue;
      }
      if (!specifier.startsWith('.')) continue; // packages: their own concern
      const target = posix.normalize(posix.join(posix.dirname(file.path), specifier));
      if (target.startsWith('..')) continue; // outside src/ (tests importing src are not checked here)
      const inside = FORBIDDEN_INSIDE.find((rule) => file.path.startsWith(rule.from) && target === rule.to);
      if (inside && !isTest(file.path)) violations.push({ file: file.path, rule: 'layer', detail: `${inside.from} -> ${inside.to} (imports ${specifier}): ${inside.why}` });
      const to = folderOf(target);
      if (to === from || SHARED.has(to)) continue;
      if (TEST_HELPERS.has(to)) {
        if (!isTest(file.path)) violations.push({ file: file.path, rule: 'test-helper', detail: `imports ${specifier}, a test helper` });
        continue;
      }
      // Tests may reach up for fixtures (a Doom map to export, a walk map built by the loader): they ship in no bundle.
      if (!(ALLOWED[from] ?? []).includes(to) && !isTest(file.path)) violations.push({ file: file.path, rule: 'layer', detail: `${from} -> ${to} (imports ${specifier}); ${from} may import ${(ALLOWED[from] ?? []).join(', ') || 'nothing outside itself'}` });
    }
    if (from !== 'app' && domNames.length > 0) violations.push({ file: file.path, rule: 'dom', detail: `uses ${domNames.join(', ')}: only app/ may touch the DOM` });
  }
  return violations;
}

/**
 * The import cycles among `files`: one per strongly connected component of the graph of static
 * imports between them (a file importing itself counts), as the shortest cycle from the
 * component's first file (by path) back to it, in import order, that file first. A component
 * larger than that cycle has other cycles through its files too; its whole list is in the
 * violation (cycleViolations). Sorted by first file.
 */
export function findCycles(files: readonly SourceFile[]): { cycle: string[]; component: string[] }[] {
  const paths = new Set(files.map((f) => f.path));
  const edges = new Map<string, string[]>();
  for (const file of files) {
    const targets = new Set<string>();
    for (const specifier of scan(file.text, file.path).staticImports) {
      if (!specifier.startsWith('.')) continue;
      const target = posix.normalize(posix.join(posix.dirname(file.path), specifier));
      if (paths.has(target)) targets.add(target);
    }
    edges.set(file.path, [...targets].sort());
  }
  // Tarjan's strongly connected components, iteratively (no recursion depth to run out of).
  const index = new Map<string, number>(), low = new Map<string, number>(), onStack = new Set<string>();
  const stack: string[] = [];
  const components: string[][] = [];
  let next = 0;
  for (const root of [...paths].sort()) {
    if (index.has(root)) continue;
    const work: [string, number][] = [[root, 0]];
    index.set(root, next), low.set(root, next++), stack.push(root), onStack.add(root);
    while (work.length > 0) {
      const top = work[work.length - 1]!;
      const [v, i] = top;
      const out = edges.get(v)!;
      if (i < out.length) {
        top[1]++;
        const w = out[i]!;
        if (!index.has(w)) {
          index.set(w, next), low.set(w, next++), stack.push(w), onStack.add(w);
          work.push([w, 0]);
        } else if (onStack.has(w)) low.set(v, Math.min(low.get(v)!, index.get(w)!));
        continue;
      }
      work.pop();
      if (work.length > 0) {
        const parent = work[work.length - 1]![0];
        low.set(parent, Math.min(low.get(parent)!, low.get(v)!));
      }
      if (low.get(v) === index.get(v)) {
        const component: string[] = [];
        let w: string;
        do {
          w = stack.pop()!;
          onStack.delete(w);
          component.push(w);
        } while (w !== v);
        if (component.length > 1 || edges.get(v)!.includes(v)) components.push(component.sort());
      }
    }
  }
  return components
    .map((component) => {
      // Breadth first from the first file, inside the component, back to it: the shortest cycle.
      const inside = new Set(component);
      const start = component[0]!;
      const from = new Map<string, string>();
      const queue = [start];
      let last: string | undefined;
      for (let q = 0; q < queue.length && last === undefined; q++) {
        for (const w of edges.get(queue[q]!)!) {
          if (w === start) {
            last = queue[q]!;
            break;
          }
          if (inside.has(w) && !from.has(w)) from.set(w, queue[q]!), queue.push(w);
        }
      }
      const cycle: string[] = [];
      for (let v: string | undefined = last; v !== undefined && v !== start; v = from.get(v)) cycle.unshift(v);
      return { cycle: [start, ...cycle], component };
    })
    .sort((a, b) => (a.cycle[0]! < b.cycle[0]! ? -1 : 1));
}

/** One line per cycle: 'a.ts -> b.ts -> a.ts', and the rest of its component when it has more files. */
export function formatCycle({ cycle, component }: { cycle: string[]; component: string[] }): string {
  const rest = component.filter((f) => !cycle.includes(f));
  return `${[...cycle, cycle[0]].join(' -> ')}${rest.length > 0 ? ` (the cycle's component also holds ${rest.join(', ')})` : ''}`;
}

/** The import cycles among `files` as violations (rule 'cycle'), each named by its first file. */
export function checkCycles(files: readonly SourceFile[]): Violation[] {
  return findCycles(files).map((c) => ({ file: c.cycle[0]!, rule: 'cycle', detail: `import cycle: ${formatCycle(c)}` }));
}

/** Every .ts file under `srcDir`, as SourceFiles. */
export function readSources(srcDir: string): SourceFile[] {
  const out: SourceFile[] = [];
  const walk = (dir: string) => {
    for (const name of readdirSync(dir)) {
      const full = join(dir, name);
      if (statSync(full).isDirectory()) walk(full);
      else if (name.endsWith('.ts') && !name.endsWith('.d.ts')) out.push({ path: relative(srcDir, full).split(sep).join('/'), text: readFileSync(full, 'utf8') });
    }
  };
  walk(srcDir);
  return out;
}

export const SRC_DIR = join(dirname(new URL(import.meta.url).pathname), '..', '..', 'src');
