import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { cross, dot, luminance, sub, type Vec3 } from '../../math/vec3.ts';
import { baseColorOf, type DiffuseMaterial, type Material, type Scene, type Texture } from '../../scene/types.ts';
import { validateScene } from '../../scene/validate.ts';
import { DOOM_TORCH, LAMP_STRENGTH, SKY_STRENGTH, sectorLightFactor } from './light-table.ts';
import { readMap } from './map-lumps.ts';
import { SKY_FLAT, type DoomImageSource, type DoomMap } from './map-types.ts';
import { cw, MapBuilder, squareRoomWad } from './test-wad.ts';
import { DoomGraphics } from './textures.ts';
import { doomMapToScene, DOOM_VFOV_DEGREES, type DoomSceneOptions } from './to-scene.ts';
import { readWad, WadStack } from './wad.ts';

function solid(name: string, width: number, height: number, alpha = 255): Texture {
  const rgba = new Uint8Array(width * height * 4);
  for (let i = 0; i < rgba.length; i += 4) rgba.set([200, 100, 50, alpha], i);
  return { name, width, height, rgba };
}

const IMAGES: DoomImageSource = {
  texture: (name) => ({ WALL: solid('WALL', 64, 128), LITE3: solid('LITE3', 32, 128), GRATE: solid('GRATE', 64, 64, 0) })[name],
  flat: (name) => (['FLOOR4_8', 'CEIL3_5', 'TLITE6_1', 'F_SKY1'].includes(name) ? solid(name, 64, 64) : undefined),
};
const SKY = solid('SKY1', 256, 128);

function convert(map: DoomMap, options: DoomSceneOptions = {}) {
  const warnings: string[] = [];
  const result = doomMapToScene(map, IMAGES, { sky: SKY, onWarning: (w) => warnings.push(w), ...options });
  validateScene(result.scene);
  return { ...result, warnings };
}

interface Triangle {
  readonly p: readonly [Vec3, Vec3, Vec3];
  readonly uv: readonly [number, number][];
  /** Geometric normal (v1 − v0) × (v2 − v0), unnormalised. */
  readonly n: Vec3;
}

/** The triangles drawn with the material named `name`. */
function trianglesOf(scene: Scene, name: string): Triangle[] {
  const out: Triangle[] = [];
  for (const mesh of scene.meshes) {
    for (let t = 0; t < mesh.indices.length / 3; t++) {
      if (scene.materials[mesh.materialIds[t]!]!.name !== name) continue;
      const idx = [0, 1, 2].map((k) => mesh.indices[3 * t + k]!);
      const p = idx.map((i) => [mesh.positions[3 * i]!, mesh.positions[3 * i + 1]!, mesh.positions[3 * i + 2]!] as Vec3) as [Vec3, Vec3, Vec3];
      const uv = idx.map((i) => [mesh.uvs![2 * i]!, mesh.uvs![2 * i + 1]!] as [number, number]);
      out.push({ p, uv, n: cross(sub(p[1], p[0]), sub(p[2], p[0])) });
    }
  }
  return out;
}

// Doom maps use two kinds: diffuse (walls, flats, lamps) and emissive (the sky); the fields of both, for reading.
type DoomMaterial = Partial<DiffuseMaterial> & Material;
const material = (scene: Scene, name: string) => scene.materials.find((m) => m.name === name || m.name.startsWith(`${name} `)) as DoomMaterial | undefined;
const mod = (a: number, n: number) => ((a % n) + n) % n;

/** A 512×512 room with a raised 128×128 platform (floor 32) and a 64×64 pillar. */
function roomMap(): { map: DoomMap; room: number; platform: number } {
  const m = new MapBuilder();
  const room = m.sector();
  const platform = m.sector({ floorHeight: 32 });
  m.loop(cw(0, 0, 512), room);
  m.loop(cw(64, 64, 128), platform, room);
  m.loop(cw(320, 320, 64).reverse(), room);
  m.player(128, 128, 90);
  return { map: m.build(), room, platform };
}

