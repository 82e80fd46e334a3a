/**
 * A Lantern scene from a Doom map: floors and ceilings (sectors.ts), walls (walls.ts), materials
 * from the WAD's textures with the light table's emitters (light-table.ts), the sky, the player's
 * view and torch, what animates (animations.ts: texture cycles, scrolling walls, sector light
 * specials, as Scene.dynamics.materialAnimations), and the things as sprites turned toward the
 * viewer (things.ts, scene/billboards.ts, as Scene.dynamics.billboards). Coordinates go through
 * coordinates.ts.
 */
import { doomWalkMap, PLAYER_HEIGHT, PLAYER_RADIUS } from './walk-map.ts';
import { IDENTITY } from '../../math/mat4.ts';
import type { Billboard, EmissionPattern, LightPattern, MaterialAnimations, Mover, MoverSet, TextureCycle, UvScroll } from '../../scene/dynamics-types.ts';
import { DoomCycles, SCROLL_LEFT_SPECIAL, sectorLightPattern, sectorNeighbours, TICS_PER_SECOND } from './animations.ts';
import { scale, type Vec3 } from '../../math/vec3.ts';
import { placeEachOnce } from '../../scene/instances.ts';
import { diffuse, type Camera, type Material, type Mesh, type Scene, type Texture } from '../../scene/types.ts';
import { directionFromAngle, flatUv, toWorld } from './coordinates.ts';
import { DEFAULT_LIGHT_TABLE, DOOM_TORCH, emissionOf, glowTexture, mergeLightTables, SKY_STRENGTH, type LightSource, type LightTable } from './light-table.ts';
import { EYE_HEIGHT, PLAYER1_START, type DoomImageSource, type DoomMap } from './map-types.ts';
import { buildSectorShapes, sectorAt, type SectorFailure, type SectorShapes } from './sectors.ts';
import type { SpriteSource } from './sprites.ts';
import { buildThings, type ThingOptions } from './things.ts';
import { buildWalls, isSky, type WallQuad } from './walls.ts';
import { billboardPoses, billboardQuad } from '../../scene/billboards.ts';
import { findMovers, type MapMovers } from './mover-sectors.ts';

export interface DoomSceneOptions {
  /** The sky texture (SKY1, ...). Without one the sky glows a plain grey. */
  readonly sky?: Texture;
  /** Entries replacing or adding to DEFAULT_LIGHT_TABLE. */
  readonly lightTable?: Partial<LightTable>;
  readonly onWarning?: (message: string) => void;
  /** Scene name; the map's name by default. */
  readonly name?: string;
  /** The WAD's animated flats and textures (animations.ts resolveCycles); none without. */
  readonly cycles?: DoomCycles;
  /** The WADs' sprites: with them, the map's things are drawn (things.ts); without, none are. */
  readonly sprites?: SpriteSource;
  /** Which things appear (skill, multiplayer). */
  readonly things?: ThingOptions;
}

export interface DoomSceneStats {
  readonly sectors: number;
  /** Sectors with floor and ceiling triangles. */
  readonly triangulatedSectors: number;
  readonly wallQuads: number;
  readonly triangles: number;
  /** Doors and lifts: sectors with a mesh of their own that moves. */
  readonly movers: number;
  readonly materials: number;
  readonly emissiveMaterials: number;
  readonly textures: number;
  /** Materials showing an animated flat or texture (texture cycles). */
  readonly cycledMaterials: number;
  /** Linedefs with the scrolling special (48) whose front side shows a texture. */
  readonly scrollingLines: number;
  /** Sectors with a light special (1, 2, 3, 4, 8, 12, 13, 17). */
  readonly lightSpecialSectors: number;
  /** Materials whose emission follows a sector's light special. */
  readonly patternedMaterials: number;
  /** Things drawn as sprites, and how many of them give light. */
  readonly sprites: number;
  readonly emittingSprites: number;
}

export interface DoomScene {
  readonly scene: Scene;
  /** Sectors whose floor and ceiling could not be built (sectors.ts). */
  readonly failures: readonly SectorFailure[];
  readonly stats: DoomSceneStats;
}

