/**
 * The page's mutable state, one object (main.ts makes it; page-status.ts, page-storage.ts and
 * page-scenes.ts read and write it): the scene shown and the one loading, the open file set, the
 * message line's timer, the adapter's facts for the estimate, what the first Play did once. Types only
 * and the initial values: no DOM, nothing runs at import.
 */
import type { AdapterFacts, CompileTimesRecord } from './first-frame-estimate.ts';
import type { SettingsPanel } from './panel.ts';
import type { SceneLocation } from './view-params.ts';

/** What the scene picker names: a built-in scene, or a file scene with its label and the part (map) shown. */
export type PickerLabel = { kind: 'builtin'; name: string } | { kind: 'file'; label: string; part?: string };

export interface PageState {
  /** The expiry of the info message shown (INFO_MESSAGE_MS), if any. */
  messageTimer: ReturnType<typeof setTimeout> | undefined;
  /** The settings panel, once made (after the link's settings are applied). */
  panel: SettingsPanel | undefined;
  /** Where the current scene came from (for links); undefined for files opened from this computer. */
  current: SceneLocation | undefined;
  /** The stage of the scene's loading under way ('starting', then the worker's stages), or undefined. */
  loading: string | undefined;
  /** How far the scene's loading has got (0–1), while `loading`. */
  loadFraction: number;
  /** Where the open file set was served from (links can name it), or undefined for local files. */
  fileSource: { format: string; urls: readonly string[]; skill?: number } | undefined;
  /** The latest load's number: a load overtaken by a later one shows nothing. */
  loadToken: number;
  /** Scenes shown so far (the test hook: an environment change must not load the scene again). */
  sceneLoads: number;
  /** Pipeline compile times measured on this computer (this adapter's), merged as compiles complete and kept for the next visit. */
  compileTimes: CompileTimesRecord | undefined;
  /** The picker's label of the scene rendering now (set once a scene is shown). */
  shownLabel: PickerLabel | undefined;
  /** The label of the open file set (the picker's file entry names it). */
  fileLabel: string;
  /** What the adapter says about itself, asked before Play for the estimate (no device is made: no GPU work). */
  adapterFacts: AdapterFacts | undefined;
  /** Whether the backend has been chosen (backend-choice.ts; the choice itself is Viewer.backend): Play waits for it. */
  backendChosen: boolean;
  /** Whether the viewer has played (the controls show by themselves the first time ever). */
  played: boolean;
  /** Whether the first frame's wait has been kept for the next visit's estimate. */
  recorded: boolean;
  /** Drag enters minus leaves over the page (the drop zone shows while above 0). */
  dragDepth: number;
}

/** The page's state when it opens: nothing loaded, nothing played. */
export function initialPageState(): PageState {
  return {
    messageTimer: undefined,
    panel: undefined,
    current: undefined,
    loading: undefined,
    loadFraction: 0,
    fileSource: undefined,
    loadToken: 0,
    sceneLoads: 0,
    compileTimes: undefined,
    shownLabel: undefined,
    fileLabel: '',
    adapterFacts: undefined,
    backendChosen: false,
    played: false,
    recorded: false,
    dragDepth: 0,
  };
}
