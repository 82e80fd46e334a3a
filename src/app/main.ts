/**
 * The page: scene picker, opening files of the registry's formats (file picker and drag-and-drop)
 * with a map picker for files of several scenes (WADs), Play,
 * the settings panel, and the canvas. Scenes load in a Web Worker with a progress bar; nothing
 * touches the GPU before Play. URL parameters (view-params.ts) choose the scene, camera and
 * settings, so a copied link restores a view.
 *
 * Clicks on the canvas select (Esc or empty space deselects) and Alt-clicks focus the lens
 * (input.ts); the panel's Material folder edits what is selected, and links carry the edits.
 *
 * Test hook: `window.lantern` exposes the viewer's state, sample count, scene, camera, lens,
 * selection and live GPU resources, and reads the estimate with its sample count; the canvas
 * carries data-state and data-samples, so scripts can wait for frames, and data-first-frame-ms (the
 * milliseconds from the first Play to its first frame, also in the panel's GPU folder).
 */
import { LanternError } from '../errors.ts';
import { BUILTIN_SCENES, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { acceptedExtensions, describeFormats, SNIFF_BYTES, sortFiles } from '../loaders/registry.ts';
import type { Pose } from './camera-controller.ts';
import { Input } from './input.ts';
import { SettingsPanel } from './panel.ts';
import { pathRelativeTo, walkEntries, type PathedFile, type WalkEntry } from './dropped-files.ts';
import { environmentOfLink } from './environment-choice.ts';
import { SceneLoader } from './scene-loader.ts';
import type { SceneRequest } from './scene-request.ts';
import { formatViewParams, linkedRenderSettings, parseViewParams, type SceneLocation, type ViewParams } from './view-params.ts';
import { describeError, Viewer, type BudgetState, type FrameProgress } from './viewer.ts';
import type { ResourceCount } from '../gpu/resource-count.ts';
import type { ThinLens } from '../scene/types.ts';
import { legendGradientCss, type DebugLegend } from '../renderer/debug-legend.ts';

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const canvas = $<HTMLCanvasElement>('view');
const sceneSelect = $<HTMLSelectElement>('scene');
const fileInput = $<HTMLInputElement>('open-file');
const folderInput = $<HTMLInputElement>('open-folder');
const mapPicker = $<HTMLLabelElement>('map-picker');
const mapSelect = $<HTMLSelectElement>('map');
const playButton = $<HTMLButtonElement>('play');
const progress = $<HTMLProgressElement>('progress');
const stats = $<HTMLSpanElement>('stats');
const message = $<HTMLParagraphElement>('message');
const dropZone = $<HTMLDivElement>('drop-zone');
const legend = $<HTMLDivElement>('legend');

/** The option of the scene picker that stands for a scene opened from a file. */
const FILE_OPTION = '__file__';

function showMessage(text: string, kind: 'info' | 'warning' | 'error'): void {
  message.hidden = false;
  message.dataset.kind = kind;
  message.textContent = text;
}
function clearMessage(): void {
  message.hidden = true;
  message.textContent = '';
}

const { view: linked, problems } = parseViewParams(new URLSearchParams(location.search));
const viewer = new Viewer(canvas, { onChange: showViewer, onMessage: showMessage });
const loader = new SceneLoader();
let panel: SettingsPanel | undefined;
/** Where the current scene came from (for links); undefined for files opened from this computer. */
let current: SceneLocation | undefined;
let loading: string | undefined;
/** Where the open file set was served from (links can name it), or undefined for local files. */
let fileSource: { format: string; urls: readonly string[]; skill?: number } | undefined;
let loadToken = 0;
/** Scenes shown so far (the test hook: an environment change must not load the scene again). */
let sceneLoads = 0;

// What the picker offers and the drop zone says come from the registry, like everything else about formats.
fileInput.accept = acceptedExtensions();
$('open-label').title = `Open ${describeFormats()}; pick the files a scene needs together (an IWAD with its PWADs, a .gltf with its .bin and textures); you can also drop files or a folder on the page`;
$('open-folder-label').title = 'Open a folder holding a scene (a .gltf with its .bin and its textures, in subfolders too)';
dropZone.textContent = `Drop ${describeFormats()}: a WAD stack (IWAD and PWADs together), a .glb, or a .gltf with its .bin and textures (or their folder)`;

for (const name of builtinSceneNames()) {
  const option = document.createElement('option');
  option.value = name;
  option.textContent = name;
  option.title = BUILTIN_SCENES[name].description;
  sceneSelect.append(option);
}

function showViewer(v: Viewer): void {
  const s = v.stats;
  canvas.dataset.state = v.state;
  canvas.dataset.samples = String(s.samples);
  if (s.firstFrameMs !== undefined) canvas.dataset.firstFrameMs = s.firstFrameMs.toFixed(1);
  playButton.textContent = v.state === 'playing' ? 'Pause' : 'Play';
  playButton.disabled = v.state === 'starting' || v.state === 'failed' || !navigator.gpu || !v.scene;
  const hidden = document.hidden && v.state === 'playing' ? ' · paused while the tab is hidden' : '';
  const budget = v.budgetText(true);
  stats.textContent =
    loading !== undefined ? `loading: ${loading}…`
    : v.state === 'idle' ? 'press Play to start'
    : v.state === 'starting' ? 'starting the GPU…'
    : `${s.samples} spp · ${s.framesPerSecond.toFixed(1)} fps · ${s.width}×${s.height} · ${s.adapter}${budget ? ` · ${budget}` : ''}${hidden}`;
  // The budget's short line (it changes only with its choice, so the header does not reflow and resize the canvas every frame); the tooltip has it all.
  stats.title = s.budget;
  panel?.showStats();
  showLegend(v.legend);
}

/** The debug view's legend under the image: what it shows and, for scalar views, the colour scale with its numbers. */
function showLegend(l: DebugLegend | undefined): void {
  legend.hidden = !l;
  if (!l) return;
  legend.querySelector('.label')!.textContent = l.label;
  const bar = legend.querySelector<HTMLDivElement>('.bar')!;
  bar.hidden = !l.scale;
  if (l.scale) {
    bar.style.background = legendGradientCss();
    bar.querySelector('.min')!.textContent = formatScale(l.scale.min);
    bar.querySelector('.max')!.textContent = `${formatScale(l.scale.max)}${l.scale.auto ? ' (image max)' : ''}`;
  }
}

const formatScale = (v: number) => (Number.isInteger(v) ? String(v) : v.toFixed(1));

// ---- loading scenes ----

/** Loads a scene in the worker and shows it; a failure leaves the current scene as it was. */
async function show(request: SceneRequest, where: SceneLocation | undefined, view: ViewParams = {}): Promise<void> {
  const token = ++loadToken;
  progress.hidden = false;
  progress.value = 0;
  loading = 'starting';
  showViewer(viewer);
  try {
    const loaded = await loader.load(request, (stage, fraction) => {
      if (token !== loadToken) return;
      progress.value = fraction;
      loading = stage;
      showViewer(viewer);
    });
    if (token !== loadToken) return;
    const { pose, mode, fovDegrees, apertureRadius, focusDistance } = view;
    await viewer.setScene(loaded, { pose, mode, fovDegrees, apertureRadius, focusDistance });
    if (view.torch) await viewer.updateSettings({ render: { torch: { ...viewer.settings.render.torch, ...view.torch } } });
    current = where;
    // The link's problems again (this warning replaces the line that named them), with the material
    // edits that do not fit the scene.
    const ignored = [...(view === linked ? problems : []), ...(view.materials ? await viewer.applyMaterialOverrides(view.materials) : [])];
    sceneLoads++;
    panel?.readFromViewer();
    // Each warning once (a texture missing from ten materials is one problem), one per line.
    const warnings = [...new Set([...loaded.warnings, ...ignored.map((p) => `ignored in the link: ${p}`)])];
    if (warnings.length > 0) showMessage([`${loaded.prepared.scene.name}: ${warnings.length === 1 ? 'a warning' : `${warnings.length} warnings`}`, ...warnings.map((w) => `· ${w}`)].join('\n'), 'warning');
  } catch (e) {
    if (token === loadToken) showMessage(describeError(e), 'error');
  } finally {
    if (token === loadToken) {
      loading = undefined;
      progress.hidden = true;
      showViewer(viewer);
    }
  }
}

function showBuiltin(name: string, view: ViewParams = {}): Promise<void> {
  sceneSelect.value = name;
  mapPicker.hidden = true;
  return show({ kind: 'builtin', name }, { kind: 'builtin', name }, view);
}

/** The file-scene entry of the scene picker, labelled with what was opened. */
function markFileScene(label: string): void {
  let option = sceneSelect.querySelector<HTMLOptionElement>(`option[value="${FILE_OPTION}"]`);
  if (!option) {
    option = document.createElement('option');
    option.value = FILE_OPTION;
    sceneSelect.append(option);
  }
  option.textContent = label;
  sceneSelect.value = FILE_OPTION;
}

/**
 * Opens files picked or dropped (or served): the registry sorts them into one scene's files (a
 * WAD stack, IWAD first) and siblings (a glTF's buffers and textures); a set of several scenes
 * (a WAD's maps) gets a map picker, a set of one is shown at once.
 */
async function openFiles(files: readonly PathedFile[], where?: { urls: readonly string[]; part?: string; skill?: number }, view: ViewParams = {}): Promise<void> {
  try {
    const heads = await Promise.all(files.map(async ({ file, path }) => ({ file, path, name: file.name, head: new Uint8Array(await file.slice(0, SNIFF_BYTES).arrayBuffer()) })));
    const { format, main, siblings } = sortFiles(heads);
    const baseUrl = where?.urls[0] ? new URL(where.urls[0], location.href).href : undefined;
    // Siblings are named from the main file's folder, the way a glTF's URIs name them.
    const mainPath = main[0]?.path ?? '';
    const beside = siblings.map((f) => ({ file: f.file, path: pathRelativeTo(mainPath, f.path) }));
    const summary = await loader.openFiles(format.id, main.map((f) => f.file), beside, baseUrl);
    fileSource = where ? { format: format.id, urls: where.urls, ...(where.skill !== undefined ? { skill: where.skill } : {}) } : undefined;
    markFileScene(summary.description);
    if (summary.parts.length === 0) {
      mapPicker.hidden = true;
      await showPart(undefined, view);
      return;
    }
    mapSelect.replaceChildren(
      ...summary.parts.map((m) => {
        const option = document.createElement('option');
        option.value = m.name;
        option.textContent = m.loadable ? m.name : `${m.name} (${m.note ?? 'not supported'})`;
        option.disabled = !m.loadable;
        return option;
      }),
    );
    const playable = summary.parts.filter((m) => m.loadable);
    const wanted = where?.part && playable.some((m) => m.name === where.part) ? where.part : playable[0]!.name;
    if (where?.part && wanted !== where.part) showMessage(`${summary.description} has no ${format.part?.noun ?? 'part'} ${where.part}; showing ${wanted}`, 'warning');
    mapSelect.value = wanted;
    mapPicker.hidden = false;
    await showPart(wanted, view);
  } catch (e) {
    showMessage(describeError(e), 'error');
    // The picker goes back to what is still shown.
    if (current?.kind === 'builtin') sceneSelect.value = current.name;
  }
}

/** A scene of the open file set: a map of a WAD, or (part undefined) the set's only scene. */
function showPart(part: string | undefined, view: ViewParams = {}): Promise<void> {
  const where: SceneLocation | undefined = fileSource ? { kind: 'files', ...fileSource, ...(part ? { part } : {}) } : undefined;
  return show({ kind: 'part', ...(part ? { part } : {}), ...(fileSource?.skill !== undefined ? { skill: fileSource.skill } : {}) }, where, view);
}

/** Files the server offers (`lantern view` serves the files named on its command line). */
async function fetchFiles(urls: readonly string[]): Promise<File[]> {
  return Promise.all(
    urls.map(async (url) => {
      let response: Response;
      try {
        response = await fetch(url);
      } catch (e) {
        throw new LanternError(`cannot fetch '${url}': ${(e as Error).message}`);
      }
      if (!response.ok) throw new LanternError(`cannot fetch '${url}': HTTP ${response.status}`, 'Open the file with the Open button instead');
      return new File([await response.arrayBuffer()], decodeURIComponent(url.split('/').pop() ?? url));
    }),
  );
}

// ---- output ----

function download(bytes: Uint8Array, name: string, type: string): void {
  const url = URL.createObjectURL(new Blob([bytes as Uint8Array<ArrayBuffer>], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

function fileStem(): string {
  return (viewer.stats.sceneName || 'lantern').replace(/[^A-Za-z0-9_-]+/g, '_');
}

function viewLink(): string {
  const params = formatViewParams({ ...viewer.viewParams(), ...(current ? { scene: current } : {}) });
  return `${location.origin}${location.pathname}?${params}`;
}

const actions = {
  screenshot: () => viewer.screenshotPng().then((png) => download(png, `${fileStem()}.png`, 'image/png')).catch((e) => showMessage(describeError(e), 'error')),
  exportExr: () => viewer.radianceExr().then((exr) => download(exr, `${fileStem()}.exr`, 'image/x-exr')).catch((e) => showMessage(describeError(e), 'error')),
  copyLink: async () => {
    const link = viewLink();
    history.replaceState(null, '', link);
    const note = current ? '' : ' (it restores the camera and settings; a file opened from this computer must be opened again)';
    try {
      await navigator.clipboard.writeText(link);
      showMessage(`Link copied${note}.`, 'info');
    } catch {
      showMessage(`The address bar now holds the link to this view${note}.`, 'info');
    }
  },
  decodeEnvironmentMap: (file: File) => loader.decodeEnvironment(file),
  report: (e: unknown) => showMessage(describeError(e), 'error'),
};

// ---- wiring ----

new ResizeObserver((entries) => {
  const entry = entries[0];
  if (!entry) return;
  const box = entry.devicePixelContentBoxSize?.[0];
  const w = box ? box.inlineSize : Math.round(entry.contentRect.width * devicePixelRatio);
  const h = box ? box.blockSize : Math.round(entry.contentRect.height * devicePixelRatio);
  viewer.resizeCanvas(Math.max(1, Math.min(8192, w)), Math.max(1, Math.min(8192, h))).catch((e) => viewer.fail(e));
}).observe(canvas);

viewer.input = new Input(canvas, {
  onClick: ({ x, y, alt }) => {
    if (alt) {
      viewer
        .focusAt(x, y)
        .then((depth) => {
          if (depth === undefined) return;
          // The Camera folder shows the new focus distance.
          panel?.readFromViewer();
          showMessage(`In focus at ${depth.toPrecision(4)} scene units (the lens's focus distance; the aperture radius sets the blur).`, 'info');
        })
        .catch((e) => showMessage(describeError(e), 'error'));
    } else viewer.select(x, y).catch((e) => showMessage(describeError(e), 'error'));
  },
  onEscape: () => void viewer.deselect().catch((e) => showMessage(describeError(e), 'error')),
  // E is the use key everywhere; Space only while walking (flying, it rises).
  onUse: (key) => {
    if (key === 'KeyE' || viewer.controller?.mode === 'walk') viewer.use();
  },
});

playButton.addEventListener('click', () => {
  if (viewer.state === 'playing') viewer.pause();
  else viewer.play().catch((e) => viewer.fail(e));
});
// Each user action starts with a clean message line; what it reports stays until the next.
sceneSelect.addEventListener('change', () => {
  clearMessage();
  if (sceneSelect.value !== FILE_OPTION) void showBuiltin(sceneSelect.value);
});
mapSelect.addEventListener('change', () => {
  clearMessage();
  void showPart(mapSelect.value);
});
/** Files of a file input, with their path inside the folder when a folder was picked. */
function pickedFiles(input: HTMLInputElement): PathedFile[] {
  const files = [...(input.files ?? [])].map((file) => ({ file, path: file.webkitRelativePath || file.name }));
  input.value = '';
  return files;
}
for (const input of [fileInput, folderInput]) {
  input.addEventListener('change', () => {
    const files = pickedFiles(input);
    clearMessage();
    if (files.length > 0) void openFiles(files);
  });
}

/**
 * What was dropped: folders are walked (a glTF with its .bin and textures/ dropped as one folder);
 * where the browser offers no entries (a synthetic drop, an old browser), the plain file list.
 */
async function droppedFiles(data: DataTransfer): Promise<PathedFile[]> {
  const entries = [...data.items].filter((item) => item.kind === 'file').map((item) => item.webkitGetAsEntry());
  const files = [...data.files];
  if (entries.length > 0 && entries.every((e) => e !== null)) {
    return walkEntries(entries as unknown as WalkEntry[]);
  }
  return files.map((file) => ({ file, path: file.name }));
}
let dragDepth = 0;
window.addEventListener('dragenter', (e) => {
  e.preventDefault();
  dragDepth++;
  dropZone.hidden = false;
});
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('dragleave', () => {
  if (--dragDepth <= 0) dropZone.hidden = true;
});
window.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  dropZone.hidden = true;
  const data = e.dataTransfer;
  clearMessage();
  if (!data) return;
  // The entries must be taken now: the DataTransfer is emptied once the event handler returns.
  droppedFiles(data)
    .then((files) => (files.length > 0 ? openFiles(files) : showMessage('Nothing to open in what was dropped (an empty folder?)', 'warning')))
    .catch((err) => showMessage(describeError(err), 'error'));
});

// Settings from the link (a sky too: it lights every scene from now on), then the panel, then the scene.
const linkedEnvironment = environmentOfLink(linked);
if (linkedEnvironment) await viewer.setEnvironment(linkedEnvironment);
else if (linked.envIntensity !== undefined) problems.push('env-intensity goes with sky=elevation,azimuth (an HDR map cannot be linked)');
await viewer.updateSettings({
  ...(linked.samplesPerFrame !== undefined ? { samplesPerFrame: linked.samplesPerFrame } : {}),
  ...(linked.scale !== undefined ? { scale: linked.scale } : {}),
  ...(linked.accumulate !== undefined ? { accumulate: linked.accumulate } : {}),
  ...(linked.animate !== undefined ? { animate: linked.animate } : {}),
  ...(linked.convergeWhenStill !== undefined ? { convergeWhenStill: linked.convergeWhenStill } : {}),
  // The torch's other settings are the scene's business: they are applied once it is loaded.
  render: { ...linkedRenderSettings(linked), ...(linked.torch?.enabled !== undefined ? { torch: { enabled: linked.torch.enabled } } : {}) },
});
panel = new SettingsPanel($('panel'), viewer, actions);
showViewer(viewer);

if (problems.length > 0) showMessage(`Ignored in the link: ${problems.join('; ')}`, 'warning');
if (!navigator.gpu) {
  showMessage(describeError(new LanternError('this browser has no WebGPU', 'Use Chrome or Edge 113+, Safari 26+ or Firefox 141+ on Windows; on Linux start Chrome with --enable-unsafe-webgpu --enable-features=Vulkan')), 'error');
}
const scene = linked.scene;
if (scene?.kind === 'files') {
  const urls = scene.urls;
  fetchFiles(urls)
    .then((files) => openFiles(files.map((file) => ({ file, path: file.name })), { urls, ...(scene.part ? { part: scene.part } : {}), ...(scene.skill !== undefined ? { skill: scene.skill } : {}) }, linked))
    .catch(async (e) => {
      showMessage(describeError(e), 'error');
      await showBuiltin('cornell');
    });
} else if (scene && !isBuiltinScene(scene.name)) {
  await showBuiltin('cornell');
  showMessage(describeError(new LanternError(`unknown scene '${scene.name}'`, `Built-in scenes are: ${builtinSceneNames().join(', ')}`)), 'error');
} else {
  void showBuiltin(scene?.name ?? 'cornell', linked);
}

// ---- test hook ----

declare global {
  interface Window {
    lantern: {
      readonly state: string;
      readonly samples: number;
      /** What the canvas shows: 'frame' (real time), 'converged' (a still view's progressive estimate) or 'progressive'. */
      readonly display: string;
      readonly scene: string;
      readonly loading: boolean;
      readonly sceneLoads: number;
      /** The environment that lights the image now (after an environment change has been uploaded), without map pixels. */
      readonly environment: Record<string, unknown> | undefined;
      readonly camera: Pose | undefined;
      /** The camera's thin lens (undefined: a pinhole). */
      readonly lens: ThinLens | undefined;
      readonly gpuResources: ResourceCount;
      /** Milliseconds from the first Play to its first frame done on the GPU (undefined before). */
      readonly firstFrameMs: number | undefined;
      /** The tracing kernels in use: 'generic', or 'specialised' once the scene has gone a second without edits. */
      readonly kernel: string;
      readonly link: string;
      /** What a click selected: material index and name, instance index. */
      readonly selection: { material: number; materialName: string; instanceIndex: number } | undefined;
      /** The tone-mapped estimate (RGBA8, without the selection outline) and the samples it holds, read at one moment. */
      readImage(): Promise<{ samples: number; width: number; height: number; rgba: number[] }>;
      simulateDeviceLoss(): void;
      /** The frame budget: whether it is on, the scale and samples per frame it chose, and its one-line account (the status line's). */
      readonly budget: BudgetState;
      /** How far the frame under way has got in its short submissions (undefined between frames). */
      readonly frame: FrameProgress | undefined;
      /** Makes every frame wait `ms` after its GPU work: a deterministically slow adapter for tests (0: off). */
      delayFrames(ms: number): void;
    };
  }
}
window.lantern = {
  get state() {
    return viewer.state;
  },
  get samples() {
    return viewer.stats.samples;
  },
  get display() {
    return viewer.stats.display;
  },
  get scene() {
    return viewer.stats.sceneName;
  },
  get loading() {
    return loading !== undefined;
  },
  get sceneLoads() {
    return sceneLoads;
  },
  get environment() {
    const e = viewer.scene?.prepared.scene.environment;
    if (!e) return undefined;
    return e.kind === 'map' ? { kind: e.kind, name: e.image.name, rotationDeg: e.rotationDeg, intensity: e.intensity } : { ...e };
  },
  get camera() {
    return viewer.controller?.pose;
  },
  get lens() {
    return viewer.lens;
  },
  get gpuResources() {
    return viewer.stats.gpuResources;
  },
  get kernel() {
    return viewer.stats.kernel;
  },
  get firstFrameMs() {
    return viewer.stats.firstFrameMs;
  },
  get link() {
    return viewLink();
  },
  get selection() {
    const s = viewer.selection;
    return s && { material: s.material, materialName: viewer.scene?.prepared.scene.materials[s.material]?.name ?? '', instanceIndex: s.instanceIndex };
  },
  readImage: () => viewer.readImage(),
  simulateDeviceLoss: () => viewer.simulateDeviceLoss(),
  get budget() {
    return viewer.budget;
  },
  get frame() {
    return viewer.frameProgress;
  },
  delayFrames(ms: number) {
    viewer.frameDelayMs = ms;
  },
};
