/**
 * Every finding of issue 17's table as a test, on inputs built in code (crafted.ts): each one once
 * crashed (a stack overflow), hung (quadratic repair, a linear scan per patch) or took gigabytes (a
 * gzip bomb, textures and images sized from a header). Each must now load, or be refused in one line
 * naming the limit and the value found, without the memory it used to take.
 */
import { describe, expect, it } from 'vitest';
import { applyLimitsOption, configureLimits, DEFAULT_LIMITS, limits, parseLimits, withLimits, WarningCap, type Limits } from '../../src/budgets.ts';
import { LanternError } from '../../src/errors.ts';
import { expectLanternError } from '../../src/expect-lantern-error.ts';
import { decodeExr } from '../../src/image/exr.ts';
import { loadDoomMap, summarizeMaps } from '../../src/loaders/doom/load.ts';
import { buildSectorShapes } from '../../src/loaders/doom/sectors.ts';
import { DoomGraphics } from '../../src/loaders/doom/textures.ts';
import { readWad, WadStack } from '../../src/loaders/doom/wad.ts';
import { NO_SIBLINGS } from '../../src/loaders/format.ts';
import { MOLECULE_FORMAT } from '../../src/loaders/molecule/format.ts';
import { GLTF_FORMAT } from '../../src/loaders/gltf/format.ts';
import { parsePly } from '../../src/loaders/ply/ply.ts';
import { glb, gltfSeed, mutateWad, plyBomb } from './targets.ts';
import { Rng } from './mutate.ts';
import { WadBuilder } from '../../src/loaders/doom/test-wad.ts';
import { bigSectorMap, bigTexturesWad, danglingSegmentsMap, gridMap, gzipBomb, hugeExr, manyLumpsWad, missingPatchesWad, noPlayerStartMap, randomLinesMap, wadOf } from './crafted.ts';
import { countBombGltf, externalBufferGltf, pngStreamBomb, progressiveJpeg, sharedImageGlb, zeroScaleGltf } from './crafted.ts';
import { decodePng, encodePng } from '../../src/image/png.ts';
import type { ResolveSibling } from '../../src/loaders/format.ts';
import { frameTime, parseCameraPath } from '../../src/scene/camera-path.ts';
import type { Scene } from '../../src/scene/types.ts';
import { continuedLineMolfile, hubMolfile, v3000Molfile, wolfWarningFloodFiles } from './crafted.ts';
import { formatOfSet } from '../../src/loaders/registry.ts';
import { packEnvironment } from '../../src/gpu/pack/environment-pack.ts';
import { loadEnvironmentImage } from '../../src/loaders/environment-image.ts';
import { constantHdr } from './crafted.ts';
import { parseSdf } from '../../src/loaders/molecule/sdf.ts';
import { moleculeMesh } from '../../src/loaders/molecule/to-scene.ts';
import type { Molecule } from '../../src/loaders/molecule/molfile.ts';

const stackOf = (bytes: Uint8Array) => new WadStack([readWad(bytes, 'crafted.wad')]);

/** The one-line refusal of a limit: a LanternError naming it and the value found. */
function expectRefusal(f: () => unknown, limit: string): LanternError {
  const thrown = expectLanternError(f);
  const message = thrown.userMessage;
  expect(message).toContain(`over the limit ${limit}=`);
  expect(message).not.toContain('\n');
  return thrown;
}

describe('Doom maps that crashed', () => {
  it('builds a sector of 65,000 vertices (push(...coords) overflowed the stack)', () => {
    const map = bigSectorMap(65_000);
    const { shapes, failures } = buildSectorShapes(map);
    expect(failures).toEqual([]);
    // The rectangle (65,000 − 3) × 1000, triangulated exactly.
    expect(shapes[0]!.area).toBe(64_997 * 1000);
  });

  it('places the camera over 140,000 vertices without a player start (Math.min(...xs) overflowed)', () => {
    const stack = stackOf(wadOf([noPlayerStartMap(140_000)]));
    const warnings: string[] = [];
    const load = loadDoomMap(stack, 'MAP01', { onWarning: (w) => warnings.push(w) });
    expect(warnings.some((w) => w.includes('no player 1 start'))).toBe(true);
    // Crafted vertices span x in [-128, 383]: the middle is at 127.5 map units, 127.5/32 m... in world x.
    expect(Number.isFinite(load.scene.camera.position[0])).toBe(true);
  });

  it('lists every map when one of them breaks the loader: the error is that map\'s, the others are summarised', () => {
    // MAP02's linedef names a sidedef whose sector index is far past the end: a LanternError-free
    // path would have to survive it; a broken map must not hide MAP01 in any case.
    const good = { ...noPlayerStartMap(0), name: 'MAP01' };
    const broken = { ...bigSectorMap(10), name: 'MAP02', sectors: [] };
    const summaries = summarizeMaps(stackOf(wadOf([good, broken])));
    expect(summaries.map((s) => s.name)).toEqual(['MAP01', 'MAP02']);
    expect(summaries[0]!.error).toBeUndefined();
    expect(summaries[1]!.error).toMatch(/^MAP02 in crafted.wad has no (usable linedefs|sectors)/);
  });
});

