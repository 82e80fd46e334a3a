/**
 * The debug views behind the Renderer facade: BVH heat maps, box wireframe, leaf size and depth,
 * normals, albedo, barycentrics and triangle ids, composed with the tone-mapped image as settings
 * ask (replace, side-by-side, overlay). Each frame that shows one runs
 *
 *   debug-view (pixel-centre primary rays, counting traversal) → raw values
 *   [bvh-wireframe (boxes at the chosen depth) → lines]
 *   debug-compose (values + lines + tone-mapped image) → the image presented or read back
 *
 * Primary rays through pixel centres carry no randomness, so the views are exact and repeatable
 * whatever the path tracer has accumulated. Owns its GPU buffers: per image size (values, lines,
 * composed image) and per scene (node depths, the node list of each wireframe depth).
 */
import { maxNodeDepth, nodeDepths, nodesAtDepth } from '../../bvh/depths.ts';
import { boundsDiagonal, bvhStats } from '../../bvh/stats.ts';
import type { SceneResources } from '../../gpu/scene-resources.ts';
import { createBufferWithData, readBuffer } from '../../gpu/readback.ts';
import { BvhWireframePass, WIREFRAME_FORMAT } from '../../passes/bvh-wireframe-pass.ts';
import { DebugComposePass } from '../../passes/debug-compose-pass.ts';
import { DebugViewPass } from '../../passes/debug-view-pass.ts';
import { debugLegend, scaleMax, type DebugLegend, type LegendFacts } from '../debug-legend.ts';
import type { PreparedScene } from '../prepare.ts';
import type { SceneFeatures } from '../../gpu/pack/scene-pack.ts';
import type { RenderSettings } from '../settings.ts';
import type { ViewUniform } from '../../gpu/view.ts';

/** Bytes per pixel of the raw values (one vec4f). */
const VALUE_BYTES_PER_PIXEL = 16;
/** The wireframe's near plane as a fraction of the scene's diagonal. */
const NEAR_FRACTION = 1e-5;

export interface DebugFrame {
  readonly prepared: PreparedScene;
  readonly resources: SceneResources;
  readonly view: ViewUniform;
  /** The tone-mapped image (rgba8unorm, TEXTURE_BINDING), whose size the debug images take. */
  readonly image: GPUTexture;
  readonly settings: RenderSettings;
}

interface SizeTargets {
  readonly width: number;
  readonly height: number;
  readonly values: GPUBuffer;
  readonly range: GPUBuffer;
  readonly wireframe: GPUTexture;
  readonly composed: GPUTexture;
}

interface SceneData {
  readonly resources: SceneResources;
  readonly nodeDepths: Uint32Array;
  readonly depthBuffer: GPUBuffer;
  readonly maxDepth: number;
  readonly maxLeafSize: number;
  readonly near: number;
  readonly wireframeNodes: Map<number, { buffer: GPUBuffer; count: number }>;
}

export class DebugViews {
  private size?: SizeTargets;
  private sceneData?: SceneData;

  private constructor(
    private readonly device: GPUDevice,
    private readonly trace: DebugViewPass,
    private readonly wireframe: BvhWireframePass,
    private readonly compose: DebugComposePass,
  ) {}

  /** `first`: the features of the scene to be shown, where known (its traversal variant compiles instead of a plain scene's). */
  static async create(device: GPUDevice, first?: SceneFeatures): Promise<DebugViews> {
    const [trace, wireframe, compose] = await Promise.all([DebugViewPass.create(device, first), BvhWireframePass.create(device), DebugComposePass.create(device)]);
    return new DebugViews(device, trace, wireframe, compose);
  }

  /** Encodes the debug view of `frame` and returns the composed image (valid until the size changes). */
  encode(encoder: GPUCommandEncoder, frame: DebugFrame): GPUTexture {
    const s = frame.settings;
    const size = this.targets(frame.image.width, frame.image.height);
    const scene = this.scene(frame.prepared, frame.resources);
    this.trace.encode(encoder, { scene: frame.resources, view: frame.view, target: { ...size, nodeDepths: scene.depthBuffer }, debugView: s.debugView });
    if (s.debugView === 'wireframe') {
      const nodes = s.wireframeLevel === 'top' && frame.prepared.levels ? this.topLevelNodes(frame.prepared, s.wireframeDepth) : this.wireframeNodes(scene, s.wireframeDepth);
      this.wireframe.encode(encoder, { scene: frame.resources, view: frame.view, nodes: nodes.buffer, count: nodes.count, near: scene.near, target: size.wireframe });
    }
    // 0 asks the shader for the image's own maximum (heatMax 'auto').
    const fixedMax = s.debugView.startsWith('heat-') && s.heatMax === 'auto' ? 0 : (scaleMax(s, this.facts(scene, 0)) ?? 0);
    this.compose.encode(encoder, { view: frame.view, input: { view: s.debugView, layout: s.debugLayout, scaleMax: fixedMax, values: size.values, range: size.range, image: frame.image, wireframe: size.wireframe }, output: size.composed });
    return size.composed;
  }

