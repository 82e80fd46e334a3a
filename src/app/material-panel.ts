/**
 * The panel's Material folder: what a click selected (its material, kind and object) and that
 * material's editable factors (scene/material-edit.ts): colour, roughness, metallic, IOR,
 * transmission and emission as a colour times a strength, only those its kind has. Each change goes
 * to Viewer.editMaterial, which rewrites the material in place before the next frame.
 */
import type { BladeApi, FolderApi, Pane } from 'tweakpane';
import type { Vec3 } from '../math/vec3.ts';
import type { PickResult } from '../renderer/renderer.ts';
import { EDITABLE_FIELDS, editableValues, EDIT_RANGES, type MaterialEdit, type MaterialEditField } from '../scene/material-edit.ts';
import type { Viewer } from './viewer.ts';

type Rgb = { r: number; g: number; b: number };
const rgb = ([r, g, b]: Vec3): Rgb => ({ r, g, b });
const vec = ({ r, g, b }: Rgb): Vec3 => [r, g, b];

/** Emission split for the panel: a colour with its largest channel 1 (white when dark) and a strength. */
export function splitEmission(e: Vec3): { color: Vec3; strength: number } {
  const strength = Math.max(...e);
  return strength > 0 ? { color: [e[0] / strength, e[1] / strength, e[2] / strength], strength } : { color: [1, 1, 1], strength: 0 };
}

export class MaterialPanel {
  private readonly folder: FolderApi;
  private readonly values = {
    selected: 'nothing: click an object',
    color: { r: 1, g: 1, b: 1 },
    roughness: 0.5,
    metallic: 0,
    ior: 1.5,
    transmission: 0,
    emissionColor: { r: 1, g: 1, b: 1 },
    emissionStrength: 0,
  };
  private readonly controls: Partial<Record<MaterialEditField, BladeApi[]>> = {};
  private shown?: PickResult;
  private syncing = false;

  constructor(pane: Pane, private readonly viewer: Viewer, report: (e: unknown) => void) {
    const v = this.values;
    this.folder = pane.addFolder({ title: 'Material (click to select)' });
    this.folder.element.title = 'Click an object to select it (Esc or a click on empty space deselects; Alt-click focuses the lens there). Edits restart the image at once and a copied link keeps them.';
    this.folder.addBinding(v, 'selected', { label: 'selected', readonly: true, multiline: true, rows: 2 });
    const edit = (make: () => MaterialEdit) => () => {
      if (this.syncing || !this.shown) return;
      this.viewer.editMaterial(this.shown.material, make()).catch(report);
    };
    this.controls.color = [this.folder.addBinding(v, 'color', { label: 'colour', color: { type: 'float' } }).on('change', edit(() => ({ color: vec(v.color) })))];
    this.controls.roughness = [this.folder.addBinding(v, 'roughness', { label: 'roughness', min: EDIT_RANGES.roughness[0], max: EDIT_RANGES.roughness[1], step: 0.01 }).on('change', edit(() => ({ roughness: v.roughness })))];
    this.controls.metallic = [this.folder.addBinding(v, 'metallic', { label: 'metallic', min: EDIT_RANGES.metallic[0], max: EDIT_RANGES.metallic[1], step: 0.01 }).on('change', edit(() => ({ metallic: v.metallic })))];
    // The slider spans common materials (water 1.33 to diamond 2.42); typed values reach validation's limit.
    this.controls.ior = [this.folder.addBinding(v, 'ior', { label: 'IOR', min: EDIT_RANGES.ior[0], max: 3, step: 0.01 }).on('change', edit(() => ({ ior: v.ior })))];
    this.controls.transmission = [this.folder.addBinding(v, 'transmission', { label: 'transmission', min: EDIT_RANGES.transmission[0], max: EDIT_RANGES.transmission[1], step: 0.01 }).on('change', edit(() => ({ transmission: v.transmission })))];
    const emission = edit(() => ({ emission: vec(v.emissionColor).map((c) => c * v.emissionStrength) as unknown as Vec3 }));
    this.controls.emission = [
      this.folder.addBinding(v, 'emissionColor', { label: 'emission colour', color: { type: 'float' } }).on('change', emission),
      this.folder.addBinding(v, 'emissionStrength', { label: 'emission strength', min: 0, step: 0.1 }).on('change', emission),
    ];
    this.folder.addButton({ title: 'Deselect (Esc)' }).on('click', () => void this.viewer.deselect().catch(report));
    this.show();
  }

  /** Takes the viewer's selection into the folder when it changed (called on every viewer change). */
  update(): void {
    if (this.viewer.selection !== this.shown) this.show();
  }

  private show(): void {
    const pick = this.viewer.selection;
    this.shown = pick;
    const scene = this.viewer.scene?.prepared.scene;
    const material = pick && scene?.materials[pick.material];
    const v = this.values;
    this.syncing = true;
    try {
      if (!pick || !material || !scene) {
        v.selected = 'nothing: click an object';
        for (const blades of Object.values(this.controls)) for (const b of blades ?? []) b.hidden = true;
      } else {
        const instance = scene.instances[pick.instanceIndex];
        v.selected = `${material.name} (${material.kind}, material ${pick.material})\non ${instance?.name ?? `instance ${pick.instanceId}`}`;
        const values = editableValues(material);
        if (values.color) v.color = rgb(values.color);
        if (values.roughness !== undefined) v.roughness = values.roughness;
        if (values.metallic !== undefined) v.metallic = values.metallic;
        if (values.ior !== undefined) v.ior = values.ior;
        if (values.transmission !== undefined) v.transmission = values.transmission;
        if (values.emission) {
          const { color, strength } = splitEmission(values.emission);
          v.emissionColor = rgb(color);
          v.emissionStrength = strength;
        }
        const fields = EDITABLE_FIELDS[material.kind];
        for (const [field, blades] of Object.entries(this.controls)) for (const b of blades ?? []) b.hidden = !fields.includes(field as MaterialEditField);
      }
      this.folder.refresh();
    } finally {
      this.syncing = false;
    }
  }
}
