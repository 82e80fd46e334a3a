/**
 * The selected object's outline in what the page presents (never in the estimate or a read-back):
 * the part of one instance made of one material, as a pick returns it and a material edit changes it.
 */
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { ViewUniform } from '../gpu/view.ts';
import { LanternError } from '../errors.ts';
import { SelectionOutlinePass, type SelectedRange } from '../passes/selection-outline-pass.ts';
import type { PreparedScene } from './prepare.ts';

export class Selection {
  private pass?: SelectionOutlinePass;
  private selected?: SelectedRange;
  /** Whether the mask must be traced again (view, size, scene or selection changed). */
  private stale = true;

  constructor(private readonly device: GPUDevice) {}

  /** The selection (source triangle range and material), if any. */
  get range(): SelectedRange | undefined {
    return this.selected;
  }

  /** The mask is to be traced again before it is next drawn. */
  markStale(): void {
    this.stale = true;
  }

  /** Compiles the outline for a scene with these features, once there is a pass (the first selection makes it). */
  prepare(features: SceneFeatures): Promise<void> | undefined {
    return this.pass?.prepare(features);
  }

  /** Selects `instanceIndex`'s triangles of `material` in the scene (undefined: none); compiles the outline on first use. */
  async set(prepared: PreparedScene, selected: { readonly instanceIndex: number; readonly material: number } | undefined): Promise<void> {
    if (selected === undefined) {
      this.selected = undefined;
      this.pass?.destroyTargets();
      return;
    }
    const triangles = prepared.triangles;
    const { instanceIndex, material } = selected;
    if (!(material >= 0 && material < prepared.scene.materials.length)) throw new LanternError(`scene '${prepared.scene.name}' has no material ${material}`);
    if (!Number.isInteger(instanceIndex) || instanceIndex < 0 || instanceIndex >= triangles.instanceFirstTriangle.length) {
      throw new LanternError(`scene '${prepared.scene.name}' has no instance ${instanceIndex}`);
    }
    if (!this.pass) {
      const pass = await SelectionOutlinePass.create(this.device, prepared.packed.features);
      this.pass ??= pass;
    }
    await this.pass.prepare(prepared.packed.features);
    // The instance's triangles are contiguous in the flattened list (scene/triangles.ts).
    const first = triangles.instanceFirstTriangle[instanceIndex]!;
    const end = triangles.instanceFirstTriangle[instanceIndex + 1] ?? triangles.count;
    this.selected = { first, end, material };
    this.stale = true;
  }

  /** Draws the outline over `image` where something is selected, and returns the image to show. */
  encode(encoder: GPUCommandEncoder, scene: SceneResources | undefined, view: ViewUniform, image: GPUTexture): GPUTexture {
    if (!this.selected || !this.pass || !scene) return image;
    this.pass.encode(encoder, { scene, view, selection: this.selected, image, traceMask: this.stale });
    this.stale = false;
    return this.pass.output;
  }

  destroy(): void {
    this.pass?.destroy();
  }
}