  /** The legend of the last encoded view; reads the image's maximum back when the scale is automatic. */
  /** Compiles the tracing variant a scene with these features needs. */
  prepare(features: SceneFeatures): Promise<void> {
    return this.trace.prepare(features);
  }

  async legend(settings: RenderSettings, prepared: PreparedScene, resources: SceneResources): Promise<DebugLegend> {
    const scene = this.scene(prepared, resources);
    const imageMax = this.size ? new Uint32Array(await readBuffer(this.device, this.size.range))[0]! : 0;
    return debugLegend(settings, this.facts(scene, imageMax));
  }

  /** The raw values of the last encoded view: 4 floats per pixel, row-major, top row first (see debug-view.wgsl). */
  async readValues(): Promise<Float32Array> {
    if (!this.size) throw new Error('DebugViews: nothing encoded yet');
    return new Float32Array(await readBuffer(this.device, this.size.values));
  }

  /** The deepest node of the scene's BVH (the wireframe depth's upper bound). */
  maxDepth(prepared: PreparedScene, resources: SceneResources): number {
    return this.scene(prepared, resources).maxDepth;
  }

  destroy(): void {
    this.destroySize();
    this.destroyScene();
    this.trace.destroy();
    this.topLevel?.buffer.destroy();
    this.wireframe.destroy();
    this.compose.destroy();
  }

  private facts(scene: SceneData, imageMax: number): LegendFacts {
    return { maxDepth: scene.maxDepth, maxLeafSize: scene.maxLeafSize, imageMax };
  }

  private targets(width: number, height: number): SizeTargets {
    if (this.size && this.size.width === width && this.size.height === height) return this.size;
    this.destroySize();
    const d = this.device;
    const texture = (label: string, usage: GPUTextureUsageFlags) => d.createTexture({ label, size: [width, height], format: WIREFRAME_FORMAT, usage });
    this.size = {
      width,
      height,
      values: d.createBuffer({ label: 'debug values', size: width * height * VALUE_BYTES_PER_PIXEL, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC }),
      range: d.createBuffer({ label: 'debug range', size: 8, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST }),
      wireframe: texture('debug wireframe', GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING),
      composed: texture('debug composed image', GPUTextureUsage.STORAGE_BINDING | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC),
    };
    return this.size;
  }

  private scene(prepared: PreparedScene, resources: SceneResources): SceneData {
    if (this.sceneData?.resources === resources) return this.sceneData;
    this.destroyScene();
    const { bvh } = prepared;
    const depths = nodeDepths(bvh);
    this.sceneData = {
      resources,
      nodeDepths: depths,
      depthBuffer: createBufferWithData(this.device, 'bvh node depths', depths, GPUBufferUsage.STORAGE),
      maxDepth: maxNodeDepth(depths),
      maxLeafSize: bvhStats(bvh).leafSizeHistogram.length - 1,
      near: Math.max(boundsDiagonal(bvh) * NEAR_FRACTION, 1e-6),
      wireframeNodes: new Map(),
    };
    return this.sceneData;
  }

  /** The top level's boxes at `depth`, made again whenever the top level was rebuilt (something moved). */
  private topLevelNodes(prepared: PreparedScene, depth: number): { buffer: GPUBuffer; count: number } {
    const tlas = prepared.levels!.tlas;
    if (this.topLevel?.tlas !== tlas || this.topLevel.depth !== depth) {
      this.topLevel?.buffer.destroy();
      const base = prepared.packed.layout.tlasBase;
      const list = nodesAtDepth(nodeDepths(tlas), depth).map((n) => n + base);
      // An empty list still needs a buffer to bind.
      const buffer = createBufferWithData(this.device, `top-level nodes at depth ${depth}`, list.length > 0 ? list : new Uint32Array(1), GPUBufferUsage.STORAGE);
      this.topLevel = { tlas, depth, buffer, count: list.length };
    }
    return this.topLevel;
  }

  private topLevel?: { tlas: object; depth: number; buffer: GPUBuffer; count: number };

  private wireframeNodes(scene: SceneData, depth: number): { buffer: GPUBuffer; count: number } {
    let nodes = scene.wireframeNodes.get(depth);
    if (!nodes) {
      const list = nodesAtDepth(scene.nodeDepths, depth);
      nodes = { buffer: createBufferWithData(this.device, `bvh nodes at depth ${depth}`, list, GPUBufferUsage.STORAGE), count: list.length };
      scene.wireframeNodes.set(depth, nodes);
    }
    return nodes;
  }

  private destroySize(): void {
    if (!this.size) return;
    this.size.values.destroy();
    this.size.range.destroy();
    this.size.wireframe.destroy();
    this.size.composed.destroy();
    this.size = undefined;
  }

  private destroyScene(): void {
    if (!this.sceneData) return;
    this.sceneData.depthBuffer.destroy();
    for (const n of this.sceneData.wireframeNodes.values()) n.buffer.destroy();
    this.sceneData = undefined;
  }
}