describe('Doom geometry that was quadratic', () => {
  it('repairs 20,000 dangling segments by failing that sector alone, and loads the map', () => {
    const map = danglingSegmentsMap(20_000);
    const before = process.memoryUsage().rss;
    const warnings: string[] = [];
    const cap = new WarningCap((w) => warnings.push(w));
    const { shapes, failures } = buildSectorShapes(map, cap.warn);
    cap.finish();
    expect(failures.map((f) => f.sector)).toEqual([1]);
    expect(failures[0]!.reason).toMatch(/sectorWork=/);
    expect(shapes[0]!.area).toBe(4160 * 4160);
    expect(process.memoryUsage().rss - before).toBeLessThan(512 * 2 ** 20);
    // Warnings of each kind are capped, with one closing line per kind.
    expect(warnings.length).toBeLessThan(200);
  });

  it('with the budget raised, the same sector is repaired (its lines are joined or dropped, none is lost)', () => {
    const { failures } = withLimits({ sectorWork: 1e9 }, () => buildSectorShapes(danglingSegmentsMap(400)));
    expect(failures.filter((f) => /sectorWork/.test(f.reason))).toEqual([]);
  });

  it('builds a 106,260-linedef grid of 52,900 sectors, each exactly its square', () => {
    const map = gridMap(230);
    expect(map.linedefs.length).toBe(106_260);
    const { shapes, failures } = buildSectorShapes(map);
    expect(failures).toEqual([]);
    expect(shapes.every((s) => s.area === 64 * 64)).toBe(true);
  });

  it('loads 30,000 random linedefs: nonsense geometry costs warnings and failed sectors, not minutes', () => {
    const stack = stackOf(wadOf([randomLinesMap(30_000, 20_000, 300)]));
    const warnings: string[] = [];
    const load = loadDoomMap(stack, 'MAP01', { onWarning: (w) => warnings.push(w) });
    expect(load.linedefs).toBe(30_000);
    // Capped: at most warningsPerKind of each kind plus one closing line per kind.
    const closing = warnings.filter((w) => w.startsWith('… and '));
    expect(closing.length).toBeGreaterThan(0);
    expect(warnings.length).toBeLessThan(40 * (limits().warningsPerKind + 1));
  });
});

describe('Doom lookups that scanned', () => {
  it('resolves 8,000 missing patches behind 20,000 lumps through the index, with capped warnings', () => {
    const stack = stackOf(missingPatchesWad(8000, 20_000));
    const warnings: string[] = [];
    const cap = new WarningCap((w) => warnings.push(w));
    const graphics = new DoomGraphics(stack, { onWarning: cap.warn });
    for (const name of graphics.textureNames()) graphics.texture(name);
    cap.finish();
    expect(graphics.textureNames()).toHaveLength(8000);
    expect(warnings).toHaveLength(limits().warningsPerKind + 1);
    expect(warnings.at(-1)).toMatch(/^… and 7,980 more warnings like "texture MP0: skipped patch MP0P: no such lump in the WADs"/);
  });

  it('reads a directory of 200,000 lumps and finds its map', () => {
    const stack = stackOf(manyLumpsWad(200_000));
    expect(stack.maps().map((m) => m.name)).toEqual(['MAP01']);
    expect(stack.files[0]!.lumps.length).toBeGreaterThan(200_000);
  });
});

