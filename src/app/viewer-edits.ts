/**
 * The viewer's live editing apart from the GPU: where a canvas point falls on the render image (the
 * pixel a pick traces), and the material edits since the scene loaded, merged per material (what
 * links carry), with those not applied yet (a slider sends many: merged, applied once before the
 * next frame). Pick, selection and focus on click are the Viewer's (they wait their turn with the
 * other changes).
 */
import { LanternError } from '../errors.ts';
import { materialEditProblem, mergeMaterialEdits, type MaterialEdit } from '../scene/material-edit.ts';
import type { Material } from '../scene/types.ts';
import type { MaterialOverride } from './material-link.ts';

/**
 * The render-image pixel under a canvas point given in CSS pixels from the canvas's top-left
 * corner (present() stretches the image over the canvas); `r`: the render image's size, undefined before Play.
 */
export function imagePoint(canvas: HTMLCanvasElement, r: { readonly width: number; readonly height: number } | undefined, x: number, y: number): [number, number] | undefined {
  const w = canvas.clientWidth || canvas.width, h = canvas.clientHeight || canvas.height;
  if (!r || r.width === 0 || w === 0 || h === 0) return undefined;
  const px = Math.floor((x / w) * r.width), py = Math.floor((y / h) * r.height);
  return px >= 0 && px < r.width && py >= 0 && py < r.height ? [px, py] : undefined;
}

/** The material edits of the scene shown: all of them since it loaded, and those not applied yet. */
export class MaterialEdits {
  /** Every material edit since the scene loaded, merged per material (what links carry). */
  private materialEdits = new Map<number, MaterialEdit>();
  /** Edits not yet applied (a slider sends many: they are merged and applied once, in order). */
  private pendingEdits = new Map<number, MaterialEdit>();

  /** How many materials have been edited. */
  get size(): number {
    return this.materialEdits.size;
  }

  /** Forgets every edit (another scene). */
  clear(): void {
    this.materialEdits = new Map();
    this.pendingEdits = new Map();
  }

  /**
   * Adds an edit of material `index` of the scene's `materials`, to be applied; or, changing nothing,
   * returns why it cannot be made: a material the scene lacks, a field its kind lacks, a value out of range.
   */
  add(materials: readonly Material[] | undefined, index: number, edit: MaterialEdit): LanternError | undefined {
    const material = materials?.[index];
    if (!material) return new LanternError(`the scene has no material ${index}`);
    const problem = materialEditProblem(material.kind, edit);
    if (problem) return new LanternError(`cannot edit material '${material.name}': ${problem}`);
    this.pendingEdits.set(index, mergeMaterialEdits(this.pendingEdits.get(index) ?? {}, edit));
    this.materialEdits.set(index, mergeMaterialEdits(this.materialEdits.get(index) ?? {}, edit));
    return undefined;
  }

  /** The edits not applied yet, which the caller applies now (undefined: none). */
  takePending(): Map<number, MaterialEdit> | undefined {
    if (this.pendingEdits.size === 0) return undefined;
    const edits = this.pendingEdits;
    this.pendingEdits = new Map();
    return edits;
  }

  /** The edits as links carry them: each material's index and name with its merged edit. */
  overrides(materials: readonly Material[]): MaterialOverride[] {
    return [...this.materialEdits].filter(([i]) => materials[i]).map(([index, edit]) => ({ index, name: materials[index]!.name, edit }));
  }
}

/** Why a link's material edit does not fit the scene, in words (a material index the scene lacks, another name at that index, a field the kind lacks), or undefined. */
export function overrideProblem(materials: readonly Material[], o: MaterialOverride): string | undefined {
  const m = materials[o.index];
  return !m ? `the scene has no material ${o.index}` : m.name !== o.name ? `material ${o.index} is '${m.name}', not '${o.name}'` : materialEditProblem(m.kind, o.edit);
}
