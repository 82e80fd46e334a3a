/**
 * What a long-lived process keeps from one command to the next (the farm's chunk server,
 * farm/chunk-server.ts): the GPU device, and the last scene as it was loaded and prepared, keyed by
 * what loaded it (session.ts openSession). Each command still gets a fresh Renderer and its own copy
 * of the prepared scene, so it renders exactly what a fresh process would: what is saved is the
 * process, Dawn's start, the scene's load and BVH, and the compiles (a device makes a pipeline it
 * already made at no cost).
 */
import type { GpuContext } from '../gpu/device.ts';
import type { LoadedPrepared } from './scene-thread.ts';

export interface SessionCache {
  gpu?: Promise<GpuContext>;
  scene?: { readonly key: string; readonly loading: Promise<LoadedPrepared> };
}
