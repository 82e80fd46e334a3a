/**
 * The scene on the GPU: the prepared scene and its resources, kept in step as the world moves
 * (instances, morphs, materials: rewritten in place, never rebuilt), with the per-tile culled scenes
 * of the tileCulling setting swapped in as the camera crosses tiles. The Renderer holds one and is
 * told, through ResidencyHooks, what each change means for the image.
 */
import type { SceneFeatures } from '../gpu/pack/scene-pack.ts';
import { packInstances } from '../gpu/pack/scene-pack.ts';
import { SceneResources, writeTriangleAttributes } from '../gpu/scene-resources.ts';
import { timedStage } from '../gpu/stage-log.ts';
import type { Vec3 } from '../math/vec3.ts';
import { isEmptyUpdate, type SceneUpdate } from '../scene/dynamics.ts';
import type { MaterialEdit } from '../scene/material-edit.ts';
import { defaultTileCulling } from '../scene/tile-culling.ts';
import { accelOf, editMaterials, LIGHT_BUFFERS, updateGeometry, withAccel, type BufferWrite, type GeometryUpdate, type PreparedScene } from './prepare.ts';
import type { Accel } from '../bvh/grid.ts';
import { TILE_SWAP_BUFFERS, TileCulledScenes, type TileCullingStats } from './tile-culled.ts';

/** What the residency asks of the renderer. */
export interface ResidencyHooks {
  /** Compiles what the recipes need for a scene with these features (awaited before a scene is swapped in). */
  compile(features: SceneFeatures): Promise<unknown>;
  /** Whether the tileCulling setting is on, and where the camera is (undefined before a camera is set). */
  tileCulling(): boolean;
  cameraPosition(): Vec3 | undefined;
  /** Another scene was swapped in (it may be traced by other kernels). */
  uploaded(): void;
  /** The geometry changed: what a selection outline traced is stale. */
  geometryChanged(): void;
  /** The scene was edited: specialised kernels are dropped and the estimate restarts. */
  edited(): void;
  /** The estimate restarts (the scene the same, its tile's geometry other). */
  restarted(): void;
}

export class SceneResidency {
  private preparedValue?: PreparedScene;
  private resourcesValue?: SceneResources;
  /** Counts uploads: a split frame holds the resources it began with. */
  private uploadCount = 0;
  /** The per-tile culled scenes while the tileCulling setting is on (and the scene has a walk map). */
  private tileCulled?: TileCulledScenes;
  /** Whether the instance records' previous transforms must be made current ('after-frame': once the next frame has used them). */
  private settle: 'no' | 'after-frame' | 'now' = 'no';
  /** CPU milliseconds of the last geometry update: bottom-level refits, the top-level build, packing. */
  lastUpdateMs?: GeometryUpdate['ms'];
  /** The switches of acceleration structure under way, one after another (switchAccel). */
  private accelPending: Promise<void> = Promise.resolve();

  constructor(
    private readonly device: GPUDevice,
    private readonly hooks: ResidencyHooks,
  ) {}

  get prepared(): PreparedScene | undefined {
    return this.preparedValue;
  }
  get resources(): SceneResources | undefined {
    return this.resourcesValue;
  }
  get uploads(): number {
    return this.uploadCount;
  }

  /** Compiles what the scene needs, then uploads it and frees the previous one (a failure leaves the old scene). */
  async upload(prepared: PreparedScene): Promise<void> {
    const compiling = this.hooks.compile(prepared.packed.features);
    // The scene uploads while the GPU driver compiles (its threads, not this one).
    const uploading = timedStage(this.device, 'upload scene', () => SceneResources.upload(this.device, prepared.packed, prepared.scene.name));
    const [compiled, uploaded] = await Promise.allSettled([compiling, uploading]);
    if (compiled.status === 'rejected') {
      if (uploaded.status === 'fulfilled') uploaded.value.destroy();
      throw compiled.reason;
    }
    if (uploaded.status === 'rejected') throw uploaded.reason;
    this.resourcesValue?.destroy();
    this.resourcesValue = uploaded.value;
    this.uploadCount++;
    this.preparedValue = prepared;
    this.hooks.geometryChanged();
    // A new scene: its own tiles, if the setting asks for them.
    this.tileCulled = undefined;
    this.configureTileCulling();
    // After the swap, so the idle timer it restarts sees the new scene.
    this.hooks.uploaded();
  }

  /**
   * Builds and uploads the static world again in the structure `accel()` names by the time the
   * switch runs, in the background (frames trace the current one meanwhile); one switch at a time,
   * so a quick bvh → grid → bvh ends on the BVH. accelSettled() waits for it.
   */
  switchAccel(accel: () => Accel): void {
    if (!this.preparedValue) return;
    this.accelPending = this.accelPending
      .catch(() => undefined)
      .then(() => (this.preparedValue && accelOf(this.preparedValue) !== accel() ? this.upload(withAccel(this.preparedValue, accel())) : undefined));
    this.accelPending.catch(() => undefined); // the error is accelSettled()'s to report
  }

  /** Resolves once the last switchAccel is done (rejects if building or uploading failed). */
  accelSettled(): Promise<void> {
    return this.accelPending;
  }

  /**
   * Renderer.applySceneUpdate: instances moved or changed material, meshes morphed, materials
   * animated. Geometry is refitted and its buffers rewritten in place (renderer/prepare.ts
   * updateGeometry), materials repacked (updateMaterials).
   */
  apply(update: SceneUpdate): PreparedScene {
    // The other tiles' scenes catch up when they are swapped in.
    this.tileCulled?.noteUpdate(update);
    return this.applyToCurrent(update);
  }