/**
 * Doom renders 90° across its 320 columns and 2·atan(100/160) = 64° down its 200 rows, which a 4:3
 * monitor stretched by 1.2 vertically. With square pixels, 90° across a 4:3 image is
 * 2·atan(tan 45° · 3/4) = 73.74° vertically: Doom's width of view, nothing stretched.
 */
/**
 * Doom shows a wall in a sector at light 255 at its palette colour; light transport gives such a
 * wall radiance ≈ its linear texture colour (light-table.ts), which is 0.04–0.15 for Doom's dark
 * palette, where the ACES curve's toe sits about a stop and a half below the identity. The camera's
 * +1.5 stops brings those colours back to about what Doom displays.
 */
export const DOOM_EXPOSURE_STOPS = 1.5;

/** The player is 56 units tall and about 1.75 m: 1/32 m per map unit is the usual conversion. */
export const DOOM_METERS_PER_UNIT = 1 / 32;

export const DOOM_VFOV_DEGREES = (2 * Math.atan(0.75) * 180) / Math.PI;

/**
 * Doom's sky (R_DrawPlanes): column = view angle in 1024ths of a turn, wrapped by the texture's
 * width, so a 256-wide sky repeats 4 times around the horizon (90° each); rows start at texture row
 * 100 on the horizon (skytexturemid = 100, the middle of the 200-row screen) and step one texture row
 * per screen row. The screen's focal length is 160 pixels (90° across 320 columns), so near the
 * horizon one radian of elevation is 160 rows (and 256 columns per 90° is 163 per radian: the sky's
 * texels are nearly square in angle). For the 128-row sky: horizonV = 100/128 = 0.781, vPerRadian =
 * 160/128 = 1.25, and the top row is reached 36° up; above that the panorama lookup clamps to it.
 */
export const SKY_COLUMNS_PER_TURN = 1024;
export const SKY_HORIZON_ROW = 100;
export const SKY_ROWS_PER_RADIAN = 160;
/** Sky colour (linear) when no sky texture is given. */
const PLAIN_SKY: Vec3 = [0.3, 0.3, 0.3];
const MISSING_ALBEDO: Vec3 = [0.5, 0.5, 0.5];

