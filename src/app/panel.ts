/**
 * The settings panel (Tweakpane): render settings, camera (field of view, movement, lens), torch, the
 * environment (scene's own, sky, HDR map, none), the selected material (material-panel.ts), what
 * the GPU is doing, and output.
 * Every change goes through the Viewer, which restarts accumulation when the change invalidates the
 * image. The render settings' bindings are derived from their schema entries (renderer/settings.ts),
 * and the viewer's own (samples per frame, resolution, field of view, the sky) from theirs
 * (viewer-settings.ts, through panel-settings.ts viewerBinding): label, limits, step and slider span
 * come from there, so the panel accepts what validation and links accept.
 * The numbers are the viewer's own measurements: frame rate and time on the wall clock, pass
 * times from GPU timestamp queries (where the adapter offers them), rays from the GPU's counters;
 * written with figures that fit their size (number-format.ts).
 *
 * Every control has a one-line tooltip; a control that does nothing for the scene and settings
 * shown (walk mode without a walk map, the denoiser's knobs in progressive mode) is disabled and
 * its tooltip says why (panel-settings.ts decides). The numbers and the output buttons sit in a
 * second pane below the settings, outside their scrolling, so they stay on screen.
 */
import { boundsDiagonal } from '../bvh/stats.ts';
import { Pane, type BladeApi, type ButtonApi, type FolderApi, type SliderInputBindingApi } from 'tweakpane';
import { formatSettingText, getAt, isValidValue, mergeSettings, parseSettingText, setAt, type PanelFolder, type SettingEntry, type SettingsPatch } from '../renderer/settings-schema.ts';
import { effectiveTorch, type RenderSettings } from '../renderer/settings.ts';
import { exposureChoice } from '../renderer/exposure.ts';
import { lookSettings } from '../renderer/looks.ts';
import { notApplicable, numberBindingLimits, PANEL_SETTINGS, settingTooltip, TOOLTIPS, unlimitedKey, viewerBinding, type PanelContext, type ViewerPanelKey } from './panel-settings.ts';
import { duration, significant, withUnit } from './number-format.ts';
import { fNumberForAperture, focalLengthForFov } from '../scene/lens.ts';
import type { MoveMode } from './camera-controller.ts';
import { VIEWER_DEFAULTS } from './viewer-settings.ts';
import type { Viewer } from './viewer.ts';
import type { ViewerDisplay } from './viewer-types.ts';
import { MaterialPanel } from './material-panel.ts';
import type { EnvironmentImage } from '../scene/environment.ts';
import { choiceOfEnvironment, DEFAULT_ENVIRONMENT_CHOICE, environmentOfChoice, type EnvironmentChoice, type EnvironmentChoiceKind } from './environment-choice.ts';

export interface PanelActions {
  screenshot(): void;
  exportExr(): void;
  copyLink(): void;
  /** Decodes an HDR panorama the user picked (in the scene worker). */
  decodeEnvironmentMap(file: File): Promise<EnvironmentImage>;
  /** Shows a problem in the page's message line (a file that is not an HDR image). */
  report(error: unknown): void;
}

/** Whether a debug view replaces the image (nothing is path traced then). */
const debugOnly = (r: RenderSettings) => r.debugView !== 'none' && r.debugLayout === 'replace';

const options = <T extends string>(values: readonly T[]) => Object.fromEntries(values.map((v) => [v, v])) as Record<T, T>;

/** Makes a switch over the setting types exhaustive: a new type fails to compile here until handled. */
function unreachable(spec: never): never {
  throw new Error(`unhandled setting type ${(spec as { type: string }).type}`);
}

/** What the 'showing' read-out says for each kind of image on the canvas. */
const DISPLAY_NAMES: Record<ViewerDisplay, string> = { frame: 'real-time frame', converged: 'still: progressive estimate', progressive: 'progressive estimate' };

/**
 * Adds a binding with Tweakpane parameters from a setting's entry (label, limits, step): the limits
 * bound what is accepted, typed values too, and the slider then covers `slider` where one is given
 * (it may be narrower than the limits, which typed values still reach).
 */
function addBound<T extends object, K extends keyof T & string>(folder: FolderApi, target: T, key: K, params: { label: string; min?: number; max?: number; step?: number; slider?: readonly [number, number] }) {
  const { slider, ...limits } = params;
  const binding = folder.addBinding(target, key, limits);
  if (slider && limits.min !== undefined && limits.max !== undefined) [(binding as unknown as SliderInputBindingApi).min, (binding as unknown as SliderInputBindingApi).max] = slider;
  return binding;
}

