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
 */
import { LanternError } from '../errors.ts';
import { BUILTIN_SCENES, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { acceptedExtensions, describeFormats, SNIFF_BYTES, sortFiles } from '../loaders/registry.ts';
import type { Pose } from './camera-controller.ts';
import { Input } from './input.ts';
import { SettingsPanel } from './panel.ts';
import { pathRelativeTo, walkEntries, type PathedFile, type WalkEntry } from './dropped-files.ts';
import { environmentOfLink, lightingNoteOf } from './environment-choice.ts';
import { SceneLoader } from './scene-loader.ts';
import type { SceneRequest } from './scene-request.ts';
import { formatViewParams, linkedRenderSettings, parseViewParams, type SceneLocation, type ViewParams } from './view-params.ts';
import { describeError, Viewer, type BudgetState, type FrameProgress } from './viewer.ts';
import type { ResourceCount } from '../gpu/resource-count.ts';
import type { ThinLens } from '../scene/types.ts';
import { legendGradientCss, type DebugLegend } from '../renderer/debug-legend.ts';
import { frameRate } from './number-format.ts';
import { adapterKey, describeEstimate, estimateFirstFrame, frameMs, remainingCompileMs, roughDuration, withMeasuredCompiles, type AdapterFacts, type CompileTimesRecord, type FirstFrameRecord } from './first-frame-estimate.ts';
import { fitStatus, part, type StatusPart } from './status-line.ts';
import type { CompileProgress } from '../gpu/pipeline-compiles.ts';

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

/** The option of the scene picker that stands for a scene opened from a file. */
const FILE_OPTION = '__file__';

/** How long an info message stays (warnings and errors stay until closed or replaced). */
const INFO_MESSAGE_MS = 8000;
let messageTimer: ReturnType<typeof setTimeout> | undefined;

/**
 * Shows one message (it replaces the last). Info expires after INFO_MESSAGE_MS; warnings and errors
 * stay until closed (×) or replaced. `details` (a scene's loading warnings) fold under the text,
 * which then reads as their count, and open on a click. `note` (information shown with warnings: how
 * a scene is lit) is a line of its own above them, in the colour of information.
 */
function showMessage(text: string, kind: 'info' | 'warning' | 'error', details: readonly string[] = [], note?: string): void {
  clearTimeout(messageTimer);
  messageBox.hidden = false;
  message.hidden = false;
  message.dataset.kind = kind;
  let body: Node = document.createTextNode(text);
  if (details.length > 0) {
    const fold = document.createElement('details');
    const summary = document.createElement('summary');
    summary.textContent = text;
    const list = document.createElement('div');
    list.textContent = details.map((d) => `· ${d}`).join('\n');
    fold.append(summary, list);
    body = fold;
  }
  const noteLine = note !== undefined ? [Object.assign(document.createElement('div'), { className: 'note', textContent: note })] : [];
  message.replaceChildren(...noteLine, body);
  if (kind === 'info') messageTimer = setTimeout(clearMessage, INFO_MESSAGE_MS);
}
function clearMessage(): void {
  clearTimeout(messageTimer);
  messageBox.hidden = true;
  message.hidden = true;
  message.textContent = '';
}
$('message-close').addEventListener('click', () => {
  clearMessage();
  canvas.focus();
});

const { view: linked, problems } = parseViewParams(new URLSearchParams(location.search));
const viewer = new Viewer(canvas, { onChange: showViewer, onMessage: showMessage });
const loader = new SceneLoader();
let panel: SettingsPanel | undefined;
/** Where the current scene came from (for links); undefined for files opened from this computer. */
let current: SceneLocation | undefined;
let loading: string | undefined;
/** How far the scene's loading has got (0–1), while `loading`. */
let loadFraction = 0;
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
  playButton.title = navigator.gpu ? '' : NO_WEBGPU;
  showStatus(v);
  panel?.showStats();
  showLegend(v.legend);
  showStart(v);
  if (v.state === 'playing') onPlaying();
}

/**
 * The status line and the bar beside it: what the page waits for (the scene loading, the pipelines
 * compiling, with how many of how many and the time left) or, while playing, the readings. Fitted
 * to its width (status-line.ts: the least important figures go first); the whole line and the
 * budget's reasons are the tooltip.
 */