export function doomMapToScene(map: DoomMap, images: DoomImageSource, options: DoomSceneOptions = {}): DoomScene {
  const warn = options.onWarning ?? (() => {});
  const table = mergeLightTables(DEFAULT_LIGHT_TABLE, options.lightTable);
  const shapes = buildSectorShapes(map, warn);
  const movers = findMovers(map, warn);
  const ranges = new Map(movers.sectors.map((m) => [m.sector, m.range]));
  const walls = buildWalls(map, (name) => images.texture(name), warn, ranges);
  const neighbours = sectorNeighbours(map);
  const patterns = new Map<number, LightPattern>();
  map.sectors.forEach((_, i) => {
    const p = sectorLightPattern(map, i, neighbours, i);
    if (p) patterns.set(i, p);
  });
  const out = new SceneParts(images, table, options.sky, warn, options.cycles, patterns);
  // Each door or lift sector is one mesh whose two morph targets move its floor and its ceiling.
  const moverMeshes = new Map(movers.sectors.map((m) => [m.sector, new MeshParts(true)]));

  let triangulatedSectors = 0;
  for (const shape of shapes.shapes) {
    const sector = map.sectors[shape.sector]!;
    if (shape.indices.length === 0) continue;
    triangulatedSectors++;
    const moverMesh = moverMeshes.get(shape.sector);
    // A closed door (ceiling at or below the floor) shows neither plane, unless it can open.
    if (sector.ceilingHeight <= sector.floorHeight && !moverMesh) continue;
    const v = shape.vertices;
    let [originU, originV] = [Infinity, Infinity];
    for (let i = 0; i < v.length; i += 2) {
      const [u, w] = flatUv(v[i]!, v[i + 1]!);
      originU = Math.min(originU, Math.floor(u));
      originV = Math.min(originV, Math.floor(w));
    }
    for (const [height, flat, up] of [[sector.floorHeight, sector.floorFlat, true], [sector.ceilingHeight, sector.ceilingFlat, false]] as const) {
      const material = isSky(flat) ? out.sky() : out.material('flat', flat, sector.lightLevel, false, { sector: shape.sector });
      const mesh = moverMesh ?? out.meshFor(material);
      const base = mesh.vertexCount();
      const motion: VertexMotion = up ? [1, 0, 0, 0] : [0, 1, 0, 0];
      for (let i = 0; i < v.length; i += 2) mesh.vertex(toWorld(v[i]!, v[i + 1]!, height), flatUv(v[i]!, v[i + 1]!, originU, originV), motion);
      // The shape's triangles are counter-clockwise seen from above: as they are, they face up
      // (floors); reversed, down (ceilings). Emission is one-sided, so this matters for lit flats.
      for (let t = 0; t < shape.indices.length; t += 3) {
        const [a, b, c] = [shape.indices[t]!, shape.indices[t + 1]!, shape.indices[t + 2]!];
        if (up) mesh.triangle(base + a, base + b, base + c, material);
        else mesh.triangle(base + a, base + c, base + b, material);
      }
    }
  }

  const scrollingLines = new Set<number>();
  for (const quad of walls) {
    const scroll = quad.side === 'front' && map.linedefs[quad.line]!.special === SCROLL_LEFT_SPECIAL && quad.surface.kind === 'texture';
    if (scroll) scrollingLines.add(quad.line);
    addWall(out, quad, map.sectors[quad.sector]!.lightLevel, scroll, quad.motion && moverMeshes.get(quad.motion.sector));
  }
  const things = options.sprites && buildThings(map, shapes, options.sprites, table, (lump, picture, light) => out.sprite(lump, picture, light), options.things, warn);

  const { meshes: staticMeshes, materials, textures, animations } = out.finish();
  const meshes = [...staticMeshes];
  const instances = placeEachOnce(staticMeshes);
  const moverMeshIndex = new Map<number, number>();
  for (const [sector, parts] of moverMeshes) {
    const name = `sector ${sector} (${movers.sectors.find((m) => m.sector === sector)!.kinds.join(' and ')})`;
    const mesh = parts.build(name, 0); // a moving sector's triangles carry their own materials
    if (!mesh) continue;
    moverMeshIndex.set(sector, meshes.push(mesh) - 1);
    instances.push({ id: instances.length, name, mesh: meshes.length - 1, worldFromObject: IDENTITY, moves: true });
  }
  const moverSet = moverSetOf(map, movers, moverMeshIndex);
  const camera = playerCamera(map, shapes, warn);
  let billboards: Billboard[] = [];
  if (things && things.billboards.length > 0) {
    // One quad for every thing, each an instance posed toward the player's view (and after that by
    // the world's billboard animator).
    const quad = meshes.push(billboardQuad(things.billboards[0]!.frames[0]!.images[0]!.material, 'sprite quad')) - 1;
    billboards = things.billboards.map((b) => ({ ...b, instance: instances.length + b.instance }));
    const poses = billboardPoses(billboards, { position: camera.position, forward: camera.forward });
    billboards.forEach((b, i) => instances.push({ id: b.instance, name: things.names[i]!, mesh: quad, moves: true, ...poses.get(b.instance)! }));
  }
  const dynamics = {
    ...(animations ? { materialAnimations: animations } : {}),
    ...(moverSet ? { movers: moverSet } : {}),
    ...(billboards.length > 0 ? { billboards } : {}),
  };
  const scene: Scene = {
    name: options.name ?? map.name,
    meshes,
    instances,
    materials,
    textures,
    camera,
    torch: DOOM_TORCH,
    // Rooms lit by lamps and corridors lit by the torch alone differ by stops: the exposure adapts.
    autoExposure: true,
    metersPerUnit: DOOM_METERS_PER_UNIT,
    walkMap: doomWalkMap(map),
    ...(Object.keys(dynamics).length > 0 && { dynamics }),
  };
  return {
    scene,
    failures: shapes.failures,
    stats: {
      sectors: map.sectors.length,
      triangulatedSectors,
      wallQuads: walls.length,
      triangles: meshes.reduce((n, m) => n + m.indices.length / 3, 0),
      movers: moverSet?.movers.length ?? 0,
      materials: materials.length,
      emissiveMaterials: materials.filter((m) => m.emission.some((c) => c > 0)).length,
      textures: textures.length,
      cycledMaterials: animations?.cycles?.length ?? 0,
      scrollingLines: scrollingLines.size,
      lightSpecialSectors: patterns.size,
      patternedMaterials: animations?.patterns?.length ?? 0,
      sprites: billboards.length,
      emittingSprites: things?.emitting ?? 0,
    },
  };
}

