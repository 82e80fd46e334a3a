/**
 * The selection highlight (shaders/passes/selection-outline.wgsl): a mask of the pixels that show the
 * selected object, traced again only when the view, the image size, the scene or the selection
 * changed, and an outline composed over the shown image into a texture of its own. The estimate and
 * what readImage() returns are never touched.
 */
import { pixelGroups } from '../gpu/kernel-variants.ts';
import { ComputeKernel, SceneKernels, TRAVERSAL_FEATURES } from '../gpu/kernel.ts';
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import type { SceneResources } from '../gpu/scene-resources.ts';
import type { ViewUniform } from '../gpu/view.ts';
import type { Vec3 } from '../math/vec3.ts';
import type { Pass, PassFrame } from './pass.ts';
import { UniformParams } from './uniform-params.ts';

const MODULE = 'passes/selection-outline';
/** Bytes per pixel of the mask (one u32). */
const MASK_BYTES_PER_PIXEL = 4;
/** The outline's colour (sRGB-encoded): an orange that stands out of most renders. */
export const SELECTION_COLOR: Vec3 = [1, 0.55, 0.1];

/** What is selected: the triangles of one material within a range of source triangles (one instance's, scene/triangles.ts). */
export interface SelectedRange {
  readonly first: number;
  readonly end: number;
  readonly material: number;
}

export interface SelectionOutlineFrame extends PassFrame {
  readonly scene: SceneResources;
  readonly view: ViewUniform;
  readonly selection: SelectedRange;
  /** The image that is shown (tone-mapped or debug), rgba8unorm. */
  readonly image: GPUTexture;
  /** Trace the mask again (the view, scene or selection changed since the last one). */
  readonly traceMask: boolean;
}

/** Its output is its own, sized to the image: `output`, the image with the outline. */
export class SelectionOutlinePass implements Pass<SelectionOutlineFrame> {
  private mask?: GPUBuffer;
  private composed?: GPUTexture;

  private constructor(
    private readonly device: GPUDevice,
    private readonly maskKernels: SceneKernels,
    private readonly outlineKernel: ComputeKernel,
    private readonly params: UniformParams<{ first: number; end: number; material: number; color: Vec3 }>,
  ) {}

  /** `first`: the features of the scene to be rendered, where known: its variants start compiling instead of a plain scene's (SceneKernels.create). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<SelectionOutlinePass> {
    const [maskKernels, outlineKernel] = await Promise.all([
      SceneKernels.create(device, { module: MODULE, entryPoint: 'selection_mask' }, TRAVERSAL_FEATURES, {}, first),
      ComputeKernel.create(device, { module: MODULE, entryPoint: 'selection_outline' }),
    ]);
    return new SelectionOutlinePass(device, maskKernels, outlineKernel, new UniformParams(device, MODULE));
  }

  /** Compiles the mask's variant for a scene (traversal with or without alpha tests). */
  prepare(features: SceneFeatures): Promise<void> {
    return this.maskKernels.prepare(features);
  }

  /**
   * Encodes the mask (when asked) and the outline into `output`, the image to show. Writes its
   * parameters with queue.writeBuffer: submit before encoding again.
   */
  encode(encoder: GPUCommandEncoder, input: SelectionOutlineFrame): void {
    const { width, height } = input.image;
    const resized = this.ensureTargets(width, height);
    const mask = this.mask!, output = this.composed!;
    const groups = pixelGroups(width, height);
    this.params.write({ first: input.selection.first, end: input.selection.end, material: input.selection.material, color: SELECTION_COLOR });
    const view = { view: input.view.buffer };
    if (input.traceMask || resized) {
      const kernel = this.maskKernels.get(input.scene.features);
      const pass = encoder.beginComputePass({ label: 'selection mask' });
      kernel.dispatch(pass, { 0: kernel.bindGroup(0, input.scene.bindings), 1: kernel.bindGroup(1, view), 2: kernel.bindGroup(2, { params: this.params.buffer, mask }) }, ...groups);
      pass.end();
    }
    const k = this.outlineKernel;
    const pass = encoder.beginComputePass({ label: 'selection outline' });
    k.dispatch(pass, { 1: k.bindGroup(1, view), 2: k.bindGroup(2, { params: this.params.buffer, mask, image: input.image.createView(), output: output.createView() }) }, ...groups);
    pass.end();
  }

  /** The image with the outline, as the last encode recorded it (its size follows the image's). */
  get output(): GPUTexture {
    if (!this.composed) throw new Error('SelectionOutlinePass: no output before encode');
    return this.composed;
  }

  /** (Re)creates the mask and the output for an image size; true when they were made anew. */
  private ensureTargets(width: number, height: number): boolean {
    if (this.composed && this.composed.width === width && this.composed.height === height) return false;
    this.destroyTargets();
    this.mask = this.device.createBuffer({ label: 'selection mask', size: width * height * MASK_BYTES_PER_PIXEL, usage: GPUBufferUsage.STORAGE });
    this.composed = this.device.createTexture({
      label: 'image with the selection',
      size: [width, height],
      format: 'rgba8unorm',
      usage: GPUTextureUsage.STORAGE_BINDING | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC,
    });
    return true;
  }

  /** Frees the mask and the output (while nothing is selected); the pipelines stay. */
  destroyTargets(): void {
    this.mask?.destroy();
    this.composed?.destroy();
    this.mask = undefined;
    this.composed = undefined;
  }

  destroy(): void {
    this.destroyTargets();
    this.params.destroy();
  }
}