export class SettingsPanel {
  private readonly pane: Pane;
  private readonly params = {
    samplesPerFrame: VIEWER_DEFAULTS.samplesPerFrame,
    scale: VIEWER_DEFAULTS.scale,
    // The frame budget chooses the resolution (and samples per frame) until the user fixes one.
    autoScale: true,
    accumulate: VIEWER_DEFAULTS.accumulate,
    animate: VIEWER_DEFAULTS.animate,
    convergeWhenStill: VIEWER_DEFAULTS.convergeWhenStill,
    // Shown until a scene's camera gives the field of view.
    fov: 60,
    mode: 'fly' as MoveMode,
    // The thin lens: aperture radius and focus distance in scene units (aperture 0: a pinhole).
    aperture: 0,
    focus: 1,
  };
  /** The lens's f-number where the scene knows its unit size (a read-out). */
  private readonly lensMonitor = { fNumber: '' };
  private apertureBinding?: SliderInputBindingApi;
  private focusBinding?: SliderInputBindingApi;
  /** The render settings' panel values by setting id (a colour as {r, g, b}; 'auto' as 0). */
  private readonly settingParams: Record<string, unknown> = {};
  private depthBinding?: SliderInputBindingApi;
  private readonly monitor = { fps: 0, frame: '', gpu: '', spp: '', shows: '', rays: '', image: '', scene: '', gpuMemory: '', kernel: '', firstFrame: '' };
  /** The Environment folder's values; the map is the last HDR file opened (kept while another kind is shown). */
  private readonly environment: EnvironmentChoice = { ...DEFAULT_ENVIRONMENT_CHOICE };
  private environmentMap?: EnvironmentImage;
  /** The bindings shown only for one kind of environment. */
  private readonly environmentControls: Partial<Record<EnvironmentChoiceKind, BladeApi[]>> = {};
  private openMapButton?: ButtonApi;
  private readonly materialPanel: MaterialPanel;
  /** True while the panel takes values from the viewer: Tweakpane reports those as changes too. */
  private syncing = false;
  /** The resolution and auto switch as last taken from the viewer (showScale follows the budget's changes). */
  private shownScale = { scale: NaN, on: true };
  private scaleBindings: { refresh(): void }[] = [];
  /** The controls that may be disabled or carry a tooltip, by their TOOLTIPS key (a setting's id, or the panel's own key). */
  private readonly controls = new Map<string, BladeApi[]>();
  /** The controls disabled now (notApplicable gave a reason). */
  private readonly disabledIds = new Set<string>();
  /** The numbers and the output buttons: a pane of their own that does not scroll away with the settings. */
  private readonly numbersPane: Pane;