describe('doomMapToScene', () => {
  it('builds a valid scene with one material per image, each image stored once', () => {
    const { scene, failures, stats, warnings } = convert(roomMap().map);
    expect(failures).toEqual([]);
    expect(warnings).toEqual([]);
    expect(scene.name).toBe('TEST');
    expect(scene.textures!.map((t) => t.name).sort()).toEqual(['CEIL3_5', 'FLOOR4_8', 'WALL']);
    expect(scene.materials.map((m) => m.name).sort()).toEqual(['CEIL3_5', 'FLOOR4_8', 'WALL']);
    for (const m of scene.materials as DoomMaterial[]) {
      expect(m.albedo).toEqual([1, 1, 1]);
      expect(m.emission).toEqual([0, 0, 0]);
      expect(scene.textures![m.albedoTexture!.texture]!.name).toBe(m.name);
    }
    expect(stats).toMatchObject({ sectors: 2, triangulatedSectors: 2, wallQuads: 4 + 4 + 4, materials: 3, emissiveMaterials: 0, textures: 3 });
  });

  it('makes floors face up and ceilings face down, with the area of their sectors', () => {
    const { scene } = convert(roomMap().map);
    const area = (tris: Triangle[]) => tris.reduce((s, t) => s + Math.hypot(...t.n) / 2, 0);
    const floors = trianglesOf(scene, 'FLOOR4_8');
    const ceilings = trianglesOf(scene, 'CEIL3_5');
    for (const t of floors) expect(t.n[1]).toBeCloseTo(Math.hypot(...t.n), 6);
    for (const t of ceilings) expect(-t.n[1]).toBeCloseTo(Math.hypot(...t.n), 6);
    // Floors: the room at height 0 (the platform and pillar cut out), the platform at 32.
    const at = (tris: Triangle[], y: number) => tris.filter((t) => t.p[0][1] === y);
    expect(area(at(floors, 0))).toBeCloseTo(512 * 512 - 128 * 128 - 64 * 64, 6);
    expect(area(at(floors, 32))).toBeCloseTo(128 * 128, 6);
    expect(area(ceilings)).toBeCloseTo(512 * 512 - 64 * 64, 6);
  });

  it('tiles flats on the 64-unit world grid with north up in the image', () => {
    const { scene } = convert(roomMap().map);
    for (const t of trianglesOf(scene, 'FLOOR4_8')) {
      t.p.forEach((p, k) => {
        const [x, y] = [p[0], -p[2]]; // back to map coordinates
        expect(mod(t.uv[k]![0] * 64 - x, 64)).toBeCloseTo(0, 3);
        expect(mod(t.uv[k]![1] * 64 + y, 64)).toBeCloseTo(0, 3); // texel row = (−y) mod 64
      });
    }
  });

  it('makes every wall face into its sector', () => {
    const m = new MapBuilder();
    const room = m.sector();
    m.loop(cw(0, 0, 256), room);
    m.player(128, 128, 0);
    const { scene } = convert(m.build());
    const centre: Vec3 = [128, 64, -128];
    const walls = trianglesOf(scene, 'WALL');
    expect(walls).toHaveLength(8);
    for (const t of walls) expect(dot(t.n, sub(centre, t.p[0]))).toBeGreaterThan(0);
  });

  it('puts walls at the heights of the sectors and keeps their texture coordinates', () => {
    const { scene } = convert(roomMap().map);
    const heights = new Set(trianglesOf(scene, 'WALL').flatMap((t) => t.p.map((p) => p[1])));
    expect([...heights].sort((a, b) => a - b)).toEqual([0, 32, 128]);
    // The platform's step: 32 units of a 128-row texture, pegged to the platform's floor (row 0 at 32).
    const step = trianglesOf(scene, 'WALL').filter((t) => t.p.every((p) => p[1] <= 32));
    expect(step.length).toBe(8);
    for (const t of step) t.p.forEach((p, k) => expect(mod(t.uv[k]![1] * 128 - (32 - p[1]), 128)).toBeCloseTo(0, 3));
  });

  it('stands the camera on player 1 start at eye height, looking along its angle', () => {
    const { scene } = convert(roomMap().map);
    expect(scene.camera.position).toEqual([128, 32 + 41, -128]); // on the platform
    expect(scene.camera.forward[0]).toBeCloseTo(0, 12);
    expect(scene.camera.forward[2]).toBeCloseTo(-1, 12); // 90° is north, −z
    expect(scene.camera.up).toEqual([0, 1, 0]);
    expect(scene.camera.vfovDegrees).toBeCloseTo(73.74, 2);
    expect(DOOM_VFOV_DEGREES).toBeCloseTo((2 * Math.atan(3 / 4) * 180) / Math.PI, 12);
  });

  it('without a player start, stands in the middle of the map looking east, and says so', () => {
    const { map } = roomMap();
    const { scene, warnings } = convert({ ...map, things: [] });
    expect(scene.camera.position).toEqual([256, 41, -256]);
    expect(scene.camera.forward).toEqual([1, 0, 0]);
    expect(warnings).toEqual(['TEST has no player 1 start; the camera stands in the middle of the map, looking east']);
  });

  it('makes light textures glow from their bright texels, scaled by the sector light level squared', () => {
    const m = new MapBuilder();
    const room = m.sector({ lightLevel: 160, ceilingFlat: 'TLITE6_1' });
    m.loop(cw(0, 0, 256), room, undefined, { middle: 'LITE3' });
    m.player(128, 128, 0);
    const { scene, stats } = convert(m.build());
    const s = LAMP_STRENGTH * (160 / 255) ** 2;
    for (const name of ['LITE3', 'TLITE6_1']) {
      const mat = material(scene, name)!;
      expect(mat.emission).toEqual([s, s, s]);
      expect(scene.textures![mat.albedoTexture!.texture]!.name).toBe(name);
      // The glow image: the same texels where bright enough, black elsewhere.
      const image = scene.textures![mat.albedoTexture!.texture]!;
      const glow = scene.textures![mat.emissionTexture!.texture]!;
      expect(glow.name).toBe(`${name}@glow`);
      expect([glow.width, glow.height]).toEqual([image.width, image.height]);
      for (let i = 0; i < glow.rgba.length; i += 4) {
        const kept = glow.rgba[i] === image.rgba[i] && glow.rgba[i + 1] === image.rgba[i + 1] && glow.rgba[i + 2] === image.rgba[i + 2];
        const black = glow.rgba[i] === 0 && glow.rgba[i + 1] === 0 && glow.rgba[i + 2] === 0;
        expect(kept || black).toBe(true);
      }
    }
    expect(stats.emissiveMaterials).toBe(2);
    // The lit ceiling faces down, so it shines into the room.
    for (const t of trianglesOf(scene, material(scene, 'TLITE6_1')!.name)) expect(t.n[1]).toBeLessThan(0);
  });

  it('takes light table overrides', () => {
    const m = new MapBuilder();
    const room = m.sector();
    m.loop(cw(0, 0, 256), room, undefined, { middle: 'LITE3' });
    const { scene } = convert(m.build(), { lightTable: { textures: { LITE3: { strength: 0 } }, flats: { floor4_8: { strength: 2, color: [1, 0.5, 0] } } } });
    expect(material(scene, 'LITE3')!.emission).toEqual([0, 0, 0]);
    expect(material(scene, 'FLOOR4_8')!.emission).toEqual([2, 1, 0]);
  });

  it('draws sky ceilings and the walls between skies with the sky panorama', () => {
    const m = new MapBuilder();
    const yard = m.sector({ ceilingFlat: SKY_FLAT, ceilingHeight: 256 });
    const low = m.sector({ ceilingFlat: SKY_FLAT, ceilingHeight: 192 });
    m.loop(cw(0, 0, 512), yard);
    m.loop(cw(128, 128, 128), low, yard);
    m.player(64, 64, 0);
    const { scene } = convert(m.build());
    const sky = material(scene, 'sky SKY1')!;
    expect(sky.kind).toBe('emissive');
    expect(sky.emission).toEqual([SKY_STRENGTH, SKY_STRENGTH, SKY_STRENGTH]);
    expect(sky.emissionMapping).toEqual({ kind: 'panorama', repeats: 4, horizonV: 100 / 128, vPerRadian: 160 / 128 });
    // Doom's texels stay pixels: its textures are sampled nearest.
    expect(scene.textures![sky.emissionTexture!.texture]).toEqual({ ...SKY, filter: 'nearest' });
    const tris = trianglesOf(scene, sky.name);
    const area = (ts: Triangle[]) => ts.reduce((s, t) => s + Math.hypot(...t.n) / 2, 0);
    // Both ceilings (facing down) and the 64-unit step between them, facing the yard.
    expect(area(tris.filter((t) => t.n[1] < 0))).toBeCloseTo(512 * 512, 6);
    expect(area(tris.filter((t) => t.n[1] === 0))).toBeCloseTo(4 * 128 * 64, 6);
    expect(trianglesOf(scene, 'WALL').every((t) => t.p.every((p) => p[1] <= 256))).toBe(true);
    // Without a sky texture, a plain glowing grey.
    const plain = doomMapToScene(m.build(), IMAGES).scene.materials.find((mat) => mat.name === 'sky')!;
    expect(plain.emissionTexture).toBeUndefined();
    expect(plain.emission[0]).toBeGreaterThan(0);
  });

  it('marks masked middle textures for alpha testing, and uses a plain material where a texture is missing', () => {
    const m = new MapBuilder();
    const room = m.sector();
    const cage = m.sector();
    m.loop(cw(0, 0, 512), room, undefined, { middle: '-' });
    m.loop(cw(128, 128, 128), cage, room, { middle: 'GRATE' });
    m.player(64, 64, 0);
    const { scene, warnings } = convert(m.build());
    expect(material(scene, 'GRATE')!.alphaMode).toBe('mask');
    expect(material(scene, 'WALL')).toBeUndefined();
    expect(baseColorOf(material(scene, 'missing texture')!)).toEqual([0.5, 0.5, 0.5]);
    expect(trianglesOf(scene, 'missing texture')).toHaveLength(8);
    expect(warnings).toEqual(['4 wall sections, the first linedef 0 (front) middle, need a texture but name none; drawn with a plain material']);
  });

  it('gives the player a torch that lights a wall at 128–256 units like sector light 160', () => {
    const { scene } = convert(roomMap().map);
    const torch = scene.torch!;
    expect(torch).toBe(DOOM_TORCH);
    expect(torch.range).toBe(1024);
    expect(torch.radius).toBe(4);
    const d = Math.sqrt(128 * 256);
    const window = (1 - (d / torch.range) ** 4) ** 2;
    const lit = (torch.intensity * window * luminance(torch.color)) / (Math.PI * d * d); // radiance / albedo
    expect(lit).toBeCloseTo(sectorLightFactor(160), 9);
  });
});

