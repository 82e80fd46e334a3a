/**
 * The fragment tracer on WebGPU (issue #30; docs/fragment-tracer.md): the progressive path tracer
 * run as a fullscreen triangle's fragment shader (shaders/passes/path-trace-fragment, linked and
 * frozen by gpu/fragment-tracer-wgsl.ts), the scene read from the textures of
 * gpu/pack/scene-textures.ts, two rgba32float targets ping-ponged for the accumulation. The same
 * WGSL that WebGL2 runs translated to GLSL, so the compute kernel's image and this one can be held
 * to each other here. Progressive only, RGB only; no ray counts.
 */
import { LanternError } from '../errors.ts';
import { FRAGMENT_ACCUMULATION_FORMAT, FRAGMENT_TRACER_ENTRY, FRAGMENT_TRACER_MODULE, FRAGMENT_VERTEX_ENTRY, fragmentTracerConstants, fragmentTracerWgsl } from '../gpu/fragment-tracer-wgsl.ts';
import { BindGroupFactory, compileShader, createBindGroupLayouts } from '../gpu/kernel.ts';
import { formatBytes, packSceneTextures, type SceneTextures } from '../gpu/pack/scene-textures.ts';
import { compileRenderPipeline } from '../gpu/pipeline-compiles.ts';
import { createBufferWithData, readBuffer } from '../gpu/readback.ts';
import { ViewUniform } from '../gpu/view.ts';
import { entryPointBindings, reflectLinked } from '../gpu/wgsl/reflect.ts';
import { pathTraceParams } from '../passes/path-trace-pass.ts';
import { UniformParams, type UniformValues } from '../passes/uniform-params.ts';
import { resolveSampler } from '../passes/variants.ts';
import type { Camera, Torch } from '../scene/types.ts';
import { accumulationEstimate, type Accumulation } from './image-readback.ts';
import type { PreparedScene } from './prepare.ts';
import { effectiveTorch, type RenderSettings } from './settings.ts';