  constructor(
    container: HTMLElement,
    private readonly viewer: Viewer,
    actions: PanelActions,
  ) {
    const settingsBox = document.createElement('div');
    settingsBox.id = 'panel-settings';
    const numbersBox = document.createElement('div');
    numbersBox.id = 'panel-numbers';
    container.append(settingsBox, numbersBox);
    this.pane = new Pane({ container: settingsBox, title: 'Lantern' });
    this.numbersPane = new Pane({ container: numbersBox });
    this.read();
    const p = this.params;
    const render = this.pane.addFolder({ title: 'Render' });
    const bind = <K extends ViewerPanelKey & keyof typeof p>(folder: FolderApi, key: K) => addBound(folder, p, key, viewerBinding(key));
    this.control('samplesPerFrame', bind(render, 'samplesPerFrame').on('change', (e) => this.apply({ samplesPerFrame: e.value })));
    const autoScale = this.control(
      'autoScale',
      render.addBinding(p, 'autoScale', { label: 'auto resolution' }).on('change', (e) => {
        if (this.syncing) return;
        // Off: the resolution the budget had chosen stays, fixed; on: the budget takes over again.
        if (e.value) this.viewer.useFrameBudget().then(() => this.readFromViewer()).catch((error) => this.viewer.fail(error));
        else this.apply({ scale: this.viewer.budget.scale });
      }),
    );
    // The slider down to the budget's smallest step (1/32: a software adapter at a large canvas).
    const scale = this.control('scale', bind(render, 'scale').on('change', (e) => this.apply({ scale: e.value })));
    this.scaleBindings = [autoScale, scale];
    this.control('accumulate', bind(render, 'accumulate').on('change', (e) => this.apply({ accumulate: e.value })));
    this.control('animate', bind(render, 'animate').on('change', (e) => this.apply({ animate: e.value })));

    const camera = this.pane.addFolder({ title: 'Camera and torch' });
    this.control(
      'fov',
      bind(camera, 'fov').on('change', (e) => {
        if (this.syncing) return;
        viewer.setFieldOfView(e.value);
        // The same aperture is another f-number at another focal length.
        this.showFNumber();
      }),
    );
    // Walk is disabled (with the reason) where the scene has no walk map, so a choice never silently reverts.
    this.control(
      'mode',
      camera.addBinding(p, 'mode', { label: 'movement', options: { walk: 'walk', fly: 'fly' } }).on('change', (e) => {
        if (this.syncing) return;
        if (!viewer.setMoveMode(e.value)) {
          p.mode = viewer.controller?.mode ?? 'fly';
          this.pane.refresh();
        }
      }),
    );

    this.addLensBindings(camera);

    const environment = this.addEnvironmentFolder(container, actions);
    this.materialPanel = new MaterialPanel(this.pane, viewer, actions.report);

    const folders: Record<PanelFolder, FolderApi> = {
      render,
      camera,
      environment,
      exposure: this.addExposureFolder(),
      denoise: this.pane.addFolder({ title: 'Denoising (real time)' }),
      hybrid: this.pane.addFolder({ title: 'Hybrid recipe', expanded: false }),
      debug: this.pane.addFolder({ title: 'Debug views', expanded: false }),
    };
    // Before the filters' own settings: whether a still view hands over to the exact progressive estimate.
    this.control('convergeWhenStill', bind(folders.denoise, 'convergeWhenStill').on('change', (e) => this.apply({ convergeWhenStill: e.value })));
    for (const entry of PANEL_SETTINGS) this.addSettingBinding(folders[entry.spec.panel!.folder], entry);
    this.fitDepthSlider();

    // The output buttons first, then the numbers a user watches most, then the details: the pane's
    // box may be shorter than its content (the page's style), and what comes first stays in view.
    const output = this.numbersPane.addFolder({ title: 'Output' });
    output.addButton({ title: 'Screenshot (PNG)' }).on('click', () => actions.screenshot());
    output.addButton({ title: 'Radiance (EXR)' }).on('click', () => actions.exportExr());
    output.addButton({ title: 'Copy link to this view' }).on('click', () => actions.copyLink());

    const numbers = this.numbersPane.addFolder({ title: 'GPU' });
    const m = this.monitor;
    numbers.addBinding(m, 'fps', { label: 'frames/s', readonly: true, view: 'graph', min: 0, max: 120 });
    numbers.addBinding(m, 'frame', { label: 'frame', readonly: true });
    numbers.addBinding(m, 'spp', { label: 'samples/pixel', readonly: true });
    numbers.addBinding(m, 'rays', { label: 'rays/s', readonly: true });
    numbers.addBinding(m, 'shows', { label: 'showing', readonly: true });
    numbers.addBinding(m, 'image', { label: 'image', readonly: true });
    numbers.addBinding(m, 'gpu', { label: 'GPU passes', readonly: true, multiline: true, rows: 10 });
    numbers.addBinding(m, 'scene', { label: 'scene', readonly: true, multiline: true, rows: 2 });
    numbers.addBinding(m, 'gpuMemory', { label: 'GPU memory', readonly: true });
    numbers.addBinding(m, 'kernel', { label: 'kernel', readonly: true });
    numbers.addBinding(m, 'firstFrame', { label: 'Play to first frame', readonly: true });
    this.showApplicability();
  }

  /** Registers a control under its TOOLTIPS key: it gets its tooltip now, and is disabled where it does not apply (showApplicability). */
  private control<T extends BladeApi>(id: string, blade: T): T {
    const list = this.controls.get(id) ?? [];
    list.push(blade);
    this.controls.set(id, list);
    return blade;
  }

  /** What the applicability rules need to know about the scene shown. */
  private context(): PanelContext {
    const render = this.viewer.settings.render;
    const scene = this.viewer.scene?.prepared.scene;
    const torch = effectiveTorch(scene, { ...render.torch, enabled: true });
    return {
      render,
      hasTorch: torch !== undefined && torch.intensity > 0,
      canWalk: this.viewer.controller?.canWalk ?? false,
      moving: this.viewer.moving,
      tileGrid: !!scene?.walkMap && !!scene.metersPerUnit,
      webgl2: this.viewer.backend.kind === 'webgl2',
    };
  }