function showStatus(v: Viewer): void {
  const s = v.stats;
  const c = v.compiles;
  noteCompiles(c);
  const compiling = c !== undefined && c.done < c.needed ? c : undefined;
  progress.hidden = loading === undefined && !compiling;
  progress.value = compiling ? compiling.done / compiling.needed : loadFraction;
  const waitParts = (prefix: string, what: string) => {
    if (!compiling) return [];
    const { done, needed } = compiling;
    const leftMs = adapterFacts ? remainingCompileMs(compiling, performance.now(), knownCompileTimes(), adapterFacts) + (v.awaitingFirstFrame ? frameMs(adapterFacts, expectedPixels()) : 0) : undefined;
    return [
      part(10, `${prefix}compiling ${what}, ${done} of ${needed}`, `compiling, ${done} of ${needed}`, `${done}/${needed} compiled`),
      leftMs === undefined ? undefined : part(6, `about ${roughDuration(leftMs)} left`, `~${roughDuration(leftMs)}`),
    ];
  };
  let parts: (StatusPart | undefined)[];
  if (loading !== undefined) parts = compiling ? waitParts('loading: ', 'shaders') : [part(10, `loading: ${loading}…`)];
  else if (!navigator.gpu) parts = [part(10, 'no WebGPU in this browser')];
  else if (v.state === 'idle') parts = [part(10, 'press Play to start')];
  else if (v.state === 'starting' || (v.awaitingFirstFrame && compiling)) parts = compiling ? waitParts('', 'shaders') : [part(10, 'starting the GPU…')];
  else if (v.awaitingFirstFrame) parts = [part(10, 'rendering the first frame…')];
  else {
    const r = v.settings.render;
    const fps = frameRate(s.framesPerSecond);
    parts = [
      // A recipe switched to compiles while the frames go on with the one before.
      ...waitParts('', v.compilingFor ?? 'shaders'),
      // A debug view that replaces the image traces no paths: no samples to count.
      part(9, r.debugView !== 'none' && r.debugLayout === 'replace' ? 'debug view' : `${s.samples} spp`),
      part(8, fps, fps.replace(/ \(.*\)$/, '')),
      part(5, `${s.width}×${s.height}`),
      part(3, v.budgetText(true), v.budget.on ? `budget ${v.budget.scale.toFixed(2)}×` : undefined),
      part(2, s.adapter),
      document.hidden && v.state === 'playing' ? part(9, 'paused while the tab is hidden', 'paused (hidden)') : undefined,
    ];
  }
  stats.textContent = fitStatus(parts, (text) => {
    stats.textContent = text;
    return stats.scrollWidth <= stats.clientWidth;
  });
  const whole = parts.flatMap((p) => (p ? [p.forms[0]] : [])).join(' · ');
  stats.title = s.budget && v.state !== 'idle' ? `${whole}\n${s.budget}` : whole;
}