/** Adds a wall quad to its material's mesh, or to `moverMesh` (a moving sector's) with its motion. */
function addWall(out: SceneParts, q: WallQuad, lightLevel: number, scroll: boolean, moverMesh?: MeshParts): void {
  const s = q.surface;
  const material = s.kind === 'sky' ? out.sky() : s.kind === 'missing' ? out.missing() : out.material('texture', s.name, lightLevel, q.section === 'masked', { sector: q.sector, scroll });
  const mesh = moverMesh ?? out.meshFor(material);
  const base = mesh.vertexCount();
  const m = q.motion;
  const bottom: VertexMotion | undefined = m && [m.bottom[0], m.bottom[1], m.vBottom[0], m.vBottom[1]];
  const top: VertexMotion | undefined = m && [m.top[0], m.top[1], m.vTop[0], m.vTop[1]];
  // Counter-clockwise seen from the quad's sector (walls.ts), so the geometric normal faces it.
  mesh.vertex(toWorld(q.x0, q.y0, q.bottom), [q.u0, q.vBottom], bottom);
  mesh.vertex(toWorld(q.x1, q.y1, q.bottom), [q.u1, q.vBottom], bottom);
  mesh.vertex(toWorld(q.x1, q.y1, q.top), [q.u1, q.vTop], top);
  mesh.vertex(toWorld(q.x0, q.y0, q.top), [q.u0, q.vTop], top);
  mesh.triangle(base, base + 1, base + 2, material);
  mesh.triangle(base, base + 2, base + 3, material);
}

/** Scene.dynamics.movers from the map's moving sectors and the meshes they got. */
function moverSetOf(map: DoomMap, found: MapMovers, meshOf: ReadonlyMap<number, number>): MoverSet | undefined {
  const index = new Map<number, number>();
  const movers: Mover[] = [];
  for (const m of found.sectors) {
    const mesh = meshOf.get(m.sector);
    if (mesh === undefined) continue;
    const sector = map.sectors[m.sector]!;
    index.set(m.sector, movers.length);
    movers.push({ mesh, sector: m.sector, kinds: m.kinds, restFloor: sector.floorHeight, restCeiling: sector.ceilingHeight, doorTop: m.doorTop, liftBottom: m.liftBottom, outline: m.outline });
  }
  if (movers.length === 0) return undefined;
  const triggers = found.triggers.flatMap((t) => {
    const moved = t.sectors.flatMap((s) => (index.has(s) ? [index.get(s)!] : []));
    return moved.length === 0 ? [] : [{ line: t.line, activation: t.activation, repeatable: t.repeatable, movers: moved, action: t.action, speed: t.speed, wait: t.wait, reverses: t.reverses }];
  });
  // Doom's USERANGE: the use key reaches 64 units.
  return { movers, triggers, useRange: 64, body: { radius: PLAYER_RADIUS, height: PLAYER_HEIGHT } };
}

/**
 * The view from player 1's start (thing type 1) at eye height above the floor it stands on, along
 * its angle. Without one: the middle of the map, looking east.
 */
function playerCamera(map: DoomMap, shapes: SectorShapes, warn: (m: string) => void): Camera {
  const start = map.things.find((t) => t.type === PLAYER1_START);
  let x: number, y: number, angle: number;
  if (start) [x, y, angle] = [start.x, start.y, start.angle];
  else {
    // A loop, not Math.min(...xs): spreading 140k arguments overflows the call stack.
    let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
    for (const v of map.vertices) [minX, minY, maxX, maxY] = [Math.min(minX, v.x), Math.min(minY, v.y), Math.max(maxX, v.x), Math.max(maxY, v.y)];
    [x, y, angle] = map.vertices.length > 0 ? [(minX + maxX) / 2, (minY + maxY) / 2, 0] : [0, 0, 0];
    warn(`${map.name} has no player 1 start; the camera stands in the middle of the map, looking east`);
  }
  const sector = sectorAt(shapes, x, y) ?? nearestSector(shapes, x, y);
  if (start && sector !== undefined && sectorAt(shapes, x, y) === undefined) warn(`the player 1 start (${x}, ${y}) is outside every sector; using the nearest, ${sector}`);
  const floor = sector === undefined ? 0 : map.sectors[sector]!.floorHeight;
  return { position: toWorld(x, y, floor + EYE_HEIGHT), forward: directionFromAngle(angle), up: [0, 1, 0], vfovDegrees: DOOM_VFOV_DEGREES, exposureStops: DOOM_EXPOSURE_STOPS };
}