  /** Disables the controls that do nothing for the scene and settings shown, with the reason as their tooltip; the others get their own tooltip. */
  private showApplicability(): void {
    const c = this.context();
    // The torch switch shows whether a torch lights the image, which an intensity set just now may have changed.
    const torchEntry = PANEL_SETTINGS.find((e) => e.id === 'torch.enabled');
    const torchShown = torchEntry && this.shownValue(torchEntry);
    if (torchEntry && this.settingParams[torchEntry.id] !== torchShown) {
      this.settingParams[torchEntry.id] = torchShown;
      const wasSyncing = this.syncing;
      this.syncing = true;
      try {
        this.pane.refresh();
      } finally {
        this.syncing = wasSyncing;
      }
    }
    for (const [id, blades] of this.controls) {
      const reason = notApplicable(id, c);
      const entry = PANEL_SETTINGS.find((e) => e.id === id);
      const tip = entry ? settingTooltip(entry) : TOOLTIPS[id];
      if (reason) this.disabledIds.add(id);
      else this.disabledIds.delete(id);
      for (const blade of blades) {
        if (blade.disabled !== (reason !== undefined)) blade.disabled = reason !== undefined;
        const title = reason ? `${reason} (${tip})` : (tip ?? '');
        if (blade.element.title !== title) blade.element.title = title;
      }
    }
  }

  /**
   * Depth of field in the Camera folder: aperture radius and focus distance (scene units, sliders
   * spanning the scene's size), the f-number they make where the scene knows its unit, and a button
   * that focuses on what lies at the image centre. Each change restarts the image (Viewer.setLens).
   */
  private addLensBindings(folder: FolderApi): void {
    const p = this.params;
    const apply = () => {
      if (this.syncing) return;
      try {
        this.viewer.setLens({ apertureRadius: p.aperture, focusDistance: p.focus });
      } catch {
        // A value the lens refuses (a focus distance of 0 typed in): back to the viewer's.
        this.readFromViewer();
        return;
      }
      this.showFNumber();
    };
    // The limits accept any lens (typed values too); the sliders' spans are fitted to the scene (fitLensSliders).
    const aperture = folder.addBinding(p, 'aperture', { label: 'aperture radius', min: 0, max: 1e9, step: 1e-4 });
    aperture.element.title = 'Radius of the thin lens in scene units: 0 is a pinhole (everything sharp); larger blurs what lies off the focus distance more.';
    aperture.on('change', apply);
    const focus = folder.addBinding(p, 'focus', { label: 'focus distance', min: 1e-4, max: 1e12, step: 1e-4 });
    focus.element.title = 'Distance along the view to the plane in focus, scene units.';
    focus.on('change', apply);
    this.apertureBinding = aperture as unknown as SliderInputBindingApi;
    this.focusBinding = focus as unknown as SliderInputBindingApi;
    folder.addBinding(this.lensMonitor, 'fNumber', { label: 'f-number', readonly: true });
    folder.addButton({ title: 'Focus on the image centre' }).on('click', () => {
      const depth = this.viewer.defaultFocusDistance();
      if (depth === undefined) return;
      this.viewer.setFocusDistance(depth);
      this.readFromViewer();
    });
    this.fitLensSliders();
  }

  /** Lens sliders sized to the scene: apertures up to a twentieth of its diagonal, focus up to twice the diagonal (and the current values). */
  private fitLensSliders(): void {
    const scene = this.viewer.scene?.prepared;
    const size = scene ? Math.max(boundsDiagonal(scene.bvh), 1e-3) : 1;
    const p = this.params;
    if (this.apertureBinding) [this.apertureBinding.min, this.apertureBinding.max] = [0, Math.max(size / 20, p.aperture)];
    if (this.focusBinding) [this.focusBinding.min, this.focusBinding.max] = [Math.min(size / 1000, p.focus), Math.max(2 * size, p.focus)];
    this.showFNumber();
  }

  private showFNumber(): void {
    const metersPerUnit = this.viewer.scene?.prepared.scene.metersPerUnit;
    const p = this.params;
    this.lensMonitor.fNumber = p.aperture <= 0 ? 'pinhole' : metersPerUnit ? `f/${fNumberForAperture(p.aperture, metersPerUnit, p.fov).toPrecision(3)} (full-frame ${focalLengthForFov(p.fov).toFixed(0)} mm)` : '– (scene size unknown)';
  }

