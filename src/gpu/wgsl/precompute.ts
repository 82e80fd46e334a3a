/**
 * The build's half of precomputed reflection: every module of src/shaders linked and reflected with
 * reflect.ts's live functions (the same code that reflects at run time where there is no data),
 * written as the PrecomputedReflection that reflect.ts reads in a bundle. Run by
 * scripts/shader-reflection.ts while Vite builds (through Vite's module runner, which gives
 * shaders/index.ts its import.meta.glob); nothing at run time imports this file.
 */
import { SHADER_MODULES } from '../../shaders/index.ts';
import { linkWgsl, type LinkedShader } from './linker.ts';
import { codeHash, liveEntryPointNames, liveEntryResources, liveLayouts, type EntryResource, type PrecomputedModule, type PrecomputedReflection, type ShaderLayouts } from './reflect.ts';

export interface PrecomputeResult {
  readonly data: PrecomputedReflection;
  /**
   * What the data leaves out, and why. Each is reflected live at run time, where it fails just as it
   * did here: scene/traversal-unrolled links only with the module gpu/specialisation.ts generates.
   */
  readonly skipped: readonly string[];
}

const message = (e: unknown) => (e as Error)?.message ?? String(e);

export function precomputeReflection(sources: ReadonlyMap<string, string> = SHADER_MODULES): PrecomputeResult {
  const definitions: unknown[] = [];
  const indices = new Map<string, number>();
  const intern = (def: unknown): number => {
    const key = JSON.stringify(def);
    let i = indices.get(key);
    if (i === undefined) {
      i = definitions.push(def) - 1;
      indices.set(key, i);
    }
    return i;
  };
  const byName = (defs: Record<string, unknown>) => Object.fromEntries(Object.entries(defs).map(([name, def]) => [name, intern(def)]));

  const modules: Record<string, PrecomputedModule> = {};
  const skipped: string[] = [];
  for (const name of [...sources.keys()].sort()) {
    let linked: LinkedShader, layouts: ShaderLayouts, entries: string[];
    try {
      linked = linkWgsl(name, sources);
      layouts = liveLayouts(linked);
      entries = liveEntryPointNames(linked);
    } catch (e) {
      skipped.push(`${name}: ${message(e)}`);
      continue;
    }
    const entryPoints: Record<string, EntryResource[]> = {};
    for (const entry of entries) {
      try {
        entryPoints[entry] = liveEntryResources(linked, entry);
      } catch (e) {
        skipped.push(`${name}:${entry}: ${message(e)}`);
      }
    }
    modules[name] = { code: codeHash(linked.code), structs: byName(layouts.structs), uniforms: byName(layouts.uniforms), entryPoints };
  }
  return { data: { definitions, modules }, skipped };
}