/** The sector with a floor corner nearest to (x, y). */
function nearestSector(shapes: SectorShapes, x: number, y: number): number | undefined {
  let best: number | undefined;
  let bestD = Infinity;
  for (const s of shapes.shapes) {
    for (let i = 0; i < s.vertices.length; i += 2) {
      const d = (s.vertices[i]! - x) ** 2 + (s.vertices[i + 1]! - y) ** 2;
      if (d < bestD) [best, bestD] = [s.sector, d];
    }
  }
  return best;
}

/** How a vertex moves per unit of its moving sector's floor and ceiling height: dy, dy, dv, dv. */
type VertexMotion = readonly [number, number, number, number];

/**
 * Triangles of one material; or, with `moves`, of a moving sector (any materials, with two morph
 * targets: the displacement of every vertex and v per unit of the floor height, then of the ceiling).
 */
class MeshParts {
  private readonly positions: number[] = [];
  private readonly uvs: number[] = [];
  private readonly indices: number[] = [];
  private readonly materials: number[] = [];
  /** Per vertex, when `moves`: VertexMotion. */
  private readonly motions: number[] = [];

  constructor(private readonly moves = false) {}

  vertexCount(): number {
    return this.positions.length / 3;
  }
  vertex(p: Vec3, uv: readonly [number, number], motion: VertexMotion = [0, 0, 0, 0]): void {
    this.positions.push(p[0], p[1], p[2]);
    this.uvs.push(uv[0], uv[1]);
    if (this.moves) this.motions.push(motion[0], motion[1], motion[2], motion[3]);
  }
  triangle(a: number, b: number, c: number, material: number): void {
    this.indices.push(a, b, c);
    this.materials.push(material);
  }
  build(name: string, material: number): Mesh | undefined {
    if (this.indices.length === 0) return undefined;
    const mesh: Mesh = {
      name,
      positions: new Float32Array(this.positions),
      indices: new Uint32Array(this.indices),
      uvs: new Float32Array(this.uvs),
      materialIds: this.moves ? new Uint32Array(this.materials) : new Uint32Array(this.indices.length / 3).fill(material),
    };
    if (!this.moves) return mesh;
    const n = this.positions.length / 3;
    // Heights are world y (coordinates.ts); v follows the pegged heights.
    const target = (k: 0 | 1) => {
      const positions = new Float32Array(3 * n), uvs = new Float32Array(2 * n);
      for (let i = 0; i < n; i++) {
        positions[3 * i + 1] = this.motions[4 * i + k]!;
        uvs[2 * i + 1] = this.motions[4 * i + 2 + k]!;
      }
      return { positions, uvs };
    };
    return { ...mesh, morphTargets: [target(0), target(1)] };
  }
}

/** Where a surface is, for the animations that depend on it. */
interface SurfacePlace {
  /** The sector whose light the surface takes (its light special makes an emitting material its own). */
  readonly sector?: number;
  /** A scrolling wall (linedef special 48, front side): its material is its own, shared by scrolling walls alone. */
  readonly scroll?: boolean;
}

/** What an animated material was made from (SceneParts.finish turns it into material animations). */
interface AnimatedMaterial {
  readonly kind: 'texture' | 'flat';
  readonly image: Texture;
  readonly source: LightSource | undefined;
  readonly emits: boolean;
  readonly cycle?: { readonly names: readonly string[]; readonly frame: number; readonly ticsPerFrame: number };
  readonly scroll: boolean;
  readonly pattern?: LightPattern;
}