describe('doomMapToScene on WADs', () => {
  it('converts a map read from a WAD, with its textures', () => {
    const stack = new WadStack([readWad(squareRoomWad(), 'room.wad')]);
    const graphics = new DoomGraphics(stack);
    const map = readMap(stack, 'MAP01');
    const warnings: string[] = [];
    const { scene, failures } = doomMapToScene(map, graphics, { sky: graphics.sky('MAP01'), onWarning: (w) => warnings.push(w) });
    validateScene(scene);
    expect(failures).toEqual([]);
    expect(warnings).toEqual([]);
    expect(scene.textures!.map((t) => t.name).sort()).toEqual(['CEIL3_5', 'FLOOR4_8', 'STARTAN3']);
    expect(scene.camera.position).toEqual([128, 41, -128]);
    expect(scene.camera.forward[2]).toBeCloseTo(-1, 12);
  });

  const DIR = '/usr/share/games/doom';
  const haveFreedoom = existsSync(`${DIR}/freedoom1.wad`) && existsSync(`${DIR}/freedoom2.wad`);

  it.skipIf(!haveFreedoom)('converts every Freedoom map with no sector failures', () => {
    const report: string[] = [];
    for (const file of ['freedoom1.wad', 'freedoom2.wad']) {
      const stack = new WadStack([readWad(readFileSync(`${DIR}/${file}`), file)]);
      const graphics = new DoomGraphics(stack);
      for (const info of stack.maps()) {
        const map = readMap(stack, info.name);
        const { scene, failures } = doomMapToScene(map, graphics, { sky: graphics.sky(info.name) });
        validateScene(scene);
        for (const f of failures) report.push(`${file} ${info.name} sector ${f.sector}: ${f.reason}`);
      }
    }
    if (report.length > 0) console.log(`sector failures:\n${report.join('\n')}`);
    expect(report).toEqual([]);
  });

  it.skipIf(!haveFreedoom)('reads, textures and triangulates E1M1 well within a second', () => {
    const bytes = readFileSync(`${DIR}/freedoom1.wad`);
    const t0 = performance.now();
    const stack = new WadStack([readWad(bytes, 'freedoom1.wad')]);
    const graphics = new DoomGraphics(stack);
    const { scene } = doomMapToScene(readMap(stack, 'E1M1'), graphics, { sky: graphics.sky('E1M1') });
    const ms = performance.now() - t0;
    console.log(`E1M1: ${ms.toFixed(0)} ms, ${scene.meshes.reduce((n, m) => n + m.indices.length / 3, 0)} triangles, ${scene.textures!.length} textures`);
    expect(ms).toBeLessThan(1000);
  });
});
