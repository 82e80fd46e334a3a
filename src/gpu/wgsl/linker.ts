/**
 * Composes WGSL modules. A module names what it needs with `#import path` lines (path relative to
 * src/shaders, no extension); linking emits every module once, dependencies first, and drops the
 * import lines. Nothing else is rewritten: variants use WGSL `override` constants, never text
 * substitution. The line map lets compiler messages point at the module and line they came from.
 */
import { LanternError } from '../../errors.ts';
import { SHADER_MODULES } from '../../shaders/index.ts';

const IMPORT_LINE = /^\s*#import\s+([A-Za-z0-9_\-/]+)\s*$/;

export interface SourceLine {
  readonly module: string;
  /** 1-based line in the module's own file. */
  readonly line: number;
}

export interface LinkedShader {
  /** The module linking started from. */
  readonly entry: string;
  readonly code: string;
  /** Modules in the order they were emitted (dependencies first, the entry last). */
  readonly modules: readonly string[];
  /** For each 1-based output line (index 0 is line 1), where it came from; null for separators. */
  readonly lineMap: readonly (SourceLine | null)[];
}

/**
 * Links `entry` (a module in `sources`) with everything it imports. `sources` defaults to the shaders
 * in src/shaders; tests pass an extended map to link their own kernels against the real modules.
 * `substitutes` links another module wherever one is imported (an implementation chosen at link time:
 * gpu/specialisation.ts links scene/traversal-unrolled where the integrator imports scene/bvh); the
 * line map names the module actually linked.
 */
export function linkWgsl(entry: string, sources: ReadonlyMap<string, string> = SHADER_MODULES, substitutes: ReadonlyMap<string, string> = new Map()): LinkedShader {
  const emitted: string[] = [];
  const done = new Set<string>();
  const visiting: string[] = [];
  const out: string[] = [];
  const lineMap: (SourceLine | null)[] = [];

  const visit = (imported: string, importedBy?: string): void => {
    const name = substitutes.get(imported) ?? imported;
    if (done.has(name)) return;
    if (visiting.includes(name)) {
      throw new LanternError(`WGSL import cycle: ${[...visiting, name].join(' -> ')}`);
    }
    const source = sources.get(name);
    if (source === undefined) {
      const where = importedBy ? ` (imported by '${importedBy}')` : '';
      throw new LanternError(`WGSL module '${name}' not found${where}`);
    }
    visiting.push(name);
    const lines = source.split('\n');
    for (const line of lines) {
      const m = IMPORT_LINE.exec(line);
      if (m) visit(m[1]!, name);
    }
    visiting.pop();
    out.push(`// ---- module ${name} ----`);
    lineMap.push(null);
    lines.forEach((line, i) => {
      if (IMPORT_LINE.test(line)) return;
      out.push(line);
      lineMap.push({ module: name, line: i + 1 });
    });
    done.add(name);
    emitted.push(name);
  };

  visit(entry);
  return { entry, code: out.join('\n'), modules: emitted, lineMap };
}

/** "module:line" for a 1-based line of linked output, for compiler messages. */
export function sourceLocation(linked: LinkedShader, line: number): string {
  const at = linked.lineMap[line - 1];
  return at ? `${at.module}.wgsl:${at.line}` : `${linked.entry} (linked line ${line})`;
}