/** The scene textures on the GPU, their views by WGSL name (group 0 of the fragment tracer, or of a test kernel linked with scene/bindings-textures). */
export function uploadSceneTextures(device: GPUDevice, textures: SceneTextures): { readonly views: Readonly<Record<string, GPUTextureView>>; destroy(): void } {
  const made: GPUTexture[] = [];
  const views: Record<string, GPUTextureView> = {};
  for (const t of textures.textures) {
    const texture = device.createTexture({ label: `scene texture ${t.name}`, size: [t.width, t.height, t.depthOrLayers], format: t.format, usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    device.queue.writeTexture({ texture }, t.data, { bytesPerRow: t.width * formatBytes(t.format), rowsPerImage: t.height }, [t.width, t.height, t.depthOrLayers]);
    made.push(texture);
    views[t.name] = texture.createView({ dimension: t.array ? '2d-array' : '2d' });
  }
  return { views, destroy: () => made.forEach((t) => t.destroy()) };
}

export interface FragmentTracerOptions {
  readonly width: number;
  readonly height: number;
  /** The settings the estimate depends on (the progressive recipe's meaning: sampler 'auto' is Sobol). */
  readonly settings: Pick<RenderSettings, 'maxBounces' | 'lightSampling' | 'seed' | 'sampler' | 'torch' | 'spectral'>;
  /** Default: the scene's camera. */
  readonly camera?: Camera;
}

export class FragmentTracer {
  private samplesDone = 0;
  /** The target holding the accumulation so far (the other is written next). */
  private current = 0;

  private constructor(
    private readonly device: GPUDevice,
    private readonly options: FragmentTracerOptions,
    private readonly pipeline: GPURenderPipeline,
    private readonly targets: readonly [GPUTexture, GPUTexture],
    /** Group 2 reading target i. */
    private readonly passGroups: readonly [GPUBindGroup, GPUBindGroup],
    private readonly sceneGroup: GPUBindGroup,
    private readonly viewGroup: GPUBindGroup,
    private readonly params: UniformParams<UniformValues>,
    private readonly owned: readonly { destroy(): void }[],
    private readonly torch: Torch | undefined,
    /** The textures uploaded, for reports. */
    readonly sceneTextures: Omit<SceneTextures, 'textures'> & { readonly sizes: readonly string[] },
  ) {}

  static async create(device: GPUDevice, prepared: PreparedScene, options: FragmentTracerOptions): Promise<FragmentTracer> {
    if (options.settings.spectral) throw new LanternError('the fragment tracer renders RGB only: spectral rendering needs the compute path tracer');
    const packed = prepared.packed;
    const textures = packSceneTextures(packed, { maxTextureDimension2D: device.limits.maxTextureDimension2D, maxTextureArrayLayers: device.limits.maxTextureArrayLayers, label: prepared.scene.name });
    const sampler = resolveSampler(options.settings.sampler, 'progressive');
    const linked = fragmentTracerWgsl(fragmentTracerConstants({ features: packed.features, sampler, rowShift: textures.rowShift }));
    const shader = reflectLinked(linked);
    const slots = entryPointBindings(shader, [FRAGMENT_VERTEX_ENTRY, FRAGMENT_TRACER_ENTRY], GPUShaderStage.FRAGMENT).map((group) =>
      // rgba32float is not filterable: the accumulation is read with textureLoad only.
      group.map((s) => (s.name === 'previous_accumulation' ? { ...s, entry: { ...s.entry, texture: { sampleType: 'unfilterable-float' as const, viewDimension: '2d' as const } } } : s)),
    );
    const layouts = createBindGroupLayouts(device, FRAGMENT_TRACER_MODULE, slots);
    const groups = new BindGroupFactory(device, FRAGMENT_TRACER_MODULE, layouts, slots);
    const module = await compileShader(device, linked);
    const pipeline = await compileRenderPipeline(device, {
      label: `${FRAGMENT_TRACER_MODULE}:${FRAGMENT_TRACER_ENTRY}`,
      layout: device.createPipelineLayout({ label: FRAGMENT_TRACER_MODULE, bindGroupLayouts: layouts }),
      vertex: { module, entryPoint: FRAGMENT_VERTEX_ENTRY },
      fragment: { module, entryPoint: FRAGMENT_TRACER_ENTRY, targets: [{ format: FRAGMENT_ACCUMULATION_FORMAT }] },
      primitive: { topology: 'triangle-list' },
    });

    const uploaded = uploadSceneTextures(device, textures);
    const owned: { destroy(): void }[] = [uploaded];
    const resources: Record<string, GPUBuffer | GPUTextureView> = { ...uploaded.views };
    for (const [name, data] of [['scene_info', packed.scene_info], ['punctual_lights', packed.punctual_lights], ['environment_info', packed.environment.environment_info]] as const) {
      const buffer = createBufferWithData(device, `fragment tracer ${name}`, data, GPUBufferUsage.UNIFORM);
      owned.push(buffer);
      resources[name] = buffer;
    }
    const view = new ViewUniform(device);
    view.update(options.camera ?? prepared.scene.camera, options.width, options.height);
    owned.push(view.buffer);
    const params = new UniformParams(device, FRAGMENT_TRACER_MODULE);
    owned.push(params);
    const target = (i: number) =>
      device.createTexture({ label: `fragment tracer accumulation ${i}`, size: [options.width, options.height], format: FRAGMENT_ACCUMULATION_FORMAT, usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC });
    const targets = [target(0), target(1)] as const;
    owned.push(...targets);
    const passGroup = (i: number) => groups.bindGroup(2, { params: params.buffer, previous_accumulation: targets[i]!.createView() });
    const sizes = textures.textures.map((t) => `${t.name} ${t.width}×${t.height}${t.depthOrLayers > 1 ? `×${t.depthOrLayers}` : ''}`);
    return new FragmentTracer(device, options, pipeline, targets, [passGroup(0), passGroup(1)], groups.bindGroup(0, resources), groups.bindGroup(1, { view: view.buffer }), params, owned, effectiveTorch(prepared.scene, options.settings.torch), { rowShift: textures.rowShift, texelsPerRecord: textures.texelsPerRecord, byteSize: textures.byteSize, sizes });
  }

  get samples(): number {
    return this.samplesDone;
  }

  /**
   * Adds `samples` paths per pixel, `perDraw` in each draw (each draw reads the accumulation so far
   * and writes it with its samples added to the other target); one submit per draw, as each draw's
   * parameters differ.
   */
  accumulate(samples: number, perDraw = 1): void {
    const o = this.options;
    const torch = this.torch;
    for (let done = 0; done < samples; done += perDraw) {
      const n = Math.min(perDraw, samples - done);
      this.params.write(
        pathTraceParams({
          tile: { x: 0, y: 0, width: o.width, height: o.height },
          sampleIndex: this.samplesDone,
          samples: n,
          maxBounces: o.settings.maxBounces,
          seed: o.settings.seed,
          lightSampling: o.settings.lightSampling,
          sampler: resolveSampler(o.settings.sampler, 'progressive'),
          ...(torch ? { torch } : {}),
        }),
      );
      const encoder = this.device.createCommandEncoder({ label: 'fragment tracer' });
      const pass = encoder.beginRenderPass({
        label: 'fragment tracer',
        colorAttachments: [{ view: this.targets[1 - this.current]!.createView(), loadOp: 'clear', clearValue: [0, 0, 0, 0], storeOp: 'store' }],
      });
      pass.setPipeline(this.pipeline);
      pass.setBindGroup(0, this.sceneGroup);
      pass.setBindGroup(1, this.viewGroup);
      pass.setBindGroup(2, this.passGroups[this.current]!);
      pass.draw(3);
      pass.end();
      this.device.queue.submit([encoder.finish()]);
      this.current = 1 - this.current;
      this.samplesDone += n;
    }
  }

  /** The raw sums (vec4f a pixel: Σ radiance, Σ luminance²), rows top first. */
  async readSums(): Promise<Float32Array> {
    const { width, height } = this.options;
    const bytesPerRow = Math.ceil((width * 16) / 256) * 256;
    const buffer = this.device.createBuffer({ label: 'fragment tracer readback', size: bytesPerRow * height, usage: GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
    try {
      const encoder = this.device.createCommandEncoder({ label: 'fragment tracer readback' });
      encoder.copyTextureToBuffer({ texture: this.targets[this.current]! }, { buffer, bytesPerRow }, [width, height]);
      this.device.queue.submit([encoder.finish()]);
      const raw = new Float32Array(await readBuffer(this.device, buffer));
      const out = new Float32Array(width * height * 4);
      for (let y = 0; y < height; y++) out.set(raw.subarray((y * bytesPerRow) / 4, (y * bytesPerRow) / 4 + width * 4), y * width * 4);
      return out;
    } finally {
      buffer.destroy();
    }
  }

  /** The estimate so far, as Renderer.readAccumulation gives the compute kernel's. */
  async readAccumulation(): Promise<Accumulation> {
    return accumulationEstimate(await this.readSums(), this.options.width, this.options.height, this.samplesDone);
  }

  destroy(): void {
    for (const o of this.owned) o.destroy();
  }
}