describe('sizes asked for by headers', () => {
  it('refuses the 48 textures of 4096² of a 23 KB WAD at the texel limit, before allocating them', () => {
    // The default allows 8 such textures (512 MiB); at a tenth of that the test stays small and the
    // arithmetic is the same.
    expect(48 * 4096 ** 2).toBeGreaterThan(DEFAULT_LIMITS.textureTexels);
    const bytes = bigTexturesWad(48, 4096);
    expect(bytes.length).toBeLessThan(24_000);
    withLimits({ textureTexels: 3 * 4096 ** 2 }, () => {
      const graphics = new DoomGraphics(stackOf(bytes));
      for (const i of [0, 1, 2]) expect(graphics.texture(`BIG${i}`)!.width).toBe(4096);
      const refusal = expectRefusal(() => graphics.texture('BIG3'), 'textureTexels');
      expect(refusal.message).toContain('67,108,864');
      expect(refusal.message).toContain('BIG3');
    });
  });

  it('refuses a gzip bomb while inflating, at the decompressed-bytes limit', () => {
    // 32 MiB of zeros in 32 KB behind a PLY header within the counts; refused at a limit of 4 MiB as
    // the default refuses gigabytes. (Zeros alone are refused as no PLY once the header's MiB is in.)
    const bomb = plyBomb({ bytes: 32 * 2 ** 20, vertices: 1000, faces: 1 });
    expect(bomb.length).toBeLessThan(50_000);
    expectLanternError(() => parsePly(gzipBomb(32 * 2 ** 20), 'zeros.ply.gz'), /zeros\.ply\.gz: not a PLY file/);
    const refusal = withLimits({ decompressedBytes: 4 * 2 ** 20 }, () => expectRefusal(() => parsePly(bomb, 'bomb.ply.gz'), 'decompressedBytes'));
    // Inflating stopped soon after the limit, not at the end of the stream.
    const inflated = Number(/at least\): ([\d,]+)/.exec(refusal.message)![1]!.replaceAll(',', ''));
    expect(inflated).toBeGreaterThan(4 * 2 ** 20);
    expect(inflated).toBeLessThan(32 * 2 ** 20);
  });

  it('inflates gzip whole whether or not the trailer\'s size is right (two members: it names only the last)', async () => {
    const { gunzipCapped } = await import('../../src/loaders/gzip.ts');
    const { gzipSync } = await import('node:zlib');
    const [a, b] = [new Uint8Array(300_000).fill(7), new Uint8Array(5000).fill(9)];
    const one = gunzipCapped(new Uint8Array(gzipSync(a)), 'one.gz');
    const two = gunzipCapped(new Uint8Array([...gzipSync(a), ...gzipSync(b)]), 'two.gz');
    expect(one).toEqual(a);
    expect(two.length).toBe(305_000);
    expect(two.subarray(300_000).every((x) => x === 9)).toBe(true);
  });

  it('refuses an EXR claiming 100,000² pixels from its header, and one claiming 8,000² at the pixel limit', () => {
    expect(() => decodeExr(hugeExr(100_000, 100_000, 410_000), 'huge.exr')).toThrow(/far larger than the file could hold/);
    // 8,000² half RGB pixels could come from 410 KB of deflate, so only the pixel limit refuses them.
    expectRefusal(() => decodeExr(hugeExr(8000, 8000, 410_000), 'big.exr'), 'imagePixels');
  });

  it('refuses a PLY face of a million corners at the polygon limit', () => {
    const corners = 1_000_000;
    const header = `ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n`;
    const head = new TextEncoder().encode(header);
    const bytes = new Uint8Array(head.length + 36 + 4 + 4 * corners);
    bytes.set(head);
    new DataView(bytes.buffer).setUint32(head.length + 36, corners, true);
    expect(() => parsePly(bytes, 'ngon.ply')).toThrow(/polygonVertices=65536/);
  });
});

describe('findings of the fuzz suite', () => {
  it('builds a molecule whose double bond reaches an atom at -1e308 Å (the bond side normalised a zero vector)', async () => {
    const text = ['m', '  Lantern           3D', '', '  2  1  0     0  0  0  0  0  0999 V2000',
      '    0.4700    2.5688    0.0006 O   0  0  0  0  0  0  0  0  0  0  0  0',
      '    -1e308    0.2592   -0.0008 C   0  0  0  0  0  0  0  0  0  0  0  0',
      '  1  2  2  0  0  0  0', 'M  END', ''].join('\n');
    const opened = await MOLECULE_FORMAT.open({ files: [{ name: 'far.mol', bytes: new TextEncoder().encode(text) }], resolve: NO_SIBLINGS });
    await expect(opened.scene()).resolves.toBeDefined();
  });

  it('leaves out a glTF attribute whose count is not POSITION\'s (it was read past its end: a RangeError)', async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const accessors = json.accessors as Array<Record<string, unknown>>;
    // TEXCOORD_0 read as 4 VEC2s from the 36-byte position view: in bounds, but one more than the 3 vertices.
    accessors[1] = { ...accessors[1], bufferView: 0, count: 4 };
    const opened = await GLTF_FORMAT.open({ files: [{ name: 'uv.glb', bytes: glb(json, bin) }], resolve: NO_SIBLINGS });
    const warnings: string[] = [];
    const scene = await opened.scene(undefined, { onWarning: (w) => warnings.push(w) });
    expect(warnings).toContain("mesh 'mesh 0' has 4 TEXCOORD_0 values for 3 vertices; TEXCOORD_0 is ignored there");
    expect(scene.meshes[0]!.uvs).toBeUndefined();
  });
});

describe('recursion', () => {
  it('places a mesh at the end of a chain of 20,000 nested glTF nodes (the visit recursed once per level)', async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const depth = 20_000;
    const nodes = Array.from({ length: depth }, (_, i) => (i + 1 < depth ? { children: [i + 1] } : { mesh: 0 }));
    const opened = await GLTF_FORMAT.open({ files: [{ name: 'deep.glb', bytes: glb({ ...json, nodes, scenes: [{ nodes: [0] }] }, bin) }], resolve: NO_SIBLINGS });
    const scene = await opened.scene();
    expect(scene.instances).toHaveLength(1);
    expect(scene.instances[0]!.id).toBe(depth - 1);
  });
});

