/**
 * Loading scenes on the page: a built-in scene from the picker, or files picked, dropped (folders
 * walked) or served (`lantern view`), which the registry sorts into one scene's files; a set of
 * several scenes (a WAD's maps) gets a map picker. Scenes load in the worker (SceneLoader) with a
 * progress bar; a failure leaves the scene shown as it was, and the pickers naming it. main.ts makes
 * one PageScenes and wires the pickers, the file inputs and the drop zone to it; nothing runs at import.
 */
import { LanternError } from '../errors.ts';
import { SNIFF_BYTES, sortFiles } from '../loaders/registry.ts';
import { pathRelativeTo, walkEntries, type PathedFile, type WalkEntry } from './dropped-files.ts';
import { lightingNoteOf } from './environment-choice.ts';
import type { PageState, PickerLabel } from './page-state.ts';
import type { PageStatus } from './page-status.ts';
import type { SceneLoader } from './scene-loader.ts';
import type { SceneRequest } from './scene-request.ts';
import type { SceneLocation, ViewParams } from './view-params.ts';
import type { Viewer } from './viewer.ts';
import { describeError } from './viewer-types.ts';

/** The option of the scene picker that stands for a scene opened from a file. */
export const FILE_OPTION = '__file__';

/** What loading scenes needs of the page. */
export interface ScenesPage {
  readonly viewer: Viewer;
  readonly loader: SceneLoader;
  readonly page: PageState;
  readonly status: PageStatus;
  /** The scene picker, the map picker and its label (hidden without maps). */
  readonly sceneSelect: HTMLSelectElement;
  readonly mapSelect: HTMLSelectElement;
  readonly mapPicker: HTMLLabelElement;
  /** The view the page's link asked for, and the problems found in the link (its scene's warning repeats them). */
  readonly linked: ViewParams;
  readonly problems: readonly string[];
  /** Shows the viewer's state on the page (main.ts showViewer). */
  showViewer(): void;
}

/** The page's scene loading: the pickers, the open file set, the loads under way. */
export class PageScenes {
  constructor(private readonly p: ScenesPage) {}

  /** Loads a scene in the worker and shows it; a failure leaves the current scene as it was, and the pickers naming it. */
  async show(request: SceneRequest, where: SceneLocation | undefined, label: PickerLabel, view: ViewParams = {}): Promise<void> {
    const token = ++this.p.page.loadToken;
    this.p.page.loadFraction = 0;
    this.p.page.loading = 'starting';
    this.p.showViewer();
    try {
      const loaded = await this.p.loader.load(request, (stage, fraction) => {
        if (token !== this.p.page.loadToken) return;
        this.p.page.loadFraction = fraction;
        this.p.page.loading = stage;
        this.p.showViewer();
      });
      if (token !== this.p.page.loadToken) return;
      const { pose, mode, fovDegrees, apertureRadius, focusDistance } = view;
      await this.p.viewer.setScene(loaded, { pose, mode, fovDegrees, apertureRadius, focusDistance });
      if (view.torch) await this.p.viewer.updateSettings({ render: { torch: { ...this.p.viewer.settings.render.torch, ...view.torch } } });
      this.p.page.current = where;
      // The link's problems again (this warning replaces the line that named them), with the material
      // edits that do not fit the scene.
      const ignored = [...(view === this.p.linked ? this.p.problems : []), ...(view.materials ? await this.p.viewer.applyMaterialOverrides(view.materials) : [])];
      this.p.page.sceneLoads++;
      this.p.page.panel?.readFromViewer();
      // Each warning once (a texture missing from ten materials is one problem), one per line.
      const warnings = [...new Set([...loaded.warnings, ...ignored.map((p) => `ignored in the link: ${p}`)])];
      // How the scene is lit and why is information, not one of the warnings.
      const name = loaded.prepared.scene.name;
      const lighting = lightingNoteOf(loaded.prepared.scene, this.p.viewer.environment);
      if (warnings.length > 0) this.p.status.showMessage(`${name}: ${warnings.length === 1 ? 'a warning' : `${warnings.length} warnings`} (click to see)`, 'warning', warnings, lighting);
      else if (lighting) this.p.status.showMessage(lighting, 'info');
      this.p.page.shownLabel = label;
    } catch (e) {
      if (token === this.p.page.loadToken) this.p.status.showMessage(describeError(e), 'error');
    } finally {
      if (token === this.p.page.loadToken) {
        this.p.page.loading = undefined;
        this.showPicked();
        this.p.showViewer();
      }
    }
  }

  /**
   * The scene picker names what is rendering: after a load that failed (a broken PLY), it goes back
   * to the scene still shown, and the map picker hides when its maps are not those of that scene.
   */
  showPicked(): void {
    const fileOption = this.p.sceneSelect.querySelector<HTMLOptionElement>(`option[value="${FILE_OPTION}"]`);
    if (this.p.page.shownLabel?.kind === 'builtin') {
      this.p.sceneSelect.value = this.p.page.shownLabel.name;
      fileOption?.remove();
      this.p.mapPicker.hidden = true;
    } else if (this.p.page.shownLabel?.kind === 'file') {
      this.markFileScene(this.p.page.shownLabel.label);
      const part = this.p.page.shownLabel.part;
      if (part !== undefined && [...this.p.mapSelect.options].some((o) => o.value === part)) this.p.mapSelect.value = part;
      else this.p.mapPicker.hidden = true;
    }
  }