  /**
   * The Environment folder: what lights the scene from outside. Every change relights the scene
   * through the viewer at once (no reload; the image restarts). The HDR file is decoded in the
   * scene worker, so that a large panorama does not stall the page.
   */
  private addEnvironmentFolder(container: HTMLElement, actions: PanelActions): FolderApi {
    const e = this.environment;
    const folder = this.pane.addFolder({ title: 'Environment' });
    folder.element.title =
      'What lights the scene from outside: its own environment, the sun and sky (Hosek–Wilkie), an HDR panorama (.hdr, .exr) or nothing. ' +
      'A copied link keeps the sky (sky=elevation,azimuth,turbidity and env-intensity); an HDR file opened from this computer cannot be linked: open it again.';
    const mapInput = document.createElement('input');
    mapInput.type = 'file';
    mapInput.id = 'open-environment';
    mapInput.accept = '.hdr,.exr';
    mapInput.hidden = true;
    container.append(mapInput);
    mapInput.addEventListener('change', () => {
      const file = mapInput.files?.[0];
      mapInput.value = '';
      if (!file) return;
      actions
        .decodeEnvironmentMap(file)
        .then((image) => {
          this.environmentMap = image;
          e.kind = 'map';
          this.pane.refresh();
          this.applyEnvironment();
        })
        .catch((error) => {
          actions.report(error);
          this.showViewerEnvironment();
        });
    });
    // No file picked for a map that has none: the folder goes back to what lights the scene.
    mapInput.addEventListener('cancel', () => this.showViewerEnvironment());

    const kinds: Record<string, EnvironmentChoiceKind> = { "scene's own": 'scene', 'sun and sky': 'sky', 'HDR map': 'map', none: 'none' };
    folder.addBinding(e, 'kind', { label: 'light from', options: kinds }).on('change', () => {
      if (this.syncing) return;
      // An HDR map with no file yet: ask for one; the scene keeps its light until it is decoded.
      if (e.kind === 'map' && !this.environmentMap) mapInput.click();
      this.applyEnvironment();
    });
    const onChange = () => this.applyEnvironment();
    // The sky's limits are its settings' (viewer-settings.ts): what a link's sky= accepts.
    this.environmentControls.sky = [
      addBound(folder, e, 'elevation', viewerBinding('sunElevation')).on('change', onChange),
      addBound(folder, e, 'azimuth', viewerBinding('sunAzimuth')).on('change', onChange),
      addBound(folder, e, 'turbidity', viewerBinding('turbidity')).on('change', onChange),
      addBound(folder, e, 'skyIntensity', viewerBinding('skyIntensity')).on('change', onChange),
    ];
    this.openMapButton = folder.addButton({ title: 'Open HDR…' }).on('click', () => mapInput.click());
    this.environmentControls.map = [
      this.openMapButton,
      folder.addBinding(e, 'mapIntensity', { label: 'map intensity', min: 0, max: 10, step: 0.01 }).on('change', onChange),
      folder.addBinding(e, 'rotation', { label: 'rotation (°)', min: -180, max: 180, step: 1 }).on('change', onChange),
    ];
    this.showEnvironmentControls();
    return folder;
  }

  /** Takes the environment the viewer has into the folder (a map chosen but never opened is undone). */
  private showViewerEnvironment(): void {
    if (this.environment.kind !== 'map' || this.environmentMap) return;
    this.syncing = true;
    try {
      Object.assign(this.environment, choiceOfEnvironment(this.viewer.environment, this.environment));
      this.showEnvironmentControls();
      this.pane.refresh();
    } finally {
      this.syncing = false;
    }
  }

  /** Shows the controls of the chosen kind only. */
  private showEnvironmentControls(): void {
    for (const [kind, controls] of Object.entries(this.environmentControls)) for (const c of controls ?? []) c.hidden = kind !== this.environment.kind;
    if (this.openMapButton) this.openMapButton.title = this.environmentMap ? `Open HDR… (${this.environmentMap.name})` : 'Open HDR…';
  }

  private applyEnvironment(): void {
    this.showEnvironmentControls();
    if (this.syncing) return;
    const e = this.environment;
    // A map chosen before its file is decoded changes nothing yet.
    if (e.kind === 'map' && !this.environmentMap) return;
    this.viewer.setEnvironment(environmentOfChoice(e, this.environmentMap)).catch((error) => this.viewer.fail(error));
  }