describe('limits', () => {
  it('parses name=value lists with k/M/G suffixes and refuses unknown names and bad values in one line', () => {
    expect(parseLimits('imagePixels=256M, sectorWork=1e9').imagePixels).toBe(256 * 2 ** 20);
    expect(parseLimits('sectorWork=1e9').sectorWork).toBe(1e9);
    expect(parseLimits('').vertices).toBe(DEFAULT_LIMITS.vertices);
    expect(() => parseLimits('pixels=5')).toThrow(/unknown limit 'pixels'/);
    expect(() => parseLimits('vertices=-5')).toThrow(/bad value for limit vertices/);
    expect(() => parseLimits('vertices')).toThrow(/expected name=value/);
  });

  it('takes --limits over LANTERN_LIMITS and hands the result to worker threads through the environment', () => {
    const saved = process.env.LANTERN_LIMITS;
    try {
      process.env.LANTERN_LIMITS = 'lumps=5,faces=7';
      configureLimits(undefined);
      applyLimitsOption('lumps=9');
      expect([limits().lumps, limits().faces]).toEqual([9, 7]);
      expect(parseLimits(process.env.LANTERN_LIMITS)).toEqual(limits());
    } finally {
      if (saved === undefined) delete process.env.LANTERN_LIMITS;
      else process.env.LANTERN_LIMITS = saved;
      configureLimits(undefined);
    }
    expect(limits().lumps).toBe(DEFAULT_LIMITS.lumps);
  });
});

describe('the fuzzer itself', () => {
  it('mutates a WAD whose lumps are all empty (the 5-minute run failed twice building such an input)', () => {
    const empty = new WadBuilder().lump('MAP01', new Uint8Array(0)).lump('THINGS', new Uint8Array(0)).build('PWAD');
    for (let seed = 1; seed <= 300; seed++) {
      const rng = new Rng(seed);
      expect(mutateWad(rng, empty)).toBeInstanceOf(Uint8Array);
    }
  });
});

// ---- issue 27 §6: glTF counts, images, degenerate nodes, camera paths, URIs ----

/** withLimits for async work: the limits stay changed until `f`'s promise settles. */
async function withLimitsAsync<T>(changes: Partial<Limits>, f: () => Promise<T>): Promise<T> {
  const before = limits();
  configureLimits(changes);
  try {
    return await f();
  } finally {
    configureLimits(before);
  }
}

/** The glTF loader as `lantern info` runs it: the scene and its warnings, or the LanternError. */
async function loadGltfFile(name: string, bytes: Uint8Array, resolve: ResolveSibling = NO_SIBLINGS): Promise<{ scene: Scene; warnings: string[] }> {
  const opened = await GLTF_FORMAT.open({ files: [{ name, bytes }], resolve });
  const warnings: string[] = [];
  const scene = await opened.scene(undefined, { onWarning: (w) => warnings.push(w) });
  return { scene, warnings };
}

/** Awaits a refusal: a one-line LanternError whose message matches. */
async function expectGltfRefusal(load: Promise<unknown>, pattern: RegExp): Promise<string> {
  const thrown = await load.then(() => undefined, (e: unknown) => e);
  expect(thrown).toBeInstanceOf(LanternError);
  const message = (thrown as LanternError).userMessage;
  expect(message).toMatch(pattern);
  expect(message).not.toContain('\n');
  return message;
}

const rssGrowth = async (f: () => Promise<unknown>) => {
  const before = process.memoryUsage().rss;
  await f();
  return process.memoryUsage().rss - before;
};