/**
 * Materials, textures and meshes as they are needed: one material per (image, emission, alpha mode),
 * each image stored once, one mesh per material. Animated surfaces get materials of their own where
 * their animation is not everyone's: a scrolling wall's texture is not the same material as the
 * still one, and an emitting surface in a sector with a light special has its sector's material
 * (cycles need nothing extra: every surface showing a frame animates alike, in Doom too).
 */
class SceneParts {
  private readonly materials: Material[] = [];
  private readonly materialIndex = new Map<string, number>();
  private readonly textures: Texture[] = [];
  private readonly textureIndex = new Map<Texture, number>();
  private readonly meshes = new Map<number, MeshParts>();
  private readonly warnedFlats = new Set<string>();
  private readonly glowImages = new Map<string, Texture>();

  constructor(
    private readonly images: DoomImageSource,
    private readonly table: LightTable,
    private readonly skyTexture: Texture | undefined,
    private readonly warn: (m: string) => void,
    private readonly cycles: DoomCycles | undefined,
    private readonly patterns: ReadonlyMap<number, LightPattern>,
  ) {}

  private readonly animated = new Map<number, AnimatedMaterial>();

  /** A wall texture or flat in a sector at `lightLevel`; the plain material when the WAD lacks it. */
  material(kind: 'texture' | 'flat', name: string, lightLevel: number, masked: boolean, place: SurfacePlace = {}): number {
    const image = kind === 'texture' ? this.images.texture(name) : this.images.flat(name);
    if (!image) {
      // Missing wall textures were reported by buildWalls; missing flats are reported here.
      if (kind === 'flat' && !this.warnedFlats.has(name)) {
        this.warnedFlats.add(name);
        this.warn(`flat ${name} is not in the WAD; drawn with a plain material`);
      }
      return this.missing();
    }
    const source = (kind === 'texture' ? this.table.textures : this.table.flats)[name];
    const emission = emissionOf(source, lightLevel);
    const pattern = emission && place.sector !== undefined ? this.patterns.get(place.sector) : undefined;
    const scroll = place.scroll === true;
    const key = `${kind}:${name}:${emission?.join(',') ?? ''}:${masked}${pattern ? `:sector ${place.sector}` : ''}${scroll ? ':scroll' : ''}`;
    const before = this.materials.length;
    const index = this.add(key, () => {
      const texture = this.texture(image);
      const glow = source?.glow ? this.glow(image, source.glow) : texture;
      return diffuse(emission ? `${name} (glowing ${+emission[0].toFixed(3)})` : name, [1, 1, 1], emission ?? [0, 0, 0], {
        albedoTexture: { texture },
        ...(emission && { emissionTexture: { texture: glow } }),
        ...(masked && { alphaMode: 'mask' as const }),
      });
    });
    if (this.materials.length > before) {
      const member = this.cycles?.of(kind, name);
      const cycle = member && { names: member.cycle.names, frame: member.frame, ticsPerFrame: member.cycle.ticsPerFrame };
      if (cycle || scroll || pattern) this.animated.set(index, { kind, image, source, emits: emission !== undefined, scroll, ...(cycle && { cycle }), ...(pattern && { pattern }) });
    }
    return index;
  }

  /** The material animations of the animated materials made so far, or undefined when there are none. */
  private animations(): MaterialAnimations | undefined {
    const cycles: TextureCycle[] = [];
    const scrolls: UvScroll[] = [];
    const patterns: EmissionPattern[] = [];
    for (const [material, a] of this.animated) {
      if (a.cycle) {
        const images = a.cycle.names.map((n) => (a.kind === 'texture' ? this.images.texture(n) : this.images.flat(n)));
        const missing = a.cycle.names.filter((_, i) => !images[i]);
        if (missing.length > 0) this.warn(`animated ${a.kind} ${a.cycle.names[0]}–${a.cycle.names.at(-1)}: ${missing.join(', ')} cannot be read; not animated`);
        else {
          const frames = images.map((im) => this.texture(im!));
          const glow = a.source?.glow;
          cycles.push({
            material,
            frames,
            ...(a.emits && { emissionFrames: glow ? images.map((im) => this.glow(im!, glow)) : frames }),
            secondsPerFrame: a.cycle.ticsPerFrame / TICS_PER_SECOND,
            firstFrame: a.cycle.frame,
          });
        }
      }
      // One texture unit per tic, leftward: u grows (walls.ts: u = offset + distance along the line).
      if (a.scroll) scrolls.push({ material, velocity: [TICS_PER_SECOND / a.image.width, 0], stepSeconds: 1 / TICS_PER_SECOND });
      if (a.pattern) {
        const full = emissionOf(a.source, 255);
        if (full) patterns.push({ material, emission: full, fullLevel: 255, exponent: 2, ticsPerSecond: TICS_PER_SECOND, pattern: a.pattern });
      }
    }
    if (cycles.length + scrolls.length + patterns.length === 0) return undefined;
    return { ...(cycles.length && { cycles }), ...(scrolls.length && { scrolls }), ...(patterns.length && { patterns }) };
  }