  /** Takes the viewer's current settings and camera into the panel (after a scene switch or a link). */
  readFromViewer(): void {
    this.syncing = true;
    try {
      this.read();
      // The depth slider spans the scene's BVH depth; the lens sliders its size.
      this.fitDepthSlider();
      this.fitLensSliders();
      this.showEnvironmentControls();
      this.pane?.refresh();
      if (this.controls.size > 0) this.showApplicability();
    } finally {
      this.syncing = false;
    }
  }

  private read(): void {
    const p = this.params;
    const s = this.viewer.settings;
    p.samplesPerFrame = s.samplesPerFrame;
    const budget = this.viewer.budget;
    p.autoScale = budget.on;
    p.scale = budget.scale;
    this.shownScale = { scale: budget.scale, on: budget.on };
    p.accumulate = s.accumulate;
    p.animate = s.animate;
    p.convergeWhenStill = s.convergeWhenStill;
    this.readExposure();
    Object.assign(this.environment, choiceOfEnvironment(this.viewer.environment, this.environment));
    if (this.environment.kind === 'map' && this.viewer.environment?.kind === 'map') this.environmentMap = this.viewer.environment.image;
    const c = this.viewer.controller;
    if (c) {
      p.fov = c.vfovDegrees;
      p.mode = c.mode;
      p.aperture = c.lens?.apertureRadius ?? 0;
      // A pinhole shows where a lens would focus: what lies at the image centre.
      p.focus = c.lens?.focusDistance ?? this.viewer.defaultFocusDistance() ?? p.focus;
    }
    for (const entry of PANEL_SETTINGS) {
      const value = this.shownValue(entry);
      const spec = entry.spec;
      if (spec.type === 'color') {
        const [r, g, b] = value as readonly [number, number, number];
        this.settingParams[entry.id] = { r, g, b };
      } else if (spec.type === 'number-or-auto') this.settingParams[entry.id] = value === 'auto' ? spec.min : value;
      else if (spec.type === 'integer-or-unlimited') {
        this.settingParams[unlimitedKey(entry.id)] = value === 'unlimited';
        // The number keeps the last cap while 'unlimited' is ticked, ready for unticking.
        if (value !== 'unlimited') this.settingParams[entry.id] = value;
        else this.settingParams[entry.id] ??= spec.default;
      } else if (spec.type === 'numbers') this.settingParams[entry.id] = formatSettingText(spec, value);
      else this.settingParams[entry.id] = value;
    }
  }

  /**
   * What the panel shows for a setting: its value, or for a torch parameter left to the scene the
   * scene's own (so the panel shows the torch that lights the image).
   */
  private shownValue(entry: SettingEntry): unknown {
    const render = this.viewer.settings.render;
    const value = getAt(render, entry.path);
    const scene = this.viewer.scene?.prepared;
    // The switch is ticked only where a torch lights the image: a scene without one shows it off (and disabled).
    if (entry.id === 'torch.enabled') return render.torch.enabled && (effectiveTorch(scene?.scene, render.torch)?.intensity ?? 0) > 0;
    if (value !== undefined || entry.path[0] !== 'torch') return value ?? entry.spec.default;
    const torch = effectiveTorch(scene?.scene, render.torch);
    const key = entry.path[1];
    if (key === 'color') return torch?.color ?? [1, 1, 1];
    if (key === 'intensity') return torch?.intensity ?? 0;
    if (key === 'range') return torch?.range ?? Math.max((scene ? boundsDiagonal(scene.bvh) : 1) / 2, 1e-3);
    return entry.spec.default;
  }

  /** The value a setting's binding now holds, in the setting's own terms. */
  private boundValue(entry: SettingEntry): unknown {
    const v = this.settingParams[entry.id];
    const spec = entry.spec;
    switch (spec.type) {
      case 'color': {
        const { r, g, b } = v as { r: number; g: number; b: number };
        return [r, g, b];
      }
      case 'number-or-auto':
        return (v as number) <= spec.min ? 'auto' : v;
      case 'integer-or-unlimited':
        return this.settingParams[unlimitedKey(entry.id)] ? 'unlimited' : v;
      case 'numbers': {
        // Typed as text ('30,120,3'); what does not parse is refused when applied.
        const parsed = parseSettingText(spec, String(v));
        return parsed.ok ? parsed.value : undefined;
      }
      case 'text':
      case 'integer':
      case 'number':
      case 'boolean':
      case 'choice':
        return v;
      default:
        return unreachable(spec);
    }
  }