describe('glTF counts read from the JSON before anything is allocated (issue 27)', () => {
  it('refuses 1.5e8 vertices without a buffer view (268 bytes that aborted V8 at 2.5 GB) at the vertex limit, allocating nothing', async () => {
    const bytes = countBombGltf('positions', 1.5e8);
    expect(bytes.length).toBeLessThan(300);
    const growth = await rssGrowth(() => expectGltfRefusal(loadGltfFile('positions.gltf', bytes), new RegExp(`vertices of the meshes it places: 150,000,000 is over the limit vertices=${DEFAULT_LIMITS.vertices.toLocaleString('en-US')}`)));
    expect(growth).toBeLessThan(64 * 2 ** 20);
  });

  it('refuses what the limits refuse, not more: a zero-filled accessor under the vertex limit loads, one over it is refused', async () => {
    await withLimitsAsync({ vertices: 3000 }, async () => {
      const { scene } = await loadGltfFile('ok.gltf', countBombGltf('positions', 3000));
      expect(scene.meshes[0]!.positions.length).toBe(9000);
      await expectGltfRefusal(loadGltfFile('over.gltf', countBombGltf('positions', 3003)), /3,003 is over the limit vertices=3,000/);
    });
  });

  it('counts the triangles of every placement against faces: 10,000 nodes placing one mesh', async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const nodes = Array.from({ length: 10_000 }, () => ({ mesh: 0 }));
    const bytes = glb({ ...json, nodes, scenes: [{ nodes: nodes.map((_, i) => i) }] }, bin);
    await withLimitsAsync({ faces: 9_999 }, () => expectGltfRefusal(loadGltfFile('many.glb', bytes), /triangles in the scene .*: 10,000 is over the limit faces=9,999/));
    await withLimitsAsync({ faces: 10_000 }, async () => expect((await loadGltfFile('many.glb', bytes)).scene.instances).toHaveLength(10_000));
  });

  it('refuses 1e9 indices without a buffer view (13 s and 3.9 GB) at the triangle limit', async () => {
    await expectGltfRefusal(loadGltfFile('indices.gltf', countBombGltf('indices', 1e9)), /333,333,333 is over the limit faces=/);
  });

  it('refuses a sparse count of 1e9 over a 3-element accessor (it ran for minutes) as damaged', async () => {
    await expectGltfRefusal(loadGltfFile('sparse.gltf', countBombGltf('sparse', 1e9)), /accessor 0: its sparse count 1,000,000,000 is not from 1 to its count 3/);
  });

  it('refuses 1e9 strided elements over a 36-byte view, naming the bytes it would read', async () => {
    await expectGltfRefusal(loadGltfFile('interleaved.gltf', countBombGltf('interleaved', 1e9)), /accessor 0 reads 15,999,999,996 bytes of buffer view 0, which has 36/);
  });

  it('refuses 1e7 EXT_mesh_gpu_instancing rows (4.5 GB) at the instance limit', async () => {
    await expectGltfRefusal(loadGltfFile('instances.gltf', countBombGltf('instances', 1e7)), /instances \(nodes with a mesh, EXT_mesh_gpu_instancing rows\): 10,000,000 is over the limit instances=/);
    await withLimitsAsync({ instances: 1000 }, async () => expect((await loadGltfFile('instances.gltf', countBombGltf('instances', 1000))).scene.instances).toHaveLength(1000));
  });

  it('sums the bytes glTF-Transform copies: a thousand accessors reading one view are a thousand copies', async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const accessors = [...(json.accessors as object[]), ...Array.from({ length: 1000 }, () => ({ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }))];
    await withLimitsAsync({ gltfBytes: 1000 * 36 }, () => expectGltfRefusal(loadGltfFile('aliased.glb', glb({ ...json, accessors }, bin)), /bytes of accessor and image data to read: 36,\d{3} is over the limit gltfBytes=36,000/));
  });

  it('refuses a missing buffer that declares 10^12 bytes (its zero-filled stand-in threw a RangeError)', async () => {
    const text = new TextDecoder().decode(externalBufferGltf('absent.bin')).replace('"byteLength":36,"uri"', '"byteLength":1000000000000,"uri"');
    await expectGltfRefusal(loadGltfFile('huge.gltf', new TextEncoder().encode(text)), /buffer 0 declares 1,000,000,000,000 bytes/);
  });
});

describe('glTF images charged before decoding, decoded once (issue 27)', () => {
  it('makes one texture of 100 images sharing one PNG, charged once to the texel budget', async () => {
    const png = encodePng(64, 64, new Uint8Array(64 * 64 * 4).fill(200));
    // The budget holds the image once: each glTF image charged separately, the second was refused.
    const { scene, warnings } = await withLimitsAsync({ textureTexels: 64 * 64 }, () => loadGltfFile('shared.glb', sharedImageGlb(100, png)));
    expect(scene.textures).toHaveLength(1);
    expect(scene.materials.every((m) => m.kind === 'metallic-roughness' && m.baseColorTexture?.texture === 0)).toBe(true);
    expect(warnings.filter((w) => w.includes('replaced by a neutral one'))).toEqual([]);
  });

  it('refuses an image over the texel budget from its header, without decoding it', async () => {
    // A valid IHDR of 4096² and a stream that is no zlib: decoded first, the warning was a decoding error.
    const png = encodePng(4096, 4096, new Uint8Array(4096 * 4096 * 4), () => new Uint8Array([1, 2, 3, 4]));
    const { warnings } = await withLimitsAsync({ textureTexels: 4096 * 4096 - 1 }, () => loadGltfFile('big.glb', sharedImageGlb(2, png)));
    expect(warnings).toEqual([expect.stringMatching(/^texture image 0 \(material 'material 0'\) is replaced by a neutral one: texture texels \(with image 0, 4096×4096\): 16,777,216 is over the limit textureTexels=16,777,215/)]);
  });

  it('does not decode a progressive JPEG of 30,000 scans (each a pass over the image: past 60 s); one of 32 decodes', async () => {
    const flood = progressiveJpeg(1024, 1024, 30_000);
    const { scene, warnings } = await loadGltfFile('scans.glb', sharedImageGlb(1, flood));
    expect(warnings[0]).toMatch(/^texture image 0 \(material 'material 0'\) is replaced by a neutral one: it is a JPEG of more than 32 scans/);
    expect(scene.textures![0]!.width).toBe(1);
    // progressiveJpeg(…, n) writes a DC scan and n AC scans.
    const most = await loadGltfFile('most.glb', sharedImageGlb(1, progressiveJpeg(256, 128, 31)));
    expect([most.scene.textures![0]!.width, most.scene.textures![0]!.height]).toEqual([256, 128]);
    const over = await loadGltfFile('over.glb', sharedImageGlb(1, progressiveJpeg(256, 128, 32)));
    expect(over.scene.textures![0]!.width).toBe(1);
  });

  it('refuses a PNG whose stream inflates past its pixels (16² inflating to 512 MB: 8 s and 1.5 GB) after inflating a slice', () => {
    const bomb = pngStreamBomb(16, 512 * 2 ** 20);
    expect(bomb.length).toBeLessThan(600_000);
    expectLanternError(() => decodePng(bomb, 'bomb.png'), /bomb\.png: its image data inflates past the 1,040 bytes its 16×16 pixels need/);
    // The same construction at its real size decodes.
    expect(decodePng(pngStreamBomb(16, 1040), 'exact.png').width).toBe(16);
  });
});