  showBuiltin(name: string, view: ViewParams = {}): Promise<void> {
    this.p.sceneSelect.value = name;
    this.p.mapPicker.hidden = true;
    return this.show({ kind: 'builtin', name }, { kind: 'builtin', name }, { kind: 'builtin', name }, view);
  }

  /** The file-scene entry of the scene picker, labelled with what was opened. */
  markFileScene(label: string): void {
    let option = this.p.sceneSelect.querySelector<HTMLOptionElement>(`option[value="${FILE_OPTION}"]`);
    if (!option) {
      option = document.createElement('option');
      option.value = FILE_OPTION;
      this.p.sceneSelect.append(option);
    }
    option.textContent = label;
    this.p.sceneSelect.value = FILE_OPTION;
  }

  /**
   * Opens files picked or dropped (or served): the registry sorts them into one scene's files (a
   * WAD stack, IWAD first) and siblings (a glTF's buffers and textures); a set of several scenes
   * (a WAD's maps) gets a map picker, a set of one is shown at once.
   */
  async openFiles(files: readonly PathedFile[], where?: { urls: readonly string[]; part?: string; skill?: number }, view: ViewParams = {}): Promise<void> {
    try {
      const heads = await Promise.all(files.map(async ({ file, path }) => ({ file, path, name: file.name, head: new Uint8Array(await file.slice(0, SNIFF_BYTES).arrayBuffer()) })));
      const { format, main, siblings } = sortFiles(heads);
      const baseUrl = where?.urls[0] ? new URL(where.urls[0], location.href).href : undefined;
      // Siblings are named from the main file's folder, the way a glTF's URIs name them.
      const mainPath = main[0]?.path ?? '';
      const beside = siblings.map((f) => ({ file: f.file, path: pathRelativeTo(mainPath, f.path) }));
      const summary = await this.p.loader.openFiles(format.id, main.map((f) => f.file), beside, baseUrl);
      this.p.page.fileSource = where ? { format: format.id, urls: where.urls, ...(where.skill !== undefined ? { skill: where.skill } : {}) } : undefined;
      this.p.page.fileLabel = summary.description;
      this.markFileScene(summary.description);
      if (summary.parts.length === 0) {
        this.p.mapPicker.hidden = true;
        await this.showPart(undefined, view);
        return;
      }
      this.p.mapSelect.replaceChildren(
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
      if (where?.part && wanted !== where.part) this.p.status.showMessage(`${summary.description} has no ${format.part?.noun ?? 'part'} ${where.part}; showing ${wanted}`, 'warning');
      this.p.mapSelect.value = wanted;
      this.p.mapPicker.hidden = false;
      await this.showPart(wanted, view);
    } catch (e) {
      this.p.status.showMessage(describeError(e), 'error');
      // The picker goes back to what is still shown.
      this.showPicked();
    }
  }

  /** A scene of the open file set: a map of a WAD, or (part undefined) the set's only scene. */
  showPart(part: string | undefined, view: ViewParams = {}): Promise<void> {
    const where: SceneLocation | undefined = this.p.page.fileSource ? { kind: 'files', ...this.p.page.fileSource, ...(part ? { part } : {}) } : undefined;
    const label: PickerLabel = { kind: 'file', label: this.p.page.fileLabel, ...(part !== undefined ? { part } : {}) };
    return this.show({ kind: 'part', ...(part ? { part } : {}), ...(this.p.page.fileSource?.skill !== undefined ? { skill: this.p.page.fileSource.skill } : {}) }, where, label, view);
  }
}

/** Files the server offers (`lantern view` serves the files named on its command line). */
export async function fetchFiles(urls: readonly string[]): Promise<File[]> {
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

/** Files of a file input, with their path inside the folder when a folder was picked. */
export function pickedFiles(input: HTMLInputElement): PathedFile[] {
  const files = [...(input.files ?? [])].map((file) => ({ file, path: file.webkitRelativePath || file.name }));
  input.value = '';
  return files;
}

/**
 * What was dropped: folders are walked (a glTF with its .bin and textures/ dropped as one folder);
 * where the browser offers no entries (a synthetic drop, an old browser), the plain file list.
 */
export async function droppedFiles(data: DataTransfer): Promise<PathedFile[]> {
  const entries = [...data.items].filter((item) => item.kind === 'file').map((item) => item.webkitGetAsEntry());
  const files = [...data.files];
  if (entries.length > 0 && entries.every((e) => e !== null)) {
    return walkEntries(entries as unknown as WalkEntry[]);
  }
  return files.map((file) => ({ file, path: file.name }));
}