  private applyToCurrent(update: SceneUpdate): PreparedScene {
    const resources = this.resourcesValue;
    if (!resources || !this.preparedValue) throw new Error('Renderer: setScene() before applySceneUpdate()');
    if (update.instances.size > 0 || update.morphWeights.size > 0) {
      const { prepared, writes, attributes, ms } = updateGeometry(this.preparedValue, update.instances, update.morphWeights);
      this.writeScene(writes);
      if (attributes) writeTriangleAttributes(this.device, this.resourcesValue!.triangleAttributes, prepared.packed.triangleAttributes);
      this.preparedValue = prepared;
      this.lastUpdateMs = ms;
      this.hooks.geometryChanged();
      // The instance records now carry last frame's transforms as the previous ones: after one frame
      // with them, they are settled (previous = current) unless another update comes first.
      this.settle = prepared.levels ? 'after-frame' : 'no';
    }
    if (update.materials.size > 0) return this.updateMaterials(update.materials);
    this.hooks.edited();
    return this.preparedValue;
  }

  /** Writes a geometry update's buffers: in place, or anew for a whole buffer that grew (the light table). */
  private writeScene(writes: readonly BufferWrite[]): void {
    let resources = this.resourcesValue!;
    for (const w of writes) {
      if (w.name === 'instances') resources = resources.rewriteInstances(this.device, w.data);
      else if (w.offset === 0 && w.data.byteLength > resources.buffers[w.name].size) resources = resources.rewriteBuffer(this.device, w.name, w.data);
      else this.device.queue.writeBuffer(resources.buffers[w.name], w.offset, w.data);
    }
    this.resourcesValue = resources;
  }

  /** Before a frame: instances that stopped moving get previous = current (no motion vectors left over). */
  settleBeforeFrame(): void {
    const p = this.preparedValue;
    if (this.settle !== 'now' || !p?.levels) return;
    const bytes = packInstances(p.scene, p.levels, p.packed.layout, p.packed.packedMaterials, new Map());
    this.resourcesValue = this.resourcesValue!.rewriteInstances(this.device, bytes);
    this.settle = 'no';
  }

  /** After a frame: the previous transforms it used are settled before the next, unless an update comes first. */
  frameDone(): void {
    if (this.settle === 'after-frame') this.settle = 'now';
  }

  /**
   * Renderer.updateMaterials: the edited records are packed again and the materials buffer rewritten;
   * an emission edit also packs the light table again (renderer/prepare.ts editMaterials) and rewrites
   * it, reallocating the light-slot buffer alone where it grew (an emitter appeared).
   */
  updateMaterials(edits: ReadonlyMap<number, MaterialEdit>): PreparedScene {
    let resources = this.resourcesValue;
    if (!resources || !this.preparedValue) throw new Error('Renderer: setScene() before updateMaterials()');
    const { prepared, lightsChanged, textureRefsChanged } = editMaterials(this.preparedValue, edits);
    resources = resources.rewriteBuffer(this.device, 'materials', prepared.packed.materials);
    // Animated textures scroll by their texture references' transforms.
    if (textureRefsChanged) resources = resources.rewriteBuffer(this.device, 'texture_refs', prepared.packed.texture_refs);
    if (lightsChanged) for (const name of LIGHT_BUFFERS) resources = resources.rewriteBuffer(this.device, name, prepared.packed[name]);
    this.resourcesValue = resources;
    this.preparedValue = prepared;
    this.hooks.edited();
    return prepared;
  }

  /** What tile culling costs and saves, while it is on. */
  get tileCullingStats(): TileCullingStats | undefined {
    return this.tileCulled?.stats();
  }

  /** Builds or drops the per-tile scenes as the setting says (the scene as it is now is the full one). */
  configureTileCulling(): void {
    const want = this.hooks.tileCulling() && this.preparedValue !== undefined;
    if (!want) {
      const culled = this.tileCulled;
      this.tileCulled = undefined;
      // Back to the whole scene, caught up with what moved.
      if (culled && this.resourcesValue) this.swapGeometry(culled.full, culled.catchUp());
      return;
    }
    if (this.tileCulled) return;
    const config = defaultTileCulling(this.preparedValue!.scene);
    if (!config) return;
    this.tileCulled = TileCulledScenes.prepare(this.preparedValue!, config.grid, config.distance);
    const position = this.hooks.cameraPosition();
    if (position) this.swapTile(position);
  }

  /** With tile culling, the camera stepped onto another tile: that tile's geometry replaces the current. */
  swapTile(position: Vec3): void {
    if (!this.tileCulled || !this.resourcesValue) return;
    const selection = this.tileCulled.select(position);
    if (!selection.changed) return;
    this.swapGeometry(selection.prepared, selection.catchUp);
  }

  /** Writes another prepared scene's geometry (same materials, textures, environment) and catches it up with the world. */
  private swapGeometry(prepared: PreparedScene, catchUp: SceneUpdate | undefined): void {
    let resources = this.resourcesValue!;
    for (const name of TILE_SWAP_BUFFERS) resources = name === 'instances' ? resources.rewriteInstances(this.device, prepared.packed.instances) : resources.rewriteBuffer(this.device, name, prepared.packed[name]);
    this.resourcesValue = resources;
    if (prepared.packed.triangleAttributes.height === 1) writeTriangleAttributes(this.device, resources.triangleAttributes, prepared.packed.triangleAttributes);
    this.preparedValue = prepared;
    this.hooks.geometryChanged();
    if (catchUp && !isEmptyUpdate(catchUp)) this.applyToCurrent(catchUp);
    this.hooks.restarted();
  }

  /** Frees the scene's GPU resources. */
  destroy(): void {
    this.resourcesValue?.destroy();
    this.resourcesValue = undefined;
  }
}
