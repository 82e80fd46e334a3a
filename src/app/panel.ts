/**
 * The settings panel (Tweakpane): render settings, camera, torch, what the GPU is doing, and output.
 * Every change goes through the Viewer, which restarts accumulation when the change invalidates the
 * image. The numbers are the viewer's own measurements: frame rate and time on the wall clock, pass
 * times from GPU timestamp queries (where the adapter offers them), rays from the GPU's counters.
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { Pane } from 'tweakpane';
import { DEBUG_LAYOUTS, DEBUG_VIEWS, DENOISE_VIEWS, effectiveTorch, TONE_MAPPERS, type DebugLayout, type DebugView, type DenoiseView } from '../renderer/settings.ts';
import type { BindingApi } from '@tweakpane/core';
import type { MoveMode } from './camera-controller.ts';
import { LIMITS } from './view-params.ts';
import type { Viewer } from './viewer.ts';

export interface PanelActions {
  screenshot(): void;
  exportExr(): void;
  copyLink(): void;
}

const options = <T extends string>(values: readonly T[]) => Object.fromEntries(values.map((v) => [v, v])) as Record<T, T>;

export class SettingsPanel {
  private readonly pane: Pane;
  private readonly params = {
    samplesPerFrame: 1,
    maxBounces: 8,
    scale: 1,
    accumulate: true,
    toneMapper: 'aces' as string,
    exposure: 0,
    fov: 60,
    mode: 'fly' as MoveMode,
    torch: true,
    torchColor: { r: 1, g: 1, b: 1 },
    torchIntensity: 0,
    torchRange: 1,
    debugView: 'none' as string,
    debugLayout: 'replace' as string,
    wireframeDepth: 0,
    heatMax: 0,
    temporal: false,
    denoise: false,
    clampK: 1.25,
    historyCap: 32,
    unlimitedHistory: false,
    denoiseView: 'output' as string,
  };
  private depthBinding?: BindingApi;
  private debugFolder?: ReturnType<Pane['addFolder']>;
  private readonly monitor = { fps: 0, frame: '', gpu: '', spp: 0, rays: '', image: '', scene: '', gpuMemory: '' };
  /** True while the panel takes values from the viewer: Tweakpane reports those as changes too. */
  private syncing = false;

  constructor(
    container: HTMLElement,
    private readonly viewer: Viewer,
    actions: PanelActions,
  ) {
    this.pane = new Pane({ container, title: 'Lantern' });
    this.read();
    const p = this.params;
    const render = this.pane.addFolder({ title: 'Render' });
    render.addBinding(p, 'samplesPerFrame', { label: 'samples/frame', min: LIMITS.samplesPerFrame[0], max: 16, step: 1 }).on('change', (e) => this.apply({ samplesPerFrame: e.value }));
    render.addBinding(p, 'maxBounces', { label: 'max bounces', min: 0, max: 32, step: 1 }).on('change', (e) => this.apply({ render: { maxBounces: e.value } }));
    render.addBinding(p, 'scale', { label: 'resolution', min: Math.min(0.25, p.scale), max: 2, step: 0.05 }).on('change', (e) => this.apply({ scale: e.value }));
    render.addBinding(p, 'accumulate', { label: 'accumulate' }).on('change', (e) => this.apply({ accumulate: e.value }));
    render.addBinding(p, 'toneMapper', { label: 'tone map', options: options(TONE_MAPPERS) }).on('change', (e) => this.apply({ render: { toneMapper: e.value as (typeof TONE_MAPPERS)[number] } }));
    render.addBinding(p, 'exposure', { label: 'exposure (stops)', min: -8, max: 8, step: 0.1 }).on('change', (e) => this.apply({ render: { exposureStops: e.value } }));

    const camera = this.pane.addFolder({ title: 'Camera and torch' });
    camera.addBinding(p, 'fov', { label: 'field of view', min: LIMITS.fovDegrees[0], max: 120, step: 1 }).on('change', (e) => this.syncing || viewer.setFieldOfView(e.value));
    camera.addBinding(p, 'mode', { label: 'movement', options: { 'walk (Doom maps)': 'walk', fly: 'fly' } }).on('change', (e) => {
      if (this.syncing) return;
      if (!viewer.setMoveMode(e.value)) {
        p.mode = viewer.controller?.mode ?? 'fly';
        this.pane.refresh();
      }
    });
    camera.addBinding(p, 'torch', { label: 'torch' }).on('change', () => this.applyTorch());
    camera.addBinding(p, 'torchColor', { label: 'torch colour', color: { type: 'float' } }).on('change', () => this.applyTorch());
    camera.addBinding(p, 'torchIntensity', { label: 'intensity (W/sr)', min: 0 }).on('change', () => this.applyTorch());
    camera.addBinding(p, 'torchRange', { label: 'range', min: 1e-3 }).on('change', () => this.applyTorch());

    const realTime = this.pane.addFolder({ title: 'Denoising (real time)' });
    realTime.addBinding(p, 'temporal', { label: 'temporal' }).on('change', (e) => this.apply({ render: { temporal: e.value } }));
    realTime.addBinding(p, 'denoise', { label: 'spatial (à-trous)' }).on('change', (e) => this.apply({ render: { denoise: e.value } }));
    realTime.addBinding(p, 'clampK', { label: 'clamp k·σ (0: off)', min: 0, max: 4, step: 0.05 }).on('change', (e) => this.apply({ render: { clampK: e.value } }));
    realTime.addBinding(p, 'historyCap', { label: 'history cap', min: 1, max: 256, step: 1 }).on('change', () => this.applyHistory());
    realTime.addBinding(p, 'unlimitedHistory', { label: 'converge when still' }).on('change', () => this.applyHistory());
    realTime.addBinding(p, 'denoiseView', { label: 'show', options: options(DENOISE_VIEWS) }).on('change', (e) => this.apply({ render: { denoiseView: e.value as DenoiseView } }));

    const debug = this.pane.addFolder({ title: 'Debug views', expanded: false });
    this.debugFolder = debug;
    debug.addBinding(p, 'debugView', { label: 'view', options: options(DEBUG_VIEWS) }).on('change', (e) => this.apply({ render: { debugView: e.value as DebugView } }));
    debug.addBinding(p, 'debugLayout', { label: 'layout', options: options(DEBUG_LAYOUTS) }).on('change', (e) => this.apply({ render: { debugLayout: e.value as DebugLayout } }));
    debug.addBinding(p, 'heatMax', { label: 'scale max (0: auto)', min: 0, step: 1 }).on('change', (e) => this.apply({ render: { heatMax: e.value > 0 ? e.value : 'auto' } }));
    this.addDepthBinding();

    const numbers = this.pane.addFolder({ title: 'GPU' });
    const m = this.monitor;
    numbers.addBinding(m, 'fps', { label: 'frames/s', readonly: true, view: 'graph', min: 0, max: 120 });
    numbers.addBinding(m, 'frame', { label: 'frame', readonly: true });
    numbers.addBinding(m, 'gpu', { label: 'GPU passes', readonly: true, multiline: true, rows: 4 });
    numbers.addBinding(m, 'spp', { label: 'samples/pixel', readonly: true, format: (v) => v.toFixed(0) });
    numbers.addBinding(m, 'rays', { label: 'rays/s', readonly: true });
    numbers.addBinding(m, 'image', { label: 'image', readonly: true });
    numbers.addBinding(m, 'scene', { label: 'scene', readonly: true, multiline: true, rows: 2 });
    numbers.addBinding(m, 'gpuMemory', { label: 'GPU memory', readonly: true });

    const output = this.pane.addFolder({ title: 'Output' });
    output.addButton({ title: 'Screenshot (PNG)' }).on('click', () => actions.screenshot());
    output.addButton({ title: 'Radiance (EXR)' }).on('click', () => actions.exportExr());
    output.addButton({ title: 'Copy link to this view' }).on('click', () => actions.copyLink());
  }

  /** Takes the viewer's current settings and camera into the panel (after a scene switch or a link). */
  readFromViewer(): void {
    this.syncing = true;
    try {
      this.read();
      // The depth slider's range is the scene's BVH depth.
      this.addDepthBinding();
      this.pane?.refresh();
    } finally {
      this.syncing = false;
    }
  }

  private read(): void {
    const p = this.params;
    const s = this.viewer.settings;
    p.samplesPerFrame = s.samplesPerFrame;
    p.maxBounces = s.render.maxBounces;
    p.scale = s.scale;
    p.accumulate = s.accumulate;
    p.toneMapper = s.render.toneMapper;
    p.exposure = s.render.exposureStops;
    p.debugView = s.render.debugView;
    p.debugLayout = s.render.debugLayout;
    p.wireframeDepth = s.render.wireframeDepth;
    p.heatMax = s.render.heatMax === 'auto' ? 0 : s.render.heatMax;
    p.temporal = s.render.temporal;
    p.denoise = s.render.denoise;
    p.clampK = s.render.clampK;
    p.unlimitedHistory = s.render.historyCap === 'unlimited';
    if (s.render.historyCap !== 'unlimited') p.historyCap = s.render.historyCap;
    p.denoiseView = s.render.denoiseView;
    const c = this.viewer.controller;
    if (c) {
      p.fov = c.vfovDegrees;
      p.mode = c.mode;
    }
    const scene = this.viewer.scene?.prepared;
    const torch = effectiveTorch(scene?.scene, s.render.torch);
    const diagonal = scene ? boundsDiagonal(scene.bvh) : 1;
    p.torch = s.render.torch.enabled;
    const color = torch?.color ?? s.render.torch.color ?? [1, 1, 1];
    p.torchColor = { r: color[0], g: color[1], b: color[2] };
    p.torchIntensity = torch?.intensity ?? s.render.torch.intensity ?? 0;
    p.torchRange = torch?.range ?? s.render.torch.range ?? Math.max(diagonal / 2, 1e-3);
  }

  /** Refreshes the numbers (called on every frame; Tweakpane redraws monitors on its own interval). */
  showStats(): void {
    const s = this.viewer.stats;
    const m = this.monitor;
    m.fps = s.framesPerSecond;
    m.frame = s.frameMs > 0 ? `${s.frameMs.toFixed(1)} ms` : '–';
    const total = s.gpuPasses.reduce((t, p) => t + p.ms, 0);
    m.gpu = s.gpuPasses.length > 0 ? [...s.gpuPasses.map((p) => `${p.name}: ${p.ms.toFixed(2)} ms`), `total: ${total.toFixed(2)} ms`].join('\n') : s.adapter ? 'no timestamp queries on this adapter' : '–';
    m.spp = s.samples;
    m.rays = s.raysPerSecond > 0 ? `${(s.raysPerSecond / 1e6).toFixed(1)} M` : '–';
    m.image = s.width > 0 ? `${s.width}×${s.height}` : '–';
    m.scene = s.sceneName ? `${s.sceneName}\n${s.triangles.toLocaleString('en')} triangles · ${s.bvhNodes.toLocaleString('en')} BVH nodes` : '–';
    m.gpuMemory = s.adapter ? `${(s.gpuResources.bytes / 2 ** 20).toFixed(1)} MiB in ${s.gpuResources.buffers} buffers, ${s.gpuResources.textures} textures` : '–';
  }

  private addDepthBinding(): void {
    if (!this.debugFolder) return;
    this.depthBinding?.dispose();
    const max = Math.max(1, this.viewer.bvhMaxDepth);
    this.params.wireframeDepth = Math.min(this.params.wireframeDepth, max);
    this.depthBinding = this.debugFolder.addBinding(this.params, 'wireframeDepth', { label: `box depth (0–${max})`, min: 0, max, step: 1 });
    this.depthBinding.on('change', (e) => this.apply({ render: { wireframeDepth: e.value as number } }));
  }

  dispose(): void {
    this.pane.dispose();
  }

  private apply(changes: Parameters<Viewer['updateSettings']>[0]): void {
    if (this.syncing) return;
    this.viewer.updateSettings(changes).catch((e) => this.viewer.fail(e));
  }

  private applyHistory(): void {
    const p = this.params;
    this.apply({ render: { historyCap: p.unlimitedHistory ? 'unlimited' : p.historyCap } });
  }

  private applyTorch(): void {
    const p = this.params;
    this.apply({
      render: { torch: { enabled: p.torch, color: [p.torchColor.r, p.torchColor.g, p.torchColor.b], intensity: Math.max(0, p.torchIntensity), range: Math.max(1e-3, p.torchRange) } },
    });
  }
}
