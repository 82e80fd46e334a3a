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
 * For a new user: before Play the canvas shows the scene's name, a Play button and the expected
 * wait for the first frame (first-frame-estimate.ts); `?` (key or button) shows the controls, once
 * by itself on the first Play (remembered in localStorage); the canvas owns the keyboard while
 * playing, so form controls hand focus back once used (an arrow key never switches scenes
 * mid-walk); `Tab` hides the settings, which are a drawer on narrow screens; messages can be
 * closed, info expires, and a scene's warnings fold into a count that opens on click. The scene
 * picker always names the scene that is rendering, also after a file that failed to load.
 *
 * Test hook: `window.lantern` exposes the viewer's state, sample count, scene, camera, lens,
 * selection and live GPU resources, and reads the estimate with its sample count; the canvas
 * carries data-state and data-samples, so scripts can wait for frames, and data-first-frame-ms (the
 * milliseconds from the first Play to its first frame, also in the panel's GPU folder).
 *
 * This file is the page's entry (index.html loads it): it finds the elements, holds the page's state
 * in one object (page-state.ts) and wires the parts; page-status.ts shows messages, the status line,
 * the legend and the overlay before Play; page-scenes.ts loads scenes (the pickers, files opened,
 * dropped or served); page-storage.ts is what the page remembers between visits.
 */
import { LanternError } from '../errors.ts';
import { BUILTIN_SCENES, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { acceptedExtensions, describeFormats } from '../loaders/registry.ts';
import type { Pose } from './camera-controller.ts';
import { Input } from './input.ts';
import { SettingsPanel } from './panel.ts';
import { environmentOfLink } from './environment-choice.ts';
import { SceneLoader } from './scene-loader.ts';
import { formatViewParams, linkedRenderSettings, parseViewParams } from './view-params.ts';
import { Viewer } from './viewer.ts';
import { describeError, type BudgetState, type FrameProgress } from './viewer-types.ts';
import type { ResourceCount } from '../gpu/resource-count.ts';
import type { ThinLens } from '../scene/types.ts';
import { adapterKey, type FirstFrameRecord } from './first-frame-estimate.ts';
import { initialPageState, type PageState } from './page-state.ts';
import { droppedFiles, fetchFiles, FILE_OPTION, PageScenes, pickedFiles } from './page-scenes.ts';
import { PageStatus } from './page-status.ts';
import { chooseBackend, describeBackend } from './backend-choice.ts';
import { FIRST_FRAME_KEY, HELP_SEEN_KEY, remember, storage } from './page-storage.ts';

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
const statusBox = $<HTMLDivElement>('status');
const message = $<HTMLDivElement>('message');
const messageBox = $<HTMLDivElement>('message-box');
const dropZone = $<HTMLDivElement>('drop-zone');
const legend = $<HTMLDivElement>('legend');
const start = $<HTMLDivElement>('start');
const startPlay = $<HTMLButtonElement>('start-play');
const help = $<HTMLElement>('help');
const helpButton = $<HTMLButtonElement>('help-button');
const panelToggle = $<HTMLButtonElement>('panel-toggle');

/** The page's mutable state (page-state.ts: a doc comment per field). */
const page: PageState = initialPageState();
const status = new PageStatus({ canvas, progress, stats, message, messageBox, legend, start, startPlay }, page);
const showMessage = status.showMessage.bind(status);
const clearMessage = status.clearMessage.bind(status);

$('message-close').addEventListener('click', () => {
  clearMessage();
  canvas.focus();
});

const { view: linked, problems } = parseViewParams(new URLSearchParams(location.search));
const viewer = new Viewer(canvas, { onChange: showViewer, onMessage: showMessage });
const loader = new SceneLoader();
const scenes = new PageScenes({ viewer, loader, page, status, sceneSelect, mapSelect, mapPicker, linked, problems, showViewer: () => showViewer(viewer) });

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
  playButton.disabled = v.state === 'starting' || v.state === 'failed' || !page.backendChosen || !v.scene;
  playButton.title = page.backendChosen ? '' : CHOOSING_BACKEND;
  status.showStatus(v);
  page.panel?.showStats();
  status.showLegend(v.legend);
  status.showStart(v);
  if (v.state === 'playing') onPlaying();
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
  const params = formatViewParams({ ...viewer.viewParams(), ...(page.current ? { scene: page.current } : {}) });
  return `${location.origin}${location.pathname}?${params}`;
}

const actions = {
  screenshot: () => viewer.screenshotPng().then((png) => download(png, `${fileStem()}.png`, 'image/png')).catch((e) => showMessage(describeError(e), 'error')),
  exportExr: () => viewer.radianceExr().then((exr) => download(exr, `${fileStem()}.exr`, 'image/x-exr')).catch((e) => showMessage(describeError(e), 'error')),
  copyLink: async () => {
    const link = viewLink();
    history.replaceState(null, '', link);
    const note = page.current ? '' : ' (it restores the camera and settings; a file opened from this computer must be opened again)';
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

// ---- before Play, help, the panel drawer, focus ----

/** Why Play waits a moment at load: WebGPU is asked for an adapter, else WebGL2 renders (backend-choice.ts). */
const CHOOSING_BACKEND = 'Asking the browser for WebGPU (WebGL2 renders without it)…';

/** Asks the adapter about itself before Play, for the estimate (no device is made: no GPU work). */
async function queryAdapter(): Promise<void> {
  try {
    const adapter = await navigator.gpu?.requestAdapter();
    if (!adapter) return;
    const info = adapter.info;
    const fallback = (info as GPUAdapterInfo & { isFallbackAdapter?: boolean }).isFallbackAdapter ?? (adapter as GPUAdapter & { isFallbackAdapter?: boolean }).isFallbackAdapter ?? false;
    page.adapterFacts = { vendor: info.vendor, architecture: info.architecture, device: info.device, description: info.description, isFallbackAdapter: fallback };
    status.showStart(viewer);
  } catch {
    // No estimate then; Play says what goes wrong.
  }
}

/** Once playing: the first time ever, the controls show by themselves; the first frame's wait is kept for the next visit's estimate. */
function onPlaying(): void {
  if (!page.played) {
    page.played = true;
    const store = storage();
    if (store && !store.getItem(HELP_SEEN_KEY)) {
      remember(HELP_SEEN_KEY, '1');
      showHelp(true);
    }
  }
  const ms = viewer.stats.firstFrameMs;
  if (ms !== undefined && page.adapterFacts && !page.recorded) {
    page.recorded = true;
    remember(FIRST_FRAME_KEY, JSON.stringify({ adapter: adapterKey(page.adapterFacts), ms, pixels: viewer.stats.width * viewer.stats.height } satisfies FirstFrameRecord));
  }
}

function showHelp(shown: boolean): void {
  help.hidden = !shown;
  helpButton.setAttribute('aria-expanded', String(shown));
}
helpButton.addEventListener('click', () => {
  showHelp(help.hidden === true);
  canvas.focus();
});
$('help-close').addEventListener('click', () => {
  showHelp(false);
  canvas.focus();
});

/** Whether the settings panel shows: beside the image on wide screens (Tab hides it), a drawer over it on narrow ones (closed at first). */
const narrow = window.matchMedia('(max-width: 460px)');
function panelShown(): boolean {
  return narrow.matches ? document.body.classList.contains('panel-open') : !document.body.classList.contains('panel-hidden');
}
function showPanel(shown: boolean): void {
  if (narrow.matches) document.body.classList.toggle('panel-open', shown);
  else document.body.classList.toggle('panel-hidden', !shown);
  panelToggle.setAttribute('aria-expanded', String(shown));
}
panelToggle.addEventListener('click', () => {
  showPanel(!panelShown());
  canvas.focus();
});
narrow.addEventListener('change', () => panelToggle.setAttribute('aria-expanded', String(panelShown())));
panelToggle.setAttribute('aria-expanded', String(panelShown()));

/** Form controls where keys are typed (not movement, not page shortcuts). */
const isFormField = (t: EventTarget | null) => t instanceof HTMLElement && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA' || t.isContentEditable);

window.addEventListener('keydown', (e) => {
  if (e.ctrlKey || e.metaKey || e.altKey) return;
  if (e.key === '?' && !isFormField(e.target)) {
    showHelp(help.hidden === true);
    e.preventDefault();
  } else if (e.key === 'Escape' && !help.hidden && !isFormField(e.target)) {
    showHelp(false);
  } else if (e.key === 'Tab' && !isFormField(e.target) && !(e.target instanceof HTMLButtonElement)) {
    // Tab from the image (or the page) shows or hides the settings; in the panel and on buttons it moves focus as usual.
    showPanel(!panelShown());
    e.preventDefault();
  }
});

/**
 * The canvas owns the keyboard while playing: a form control gives focus back once used (a choice
 * made, Enter, Escape), so the arrow keys move the camera instead of switching scenes. Text typed in
 * a field keeps the focus until Enter.
 */
function giveBackFocus(target: EventTarget | null): void {
  if (!(target instanceof HTMLElement)) return;
  if (target.tagName === 'SELECT' || (target instanceof HTMLInputElement && target.type !== 'text' && target.type !== 'number')) target.blur();
  canvas.focus({ preventScroll: true });
}
for (const control of [sceneSelect, mapSelect]) control.addEventListener('change', (e) => giveBackFocus(e.target));
$('panel').addEventListener('change', (e) => {
  // A text field's change comes with Enter or leaving it: either way it is done.
  const t = e.target;
  if (t instanceof HTMLSelectElement || (t instanceof HTMLInputElement && (t.type === 'checkbox' || t.type === 'file'))) giveBackFocus(t);
});
document.addEventListener('keydown', (e) => {
  if ((e.key === 'Enter' || e.key === 'Escape') && isFormField(e.target)) {
    const t = e.target as HTMLElement;
    // Enter commits the field (Tweakpane listens for it first); then the image has the keyboard.
    setTimeout(() => {
      t.blur();
      canvas.focus({ preventScroll: true });
    });
  }
});
startPlay.addEventListener('click', () => playButton.click());

// ---- wiring ----

// The status line follows its width (a window resized, the panel shown or hidden) and, while the
// page waits, the time left; its text never changes its size (style.css), so this cannot loop.
new ResizeObserver(() => status.showStatus(viewer)).observe(statusBox);
setInterval(() => {
  const c = viewer.compiles;
  if ((c && c.done < c.needed) || viewer.awaitingFirstFrame) status.showStatus(viewer);
}, 1000);

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
          page.panel?.readFromViewer();
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
  // Space on a focused Play button would pause again: the keyboard goes to the image.
  canvas.focus({ preventScroll: true });
});
// Each user action starts with a clean message line; what it reports stays until the next.
sceneSelect.addEventListener('change', () => {
  clearMessage();
  if (sceneSelect.value !== FILE_OPTION) void scenes.showBuiltin(sceneSelect.value);
});
mapSelect.addEventListener('change', () => {
  clearMessage();
  void scenes.showPart(mapSelect.value);
});
for (const input of [fileInput, folderInput]) {
  input.addEventListener('change', () => {
    const files = pickedFiles(input);
    clearMessage();
    if (files.length > 0) void scenes.openFiles(files);
  });
}

window.addEventListener('dragenter', (e) => {
  e.preventDefault();
  page.dragDepth++;
  dropZone.hidden = false;
});
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('dragleave', () => {
  if (--page.dragDepth <= 0) dropZone.hidden = true;
});
window.addEventListener('drop', (e) => {
  e.preventDefault();
  page.dragDepth = 0;
  dropZone.hidden = true;
  const data = e.dataTransfer;
  clearMessage();
  if (!data) return;
  // The entries must be taken now: the DataTransfer is emptied once the event handler returns.
  droppedFiles(data)
    .then((files) => (files.length > 0 ? scenes.openFiles(files) : showMessage('Nothing to open in what was dropped (an empty folder?)', 'warning')))
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
page.panel = new SettingsPanel($('panel'), viewer, actions);
showViewer(viewer);

if (problems.length > 0) showMessage(`Ignored in the link: ${problems.join('; ')}`, 'warning');
// WebGPU where it gives an adapter, else (or with backend=webgl2) WebGL2's fragment path tracer.
void chooseBackend(location.search, navigator.gpu).then((choice) => {
  viewer.backend = choice;
  page.backendChosen = true;
  if (choice.kind === 'webgpu') void queryAdapter();
  else showMessage(`Rendering with ${describeBackend(choice)}. Real-time denoising, ReSTIR, the hybrid recipe, spectral mode and the debug views need WebGPU.`, 'info');
  page.panel?.readFromViewer();
  showViewer(viewer);
});
const scene = linked.scene;
if (scene?.kind === 'files') {
  const urls = scene.urls;
  fetchFiles(urls)
    .then((files) => scenes.openFiles(files.map((file) => ({ file, path: file.name })), { urls, ...(scene.part ? { part: scene.part } : {}), ...(scene.skill !== undefined ? { skill: scene.skill } : {}) }, linked))
    .catch(async (e) => {
      showMessage(describeError(e), 'error');
      await scenes.showBuiltin('cornell');
    });
} else if (scene && !isBuiltinScene(scene.name)) {
  await scenes.showBuiltin('cornell');
  showMessage(describeError(new LanternError(`unknown scene '${scene.name}'`, `Built-in scenes are: ${builtinSceneNames().join(', ')}`)), 'error');
} else {
  void scenes.showBuiltin(scene?.name ?? 'cornell', linked);
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
      /** The progressive estimate's mean radiance (RGB floats a pixel, top row first) and its samples, read at one moment. */
      readRadiance(): Promise<{ samples: number; width: number; height: number; rgb: number[] }>;
      /** The backend rendering (backend-choice.ts), in the page's words, and on WebGL2 each program compiled with its milliseconds. */
      readonly backend: { kind: string; description: string; compiles: { key: string; ms: number }[] };
      simulateDeviceLoss(): void;
      /** The frame budget: whether it is on, the scale and samples per frame it chose, and its one-line account (the status line's). */
      readonly budget: BudgetState;
      /** How far the frame under way has got in its short submissions (undefined between frames). */
      readonly frame: FrameProgress | undefined;
      /** Makes every frame wait `ms` after its GPU work: a deterministically slow adapter for tests (0: off). */
      delayFrames(ms: number): void;
      /** Seconds the scene's world (doors, lifts, the phantom) has played. */
      readonly worldSeconds: number;
      /** Every pipeline the page's device was asked to compile (label and override constants), in request order. */
      readonly pipelines: readonly string[];
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
    return page.loading !== undefined;
  },
  get sceneLoads() {
    return page.sceneLoads;
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
  readRadiance: () => viewer.readRadiance(),
  get backend() {
    return { kind: viewer.backend.kind, description: describeBackend(viewer.backend), compiles: [...viewer.webgl2.compiles] };
  },
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
  get worldSeconds() {
    return viewer.worldSeconds;
  },
  get pipelines() {
    return [...viewer.pipelines];
  },
};

