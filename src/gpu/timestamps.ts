/**
 * GPU pass timings from timestamp queries. One GpuTimer measures up to `capacity` passes per
 * resolve: each pass asks for `timestampWrites(name)`, then `resolve(encoder)` and `read()` give
 * milliseconds per pass. Where the adapter has no timestamp queries the timer is absent and callers
 * fall back to wall-clock time around `onSubmittedWorkDone`.
 */
export class GpuTimer {
  private readonly querySet: GPUQuerySet;
  private readonly resolveBuffer: GPUBuffer;
  private readonly readBuffer: GPUBuffer;
  private names: string[] = [];

  constructor(device: GPUDevice, readonly capacity = 64) {
    this.querySet = device.createQuerySet({ label: 'pass timestamps', type: 'timestamp', count: capacity * 2 });
    this.resolveBuffer = device.createBuffer({ label: 'timestamp resolve', size: capacity * 16, usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC });
    this.readBuffer = device.createBuffer({ label: 'timestamp read', size: capacity * 16, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
  }

  /** Passes that can still be timed before the next read. */
  get room(): number {
    return this.capacity - this.names.length;
  }

  /** The `timestampWrites` of a compute or render pass descriptor, recording a pass named `name`. */
  timestampWrites(name: string): GPUComputePassTimestampWrites {
    if (this.names.length >= this.capacity) throw new Error(`GpuTimer holds at most ${this.capacity} passes per resolve`);
    const i = this.names.length;
    this.names.push(name);
    return { querySet: this.querySet, beginningOfPassWriteIndex: 2 * i, endOfPassWriteIndex: 2 * i + 1 };
  }

  /** Forgets the passes recorded since the last read (a frame given up before its resolve): their slots are reused. */
  discard(): void {
    this.names = [];
  }

  /** Records the copy of this round's timestamps; call once after the timed passes, then submit. */
  resolve(encoder: GPUCommandEncoder): void {
    const n = this.names.length;
    if (n === 0) return;
    encoder.resolveQuerySet(this.querySet, 0, 2 * n, this.resolveBuffer, 0);
    encoder.copyBufferToBuffer(this.resolveBuffer, 0, this.readBuffer, 0, 16 * n);
  }

  /** Milliseconds of each pass recorded since the last read, in recording order. */
  async read(): Promise<{ name: string; ms: number }[]> {
    const names = this.names;
    this.names = [];
    if (names.length === 0) return [];
    await this.readBuffer.mapAsync(GPUMapMode.READ, 0, 16 * names.length);
    const t = new BigUint64Array(this.readBuffer.getMappedRange(0, 16 * names.length).slice(0));
    this.readBuffer.unmap();
    return names.map((name, i) => ({ name, ms: Number(t[2 * i + 1]! - t[2 * i]!) / 1e6 }));
  }

  destroy(): void {
    this.querySet.destroy();
    this.resolveBuffer.destroy();
    this.readBuffer.destroy();
  }
}