  private addSettingBinding(folder: FolderApi, entry: SettingEntry): void {
    const spec = entry.spec;
    const hint = spec.panel!;
    const onChange = () => this.applySetting(entry);
    switch (spec.type) {
      case 'boolean':
        this.control(entry.id, folder.addBinding(this.settingParams, entry.id, { label: hint.label }).on('change', onChange));
        return;
      case 'choice':
        this.control(entry.id, folder.addBinding(this.settingParams, entry.id, { label: hint.label, options: options(spec.values) }).on('change', onChange));
        return;
      case 'color':
        this.control(entry.id, folder.addBinding(this.settingParams, entry.id, { label: hint.label, color: { type: 'float' } }).on('change', onChange));
        return;
      case 'numbers':
      case 'text':
        this.control(entry.id, folder.addBinding(this.settingParams, entry.id, { label: hint.label }).on('change', onChange));
        return;
      case 'integer':
      case 'number':
      case 'number-or-auto':
      case 'integer-or-unlimited': {
        const limits = numberBindingLimits(entry);
        // The slider's span is apart from the limits: it may be narrower, while typed values reach the limits.
        const binding = this.control(entry.id, addBound(folder, this.settingParams, entry.id, { label: hint.label, ...limits }));
        binding.on('change', onChange);
        // The depth slider reaches the scene's own BVH depth (see readFromViewer).
        if (entry.id === 'wireframeDepth' && limits.min !== undefined && limits.max !== undefined) this.depthBinding = binding as unknown as SliderInputBindingApi;
        if (spec.type === 'integer-or-unlimited') this.control(entry.id, folder.addBinding(this.settingParams, unlimitedKey(entry.id), { label: hint.unlimitedLabel ?? 'unlimited' }).on('change', onChange));
        return;
      }
      default:
        unreachable(spec);
    }
  }

  // ---- Exposure and tone (issue #16): automatic or manual exposure, and the Doom-like look. ----
  // The exposure setting may be left to the scene (automatic for the game maps), a number of stops or
  // 'auto', so it is drawn here rather than from its schema entry: a checkbox for automatic and a
  // slider for manual stops. The compensation, adaptation time and tone curve follow from the schema.

  private readonly exposureParams = { auto: false, stops: 0 };
  private exposureStopsBinding?: BladeApi;

  private addExposureFolder(): FolderApi {
    const folder = this.pane.addFolder({ title: 'Exposure and tone' });
    const e = this.exposureParams;
    const look = folder.addButton({ title: 'Doom-like look' });
    look.element.title = "Automatic exposure, a compensation and a tone curve that resemble the game's brightness, and the scene's own torch.";
    look.on('click', () => this.apply({ render: lookSettings('doom') as Partial<RenderSettings> }));
    const auto = folder.addBinding(e, 'auto', { label: 'automatic' });
    auto.element.title = "Eye adaptation: the exposure follows the image's average brightness (log-average luminance), over the adaptation time. On by default for Doom and Wolfenstein maps, off for reference scenes.";
    auto.on('change', () => {
      this.showExposureControls();
      if (!this.syncing) this.apply({ render: { exposureStops: e.auto ? 'auto' : e.stops } });
    });
    const stops = folder.addBinding(e, 'stops', { label: 'exposure (stops)', min: -64, max: 64, step: 0.1 });
    [(stops as unknown as SliderInputBindingApi).min, (stops as unknown as SliderInputBindingApi).max] = [-8, 8];
    stops.element.title = "Manual exposure: stops over the scene's own (each stop doubles the brightness).";
    stops.on('change', () => {
      if (!this.syncing) this.apply({ render: { exposureStops: e.stops } });
    });
    this.exposureStopsBinding = stops;
    return folder;
  }

  /** The exposure as the viewer has it: automatic where the setting or the scene's kind says so. */
  private readExposure(): void {
    const render = this.viewer.settings.render;
    const e = this.exposureParams;
    e.auto = exposureChoice(this.viewer.scene?.prepared.scene, 0, render).kind === 'auto';
    if (typeof render.exposureStops === 'number') e.stops = render.exposureStops;
    this.showExposureControls();
  }

  private showExposureControls(): void {
    if (this.exposureStopsBinding) this.exposureStopsBinding.disabled = this.exposureParams.auto;
  }
  // ---- End of exposure and tone. ----

