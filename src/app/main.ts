/**
 * The page: a scene picker, Play/Pause, and the canvas. Nothing touches the GPU before Play.
 * URL parameters: scene=<name>, scale=<render resolution / canvas resolution>.
 * Test hook: `window.lantern` exposes the viewer's state and sample count, and the canvas carries
 * data-state and data-samples, so scripts (the Playwright tests) can wait for frames.
 */
import { LanternError } from '../errors.ts';
import { BUILTIN_SCENES, builtinSceneNames, isBuiltinScene } from '../loaders/builtin/index.ts';
import { Viewer } from './viewer.ts';

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
const canvas = $<HTMLCanvasElement>('view');
const sceneSelect = $<HTMLSelectElement>('scene');
const playButton = $<HTMLButtonElement>('play');
const stats = $<HTMLSpanElement>('stats');
const message = $<HTMLParagraphElement>('message');

const params = new URLSearchParams(location.search);
const requested = params.get('scene') ?? 'cornell';
// Render resolution as a fraction of the canvas (0.25–2 in the viewer; tests go lower on SwiftShader).
const scale = Math.min(2, Math.max(1 / 64, Number(params.get('scale') ?? 1) || 1));
const initial = isBuiltinScene(requested) ? requested : 'cornell';

for (const name of builtinSceneNames()) {
  const option = document.createElement('option');
  option.value = name;
  option.textContent = name;
  option.title = BUILTIN_SCENES[name].description;
  sceneSelect.append(option);
}
sceneSelect.value = initial;

function showError(error: unknown): void {
  message.hidden = false;
  message.textContent = error instanceof LanternError ? error.userMessage : `Something went wrong: ${(error as Error)?.message ?? error}`;
}

function showViewer(v: Viewer): void {
  const s = v.stats;
  canvas.dataset.state = v.state;
  canvas.dataset.samples = String(s.samples);
  playButton.textContent = v.state === 'playing' ? 'Pause' : 'Play';
  playButton.disabled = v.state === 'starting' || v.state === 'failed';
  stats.textContent = v.state === 'idle' ? 'press Play to start' : `${s.samples} spp · ${s.framesPerSecond.toFixed(1)} fps · ${s.adapter}`;
  if (v.state === 'failed') showError(v.failure);
}

const viewer = new Viewer(canvas, initial, scale, showViewer);
showViewer(viewer);
if (!isBuiltinScene(requested)) showError(new LanternError(`unknown scene '${requested}'`, `Built-in scenes are: ${builtinSceneNames().join(', ')}`));
if (!navigator.gpu) {
  showError(new LanternError('this browser has no WebGPU', 'Use Chrome or Edge 113+, Safari 26+ or Firefox 141+ on Windows; on Linux Chrome needs --enable-unsafe-webgpu --enable-features=Vulkan'));
  playButton.disabled = true;
}

playButton.addEventListener('click', () => {
  if (viewer.state === 'playing') viewer.pause();
  else viewer.play().catch((e) => viewer.fail(e));
});
sceneSelect.addEventListener('change', () => {
  viewer.selectScene(sceneSelect.value).catch((e) => viewer.fail(e));
});

declare global {
  interface Window {
    lantern: { readonly state: string; readonly samples: number };
  }
}
window.lantern = {
  get state() {
    return viewer.state;
  },
  get samples() {
    return viewer.stats.samples;
  },
};