  /**
   * A sprite lump's picture: masked like Doom's sprites, nearest. Light-giving things emit from their
   * bright texels on both faces, at full strength whatever the sector's light (Doom draws them full bright).
   */
  sprite(lump: string, picture: Texture, light: LightSource | undefined): number {
    const emission = emissionOf(light, 255);
    const key = `sprite:${lump}:${emission?.join(',') ?? ''}`;
    return this.add(key, () => {
      const texture = this.texture(picture);
      const glow = emission && light?.glow ? this.glow(picture, light.glow) : texture;
      return diffuse(emission ? `${lump} (glowing ${+emission[0].toFixed(3)})` : lump, [1, 1, 1], emission ?? [0, 0, 0], {
        albedoTexture: { texture },
        alphaMode: 'mask',
        ...(emission && { emissionTexture: { texture: glow }, twoSidedEmission: true }),
      });
    });
  }

  /** Emits the sky picture by viewing direction, as Doom draws it behind F_SKY1; reflects nothing. */
  sky(): number {
    return this.add('sky', () => {
      const sky = this.skyTexture;
      if (!sky) return { kind: 'emissive', name: 'sky', emission: scale(PLAIN_SKY, SKY_STRENGTH) };
      return {
        kind: 'emissive',
        name: `sky ${sky.name}`,
        emission: [SKY_STRENGTH, SKY_STRENGTH, SKY_STRENGTH],
        emissionTexture: { texture: this.texture(sky) },
        emissionMapping: {
          kind: 'panorama',
          repeats: SKY_COLUMNS_PER_TURN / sky.width,
          horizonV: SKY_HORIZON_ROW / sky.height,
          vPerRadian: SKY_ROWS_PER_RADIAN / sky.height,
        },
      };
    });
  }

  /** For surfaces whose texture is missing: plain mid grey. */
  missing(): number {
    return this.add('missing', () => diffuse('missing texture', MISSING_ALBEDO));
  }

  meshFor(material: number): MeshParts {
    let mesh = this.meshes.get(material);
    if (!mesh) this.meshes.set(material, (mesh = new MeshParts()));
    return mesh;
  }

  finish(): { meshes: Mesh[]; materials: Material[]; textures: Texture[]; animations: MaterialAnimations | undefined } {
    const animations = this.animations();
    const meshes: Mesh[] = [];
    for (const [material, parts] of this.meshes) {
      const mesh = parts.build(this.materials[material]!.name, material);
      if (mesh) meshes.push(mesh);
    }
    return { meshes, materials: this.materials, textures: this.textures, animations };
  }

  private add(key: string, make: () => Material): number {
    let index = this.materialIndex.get(key);
    if (index === undefined) {
      index = this.materials.push(make()) - 1;
      this.materialIndex.set(key, index);
    }
    return index;
  }

  /** The glowing part of an image (light-table.ts glowTexture), made once per image and threshold. */
  private glow(image: Texture, threshold: number): number {
    const key = `${image.name}@${threshold}`;
    let glow = this.glowImages.get(key);
    if (!glow) this.glowImages.set(key, (glow = glowTexture(image, threshold)));
    return this.texture(glow);
  }

  /** Each image once (the image source hands out one object per name). */
  private texture(image: Texture): number {
    let index = this.textureIndex.get(image);
    if (index === undefined) {
      // Doom's texels are seen as pixels, never blurred.
      index = this.textures.push({ ...image, filter: 'nearest' }) - 1;
      this.textureIndex.set(image, index);
    }
    return index;
  }
}