  /**
   * The resolution control shows the scale that renders: the frame budget's as it changes it, or the
   * user's once fixed. Only a change on the viewer's side is taken (a slider being dragged is not
   * pulled back while the viewer applies it).
   */
  private showScale(): void {
    const { scale, on } = this.viewer.budget;
    if (scale === this.shownScale.scale && on === this.shownScale.on) return;
    this.shownScale = { scale, on };
    this.syncing = true;
    try {
      this.params.scale = scale;
      this.params.autoScale = on;
      for (const b of this.scaleBindings) b.refresh();
    } finally {
      this.syncing = false;
    }
  }

  /** Refreshes the numbers and the resolution control (called on every frame; Tweakpane redraws monitors on its own interval). */
  showStats(): void {
    this.showScale();
    this.materialPanel.update();
    const s = this.viewer.stats;
    const m = this.monitor;
    m.fps = s.framesPerSecond;
    m.frame = s.frameMs > 0 ? duration(s.frameMs) : '–';
    const total = s.gpuPasses.reduce((t, p) => t + p.ms, 0);
    m.gpu = s.gpuPasses.length > 0 ? [...s.gpuPasses.map((p) => `${p.name}: ${duration(p.ms)}`), `total: ${duration(total)}`].join('\n') : s.adapter ? 'no timestamp queries on this adapter' : '–';
    // A debug view that replaces the image traces no paths: its frames are not samples of the image.
    m.spp = debugOnly(this.viewer.settings.render) ? '– (debug view)' : String(s.samples);
    m.shows = DISPLAY_NAMES[s.display];
    m.rays = s.raysPerSecond > 0 ? withUnit(s.raysPerSecond, '').trim() : '–';
    m.image = s.width > 0 ? `${s.width}×${s.height}` : '–';
    m.scene = s.sceneName ? `${s.sceneName}\n${s.triangles.toLocaleString('en')} triangles · ${s.bvhNodes.toLocaleString('en')} BVH nodes` : '–';
    m.gpuMemory = s.adapter ? `${significant(s.gpuResources.bytes / 2 ** 20)} MiB in ${s.gpuResources.buffers} buffers, ${s.gpuResources.textures} textures` : '–';
    m.kernel = s.adapter ? (s.kernel === 'specialised' ? 'specialised to the scene' : 'generic') : '–';
    m.firstFrame = s.firstFrameMs !== undefined ? duration(s.firstFrameMs) : '–';
  }

  private fitDepthSlider(): void {
    if (!this.depthBinding) return;
    const max = Math.max(1, this.viewer.bvhMaxDepth);
    this.depthBinding.max = max;
    this.depthBinding.label = `box depth (0–${max})`;
  }

  dispose(): void {
    this.pane.dispose();
    this.numbersPane.dispose();
  }

  private apply(changes: Parameters<Viewer['updateSettings']>[0]): void {
    if (this.syncing) return;
    this.viewer
      .updateSettings(changes)
      // What applies may have changed with it (the denoiser's knobs once both filters are off). The
      // values are not read back: later changes may still be queued behind this one.
      .then(() => this.showApplicability())
      .catch((e) => this.viewer.fail(e));
  }

  /**
   * Applies a setting the user changed. A value the schema refuses (a torch range of 0) is not applied:
   * the panel goes back to the viewer's. A torch parameter goes with the torch's other shown values,
   * so that giving a torch-less scene an intensity also gives it the range the panel shows.
   */
  private applySetting(entry: SettingEntry): void {
    if (this.syncing) return;
    const group = entry.path.length > 1 ? PANEL_SETTINGS.filter((e) => e.path.length > 1 && e.path[0] === entry.path[0]) : [entry];
    if (!group.every((e) => isValidValue(e.spec, this.boundValue(e)))) {
      this.readFromViewer();
      return;
    }
    const patch: Record<string, unknown> = {};
    // A disabled switch shows what applies (the torch off where there is none), not the setting: the setting is sent unchanged.
    for (const e of group) setAt(patch, e.path, this.disabledIds.has(e.id) ? getAt(this.viewer.settings.render, e.path) : this.boundValue(e));
    // Only the changed top-level setting goes: the viewer applies changes in order, after pipelines
    // compile, so its settings may not hold the previous change yet and must not be sent back whole.
    const key = entry.path[0] as keyof RenderSettings;
    const current = this.viewer.settings.render[key];
    const value = entry.path.length > 1 ? mergeSettings(current, patch[key] as SettingsPatch<typeof current>) : patch[key];
    this.apply({ render: { [key]: value } });
  }
}