describe('glTF nodes that collapse what they carry (issue 27)', () => {
  it.each(['camera', 'spot', 'directional'] as const)('leaves out a %s on a zero-scaled node with a warning (it was an internal error)', async (what) => {
    const { scene, warnings } = await loadGltfFile(`${what}.gltf`, zeroScaleGltf(what));
    expect(warnings).toContainEqual(expect.stringMatching(what === 'camera' ? /^the camera 'camera' is left out: its node's transform collapses its view/ : new RegExp(`^the ${what} light 'light 0' is left out: its node's transform gives it no direction`)));
    expect(scene.lights).toEqual([]);
    // The framing of the model replaces a camera left out.
    expect(Number.isFinite(scene.camera.forward[2])).toBe(true);
  });

  it('keeps a point light on a zero-scaled node: it needs no direction', async () => {
    const { scene } = await loadGltfFile('point.gltf', zeroScaleGltf('point'));
    expect(scene.lights).toEqual([expect.objectContaining({ kind: 'point', position: [0, 0, 0] })]);
  });

  it('leaves out a mesh whose node transform is past the float range (1e308 scales nested), keeping the rest', async () => {
    const text = new TextDecoder().decode(zeroScaleGltf('mesh')).replace('"nodes":[{"mesh":0},{"mesh":0,"scale":[0,0,0]}]', '"nodes":[{"mesh":0},{"scale":[1e308,1e308,1e308],"children":[2]},{"mesh":0,"scale":[1e308,1e308,1e308]}]');
    const { scene, warnings } = await loadGltfFile('far.gltf', new TextEncoder().encode(text));
    expect(scene.instances.map((i) => i.id)).toEqual([0]);
    expect(warnings).toContain("node 2's transform is past the float range: the mesh it places is left out there");
  });
});

describe('camera paths at the edges of the float range (issue 27)', () => {
  it('refuses keyframes at ±1e308 seconds (their span is infinite: NaN frame times, then an internal error), naming the keyframe', () => {
    const path = { keyframes: [{ time: -1e308, position: [0, 0, 5], target: [0, 0, 0] }, { time: 1e308, position: [0, 1, 5], target: [0, 0, 0] }] };
    expectLanternError(() => parseCameraPath(path, 'path.json'), /^path\.json: keyframe 0: "time" must be a number of seconds from -1000000 to 1000000$/);
    const ok = parseCameraPath({ keyframes: [{ ...path.keyframes[0], time: -1e6 }, { ...path.keyframes[1], time: 1e6 }] });
    expect(frameTime(ok, 15, 31)).toBe(0);
  });
});

describe('what a glTF may name (issue 27)', () => {
  /** A resolver that serves `files` and records what it was asked for. */
  const recording = (files: Record<string, Uint8Array>) => {
    const asked: string[] = [];
    const resolve: ResolveSibling = (uri) => {
      asked.push(uri);
      return Promise.resolve(files[uri]);
    };
    return { asked, resolve };
  };
  const triangle = new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);

  it.each([
    ['../../../../../../etc/hostname', "it leads out of the model's folder"],
    ['%2e%2e/secret.bin', "it leads out of the model's folder"],
    ['/etc/hostname', 'it is an absolute path'],
    ['file:///etc/hostname', 'it is a URL (file:), not a path beside the model'],
    ['https://example.com/x.bin', 'it is a URL (https:), not a path beside the model'],
  ])('never asks for %s, and says why in one line', async (uri, reason) => {
    const { asked, resolve } = recording({ [uri]: triangle });
    const message = await expectGltfRefusal(loadGltfFile('escape.gltf', externalBufferGltf(uri), resolve), /nothing to show/);
    expect(message).toBe(`escape: nothing to show, the geometry is in ${uri}, which Lantern does not read (${reason}). A model may name only files in its own folder and below: put the file in the model's folder and name it by a relative path`);
    expect(asked).toEqual([]);
  });

  it('reads files below its folder, by the decoded path, each once however many images name it', async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const png = encodePng(2, 2, new Uint8Array(16).fill(9));
    const images = Array.from({ length: 3 }, () => ({ uri: 'tex/../tex/wood%20grain.png' }));
    const { asked, resolve } = recording({ 'tex/../tex/wood%20grain.png': png });
    const { scene, warnings } = await loadGltfFile('model.glb', glb({ ...json, images, textures: [{ source: 0 }, { source: 1 }, { source: 2 }] }, bin), resolve);
    expect(asked).toEqual(['tex/../tex/wood%20grain.png']);
    expect(scene.textures![0]!.width).toBe(2);
    expect(warnings.filter((w) => w.includes('missing') || w.includes('not read'))).toEqual([]);
  });

  it("names a refused texture as a missing one, with the reason, and loads the rest", async () => {
    const { json, bin } = gltfSeed(new Rng(1));
    const { scene, warnings } = await loadGltfFile('model.glb', glb({ ...json, images: [{ uri: '../shared/wood.png' }] }, bin));
    expect(warnings).toContain("../shared/wood.png is not read (it leads out of the model's folder; a model may name only files in its own folder and below): textures that use it are replaced by neutral ones");
    expect(scene.instances).toHaveLength(1);
  });

  it("offers `lantern view` only the files it may name", () => {
    const json = { asset: { version: '2.0' }, buffers: [{ uri: 'a.bin', byteLength: 1 }, { uri: '../b.bin', byteLength: 1 }, { uri: 'data:,x', byteLength: 1 }], images: [{ uri: 'tex/./c%20d.png' }, { uri: 'file:///etc/hostname' }, { uri: '/etc/hostname' }] };
    expect(GLTF_FORMAT.siblings!({ name: 'm.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) })).toEqual(['a.bin', 'tex/c d.png']);
  });
});

describe('issue 27: molecules that were quadratic or unbounded', () => {
  it('reads an atom line continued over 200,000 lines (each continuation re-joined the whole line: 32 s at 100,000)', () => {
    const [m] = parseSdf(continuedLineMolfile(200_000), 'continued.mol');
    expect(m!.atoms.map((a) => [a.element.symbol, ...a.position])).toEqual([['C', 0, 0, 0], ['O', 1.2, 0, 0]]);
    expect(m!.bonds).toEqual([{ a: 0, b: 1, type: 2 }]);
  });

  it('draws 20,000 double bonds on one atom, each beside its axis (each bond looked at every other: 77 s)', () => {
    for (const collinear of [false, true]) {
      const [m] = parseSdf(hubMolfile(20_000, 2, collinear), 'hub.mol');
      const { mesh } = moleculeMesh(m!);
      const e = mesh.capsules!.endpoints;
      expect(mesh.capsules!.radii).toHaveLength(40_000);
      // Capsule 2k is bond k's first line: its start sits DOUBLE_OFFSET (0.13 Å) off the carbon at the origin.
      for (const k of [0, 9_999, 19_999]) expect(Math.hypot(e[12 * k]!, e[12 * k + 1]!, e[12 * k + 2]!)).toBeCloseTo(0.13, 5);
    }
  });

  it('looks at a bounded number of neighbours per bond: the work of a hub atom grows linearly with its bonds', () => {
    // Reads of molecule.bonds[i], counted through a proxy: the old side direction filtered every bond
    // for each bond (4 million reads for 2,000 bonds).
    const reads = (n: number) => {
      const [m] = parseSdf(hubMolfile(n, 2, true), 'hub.mol');
      let count = 0;
      const bonds = new Proxy(m!.bonds as Molecule['bonds'][number][], {
        get(target, key, receiver) {
          if (typeof key === 'string' && /^\d+$/.test(key)) count++;
          return Reflect.get(target, key, receiver);
        },
      });
      moleculeMesh({ ...m!, bonds });
      return count;
    };
    const [small, large] = [reads(200), reads(2000)];
    expect(large).toBeLessThan(12 * small);
    expect(large).toBeLessThan(100 * 2000);
  });

  it('refuses V3000 COUNTS over the moleculeRecords limit from the COUNTS line, before the blocks are read', () => {
    // The atom block after it is broken: a refusal naming COUNTS's line proves nothing past it was read.
    const text = v3000Molfile(['1 C x 0 0 0'], [], '1000000000000000 0');
    const refusal = expectRefusal(() => parseSdf(text, 'counts.mol'), 'moleculeRecords');
    expect(refusal.userMessage).toMatch(/^counts\.mol: atoms \(with line 6\): 1,000,000,000,000,000 is over the limit moleculeRecords=/);
    expectRefusal(() => parseSdf(v3000Molfile(['1 C 0 0 0 0'], [], '1 9999999'), 'bonds.mol'), 'moleculeRecords');
    // An atom block longer than its COUNTS is refused at the first atom too many, not at its end.
    expectLanternError(() => parseSdf(v3000Molfile(['1 C 0 0 0 0', '2 C 1 0 0 0', '3 x'], [], '1 0'), 'more.mol'), /^more\.mol line 9: the atom block has more atoms than the 1 COUNTS says/);
  });

  it('charges the atoms of all records of an SD file to one budget', () => {
    const record = v3000Molfile(['1 C 0 0 0 0', '2 O 1.2 0 0 0'], ['1 2 1 2']);
    const sdf = `${record}$$$$\n${record}$$$$\n${record}$$$$\n`;
    expect(withLimits({ moleculeRecords: 6 }, () => parseSdf(sdf, 'three.sdf'))).toHaveLength(3);
    expectRefusal(() => withLimits({ moleculeRecords: 5 }, () => parseSdf(sdf, 'three.sdf')), 'moleculeRecords');
  });

  it('refuses a line over a megabyte in one line (a file without line breaks was gathered whole)', () => {
    const text = `x\n\n\n${'1'.repeat(3 << 20)}`;
    expectLanternError(() => parseSdf(text, 'flat.mol'), /^flat\.mol line 4: a line longer than 1,048,576 characters/);
  });
});

describe('issue 27: Wolfenstein 3D warnings', () => {
  it('caps a map whose every tile warns at warningsPerKind a kind, with one closing line each (it printed 32,040 lines)', async () => {
    const { format, files } = formatOfSet(wolfWarningFloodFiles().map((f) => ({ ...f, head: f.bytes.subarray(0, 1024) })));
    const opened = await format.open({ files, resolve: NO_SIBLINGS });
    const warnings: string[] = [];
    await opened.scene('E1L1', { onWarning: (w) => warnings.push(w) });
    const perKind = limits().warningsPerKind;
    const shown = warnings.filter((w) => !w.startsWith('… and '));
    expect(shown.filter((w) => w.includes('a second player start'))).toHaveLength(perKind);
    expect(shown.filter((w) => w.includes('is not on a wall'))).toHaveLength(perKind);
    // 179 rows of 179 tiles: 89 rows of player starts (all but one a second start), 90 of push-wall marks.
    const closing = warnings.filter((w) => w.startsWith('… and '));
    expect(closing.map((w) => /^… and ([\d,]+) more/.exec(w)![1]).sort()).toEqual([(90 * 179 - perKind).toLocaleString('en-US'), (89 * 179 - 1 - perKind).toLocaleString('en-US')].sort());
    expect(warnings.length).toBeLessThan(2 * perKind + 10);
  });
});

describe('issue 27: PLY limits that kept no promise', () => {
  it('refuses a .ply.gz declaring 10.3 million faces from its header, before the body is inflated', () => {
    // The body is a bomb past decompressedBytes: a refusal of the faces (not of the bytes) shows the
    // header was read first. Before, all 134 MB inflated and the load took 2.7 GB.
    const bomb = plyBomb({ bytes: 16 * 2 ** 20, vertices: 3, faces: 10_300_000 });
    const refusal = withLimits({ decompressedBytes: 8 * 2 ** 20 }, () => expectRefusal(() => parsePly(bomb, 'bomb.ply.gz'), 'faces'));
    expect(refusal.userMessage).toMatch(/^bomb\.ply\.gz: faces: 10,300,000 is over the limit faces=/);
    // Within the counts, the same body is still stopped at decompressedBytes.
    const inLimits = plyBomb({ bytes: 16 * 2 ** 20, vertices: 1000, faces: 1 });
    withLimits({ decompressedBytes: 8 * 2 ** 20 }, () => expectRefusal(() => parsePly(inLimits, 'bomb.ply.gz'), 'decompressedBytes'));
  });

  it('the default face and vertex limits are below what fits in 2 GB at the measured cost of a load', () => {
    // docs/hardening.md: a load costs about 280 bytes a triangle and 130 a vertex (with its normal)
    // plus 200 MB; 10.3 million triangles once passed the default and loaded at 2.9 GB.
    expect(200e6 + 280 * DEFAULT_LIMITS.faces + 130 * DEFAULT_LIMITS.vertices).toBeLessThan(1.6e9);
    expect(DEFAULT_LIMITS.faces).toBeLessThan(10_300_000);
  });
});

describe('issue 27: 8K lat-long maps', () => {
  it('an 8192-wide map\'s sampling table is 8192 texels wide, what devices allow (it needed 8,193: the documented 8K limit was refused)', () => {
    // A map of the limit's width, 2 rows high: the table's width is the map's, not one more.
    const image = loadEnvironmentImage(constantHdr(8192, 2), 'wide.hdr');
    const packed = packEnvironment({ kind: 'map', image, rotationDeg: 0, intensity: 1 });
    expect([packed.environment_cdf.width, packed.environment_cdf.height]).toEqual([8192, 3]);
    expect(Math.max(packed.environment_map.width, packed.environment_map.height)).toBe(8192);
  });

  it('refuses an 8192×4096 map whose file is only its header before allocating its pixels', () => {
    expectLanternError(() => loadEnvironmentImage(constantHdr(8192, 4096, true), 'cut.hdr'), /^cut\.hdr: truncated: 4096 scanlines need at least/);
  });
});