/** Pipeline compile times measured on this computer (this adapter's), merged as compiles complete and kept for the next visit. */
let compileTimes: CompileTimesRecord | undefined;
function knownCompileTimes(): Readonly<Record<string, number>> {
  if (!adapterFacts) return {};
  const adapter = adapterKey(adapterFacts);
  if (compileTimes?.adapter !== adapter) {
    let stored: Partial<CompileTimesRecord> | undefined;
    try {
      stored = JSON.parse(storage()?.getItem(COMPILE_TIMES_KEY) ?? 'null') ?? undefined;
    } catch {
      stored = undefined;
    }
    const ms = stored?.adapter === adapter && stored.ms && typeof stored.ms === 'object' ? Object.fromEntries(Object.entries(stored.ms).filter(([, v]) => typeof v === 'number' && v >= 0)) : {};
    compileTimes = { adapter, ms };
  }
  return compileTimes.ms;
}
function noteCompiles(c: CompileProgress | undefined): void {
  if (!c || !adapterFacts) return;
  const known = knownCompileTimes();
  const next = withMeasuredCompiles(known, c.compiles);
  if (next === known) return;
  compileTimes = { adapter: compileTimes!.adapter, ms: next };
  remember(COMPILE_TIMES_KEY, JSON.stringify(compileTimes));
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

/** What the scene picker names: a built-in scene, or a file scene with its label and the part (map) shown. */
type PickerLabel = { kind: 'builtin'; name: string } | { kind: 'file'; label: string; part?: string };
/** The picker's label of the scene rendering now (set once a scene is shown). */
let shownLabel: PickerLabel | undefined;

/** Loads a scene in the worker and shows it; a failure leaves the current scene as it was, and the pickers naming it. */
async function show(request: SceneRequest, where: SceneLocation | undefined, label: PickerLabel, view: ViewParams = {}): Promise<void> {
  const token = ++loadToken;
  loadFraction = 0;
  loading = 'starting';
  showViewer(viewer);
  try {
    const loaded = await loader.load(request, (stage, fraction) => {
      if (token !== loadToken) return;
      loadFraction = fraction;
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
    // How the scene is lit and why is information, not one of the warnings.
    const name = loaded.prepared.scene.name;
    const lighting = lightingNoteOf(loaded.prepared.scene, viewer.environment);
    if (warnings.length > 0) showMessage(`${name}: ${warnings.length === 1 ? 'a warning' : `${warnings.length} warnings`} (click to see)`, 'warning', warnings, lighting);
    else if (lighting) showMessage(lighting, 'info');
    shownLabel = label;
  } catch (e) {
    if (token === loadToken) showMessage(describeError(e), 'error');
  } finally {
    if (token === loadToken) {
      loading = undefined;
      showPicked();
      showViewer(viewer);
    }
  }
}

/**
 * The scene picker names what is rendering: after a load that failed (a broken PLY), it goes back
 * to the scene still shown, and the map picker hides when its maps are not those of that scene.
 */
function showPicked(): void {
  const fileOption = sceneSelect.querySelector<HTMLOptionElement>(`option[value="${FILE_OPTION}"]`);
  if (shownLabel?.kind === 'builtin') {
    sceneSelect.value = shownLabel.name;
    fileOption?.remove();
    mapPicker.hidden = true;
  } else if (shownLabel?.kind === 'file') {
    markFileScene(shownLabel.label);
    const part = shownLabel.part;
    if (part !== undefined && [...mapSelect.options].some((o) => o.value === part)) mapSelect.value = part;
    else mapPicker.hidden = true;
  }
}

function showBuiltin(name: string, view: ViewParams = {}): Promise<void> {
  sceneSelect.value = name;
  mapPicker.hidden = true;
  return show({ kind: 'builtin', name }, { kind: 'builtin', name }, { kind: 'builtin', name }, view);
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
    fileLabel = summary.description;
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
    showPicked();
  }
}

/** The label of the open file set (the picker's file entry names it). */
let fileLabel = '';

/** A scene of the open file set: a map of a WAD, or (part undefined) the set's only scene. */
function showPart(part: string | undefined, view: ViewParams = {}): Promise<void> {
  const where: SceneLocation | undefined = fileSource ? { kind: 'files', ...fileSource, ...(part ? { part } : {}) } : undefined;
  const label: PickerLabel = { kind: 'file', label: fileLabel, ...(part !== undefined ? { part } : {}) };
  return show({ kind: 'part', ...(part ? { part } : {}), ...(fileSource?.skill !== undefined ? { skill: fileSource.skill } : {}) }, where, label, view);
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

// ---- before Play, help, the panel drawer, focus ----

/** Why Play stays disabled without WebGPU (the canvas's overlay says how to get it). */
const NO_WEBGPU = 'This browser has no WebGPU: see the notes over the image for how to enable it, or render with the lantern command';

/** localStorage keys: whether the controls were shown once; first frames measured per adapter. */
const HELP_SEEN_KEY = 'lantern.helpSeen';
const FIRST_FRAME_KEY = 'lantern.firstFrame';
/** Pipeline compile times per adapter (first-frame-estimate.ts CompileTimesRecord): the next visit's estimate of each compile. */
const COMPILE_TIMES_KEY = 'lantern.compileTimes';

/** localStorage, or undefined where the browser refuses it (private modes, file: pages). */
function storage(): Storage | undefined {
  try {
    return window.localStorage;
  } catch {
    return undefined;
  }
}

/** Keeps a value in localStorage where the browser lets it (a full or refused store only loses the memory). */
function remember(key: string, value: string): void {
  try {
    storage()?.setItem(key, value);
  } catch {
    // Nothing to do: the page works the same without it.
  }
}

/** What the adapter says about itself, asked before Play for the estimate (no device is made: no GPU work). */
let adapterFacts: AdapterFacts | undefined;
async function queryAdapter(): Promise<void> {
  try {
    const adapter = await navigator.gpu?.requestAdapter();
    if (!adapter) return;
    const info = adapter.info;
    const fallback = (info as GPUAdapterInfo & { isFallbackAdapter?: boolean }).isFallbackAdapter ?? (adapter as GPUAdapter & { isFallbackAdapter?: boolean }).isFallbackAdapter ?? false;
    adapterFacts = { vendor: info.vendor, architecture: info.architecture, device: info.device, description: info.description, isFallbackAdapter: fallback };
    showStart(viewer);
  } catch {
    // No estimate then; Play says what goes wrong.
  }
}

function firstFrameRecord(): FirstFrameRecord | undefined {
  try {
    const raw = storage()?.getItem(FIRST_FRAME_KEY);
    const r = raw ? (JSON.parse(raw) as Partial<FirstFrameRecord>) : undefined;
    return r && typeof r.adapter === 'string' && typeof r.ms === 'number' && typeof r.pixels === 'number' ? { adapter: r.adapter, ms: r.ms, pixels: r.pixels } : undefined;
  } catch {
    return undefined;
  }
}

/** The pixels the first frame will have: the canvas's device pixels times the resolution scale. */
const expectedPixels = () => Math.max(1, Math.round(canvas.width * viewer.settings.scale) * Math.round(canvas.height * viewer.settings.scale));

/** The overlay before Play: the scene's name, Play, and the expected wait; without WebGPU, how to get it. */
function showStart(v: Viewer): void {
  const before = v.state === 'idle';
  start.hidden = !before;
  if (!before) return;
  start.querySelector('.scene-name')!.textContent = loading !== undefined ? `Loading ${v.stats.sceneName || 'the scene'}…` : v.stats.sceneName;
  const noGpu = !navigator.gpu;
  start.querySelector<HTMLElement>('.no-webgpu')!.hidden = !noGpu;
  startPlay.hidden = noGpu;
  startPlay.disabled = !v.scene || loading !== undefined;
  const estimate = estimateFirstFrame(adapterFacts, expectedPixels(), firstFrameRecord());
  start.querySelector('.estimate')!.textContent = noGpu ? '' : estimate ? describeEstimate(estimate) : '';
}

let played = false;
/** Once playing: the first time ever, the controls show by themselves; the first frame's wait is kept for the next visit's estimate. */
function onPlaying(): void {
  if (!played) {
    played = true;
    const store = storage();
    if (store && !store.getItem(HELP_SEEN_KEY)) {
      remember(HELP_SEEN_KEY, '1');
      showHelp(true);
    }
  }
  const ms = viewer.stats.firstFrameMs;
  if (ms !== undefined && adapterFacts && !recorded) {
    recorded = true;
    remember(FIRST_FRAME_KEY, JSON.stringify({ adapter: adapterKey(adapterFacts), ms, pixels: viewer.stats.width * viewer.stats.height } satisfies FirstFrameRecord));
  }
}
let recorded = false;

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
new ResizeObserver(() => showStatus(viewer)).observe(statusBox);
setInterval(() => {
  const c = viewer.compiles;
  if ((c && c.done < c.needed) || viewer.awaitingFirstFrame) showStatus(viewer);
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
  // Space on a focused Play button would pause again: the keyboard goes to the image.
  canvas.focus({ preventScroll: true });
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
  showMessage(describeError(new LanternError('this browser has no WebGPU', 'The notes over the image say which browsers have it and how to turn it on; the lantern command renders without a browser')), 'error');
} else void queryAdapter();
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
  get worldSeconds() {
    return viewer.worldSeconds;
  },
  get pipelines() {
    return [...viewer.pipelines];
  },
};
