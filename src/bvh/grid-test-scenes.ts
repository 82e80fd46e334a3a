/**
 * Test scenes for the grid traversal (bvh/grid.ts): a tile map like a Wolfenstein level (wall faces
 * on a square grid of tiles, a floor and a ceiling quad per open tile, the map's grid as
 * Scene.tileGrid), optionally with a moving door panel and a static sphere. Seeded; pure.
 */
import { fromTrs, IDENTITY, translation } from '../math/mat4.ts';
import { seededRandom } from '../math/seeded-random.ts';
import { diffuse, type Mesh, type Scene } from '../scene/types.ts';

export interface TileMapOptions {
  /** Tiles on each side (the map is n × n, its border solid). */
  readonly n?: number;
  /** A tile's side and the walls' height, in scene units. */
  readonly tile?: number;
  readonly height?: number;
  readonly seed?: number;
  /** A door panel (a moving instance) in an open tile, and a few moving spheres. */
  readonly moving?: boolean;
}

/** The tile map; solid tiles at about a quarter of the inside, chosen by the seed. */
export function tileMapScene(options: TileMapOptions = {}): Scene {
  const n = options.n ?? 64, tile = options.tile ?? 2, height = options.height ?? 2.5;
  const rnd = seededRandom(options.seed ?? 7);
  const solid = (x: number, z: number) => x <= 0 || z <= 0 || x >= n - 1 || z >= n - 1 || map[z * n + x] === 1;
  const map = new Uint8Array(n * n);
  for (let z = 1; z < n - 1; z++) for (let x = 1; x < n - 1; x++) map[z * n + x] = rnd() < 0.25 ? 1 : 0;
  const positions: number[] = [], uvs: number[] = [], materialIds: number[] = [];
  // A quad from corner a along u and v, as two triangles with their uvs.
  const quad = (a: readonly number[], u: readonly number[], v: readonly number[], material: number) => {
    const p = (s: number, t: number) => [a[0]! + s * u[0]! + t * v[0]!, a[1]! + s * u[1]! + t * v[1]!, a[2]! + s * u[2]! + t * v[2]!];
    for (const [s, t] of [[0, 0], [1, 0], [1, 1], [0, 0], [1, 1], [0, 1]] as const) {
      positions.push(...p(s, t));
      uvs.push(s, t);
    }
    materialIds.push(material, material);
  };
  for (let z = 0; z < n; z++) {
    for (let x = 0; x < n; x++) {
      const x0 = x * tile, z0 = z * tile;
      if (!solid(x, z)) {
        quad([x0, 0, z0], [0, 0, tile], [tile, 0, 0], 0); // floor, facing up
        quad([x0, height, z0], [tile, 0, 0], [0, 0, tile], 1); // ceiling, facing down
        continue;
      }
      // Faces toward open neighbours only, as a tile map's walls are drawn.
      if (x + 1 < n && !solid(x + 1, z)) quad([x0 + tile, 0, z0], [0, 0, tile], [0, height, 0], 2);
      if (x > 0 && !solid(x - 1, z)) quad([x0, 0, z0 + tile], [0, 0, -tile], [0, height, 0], 2);
      if (z + 1 < n && !solid(x, z + 1)) quad([x0 + tile, 0, z0 + tile], [-tile, 0, 0], [0, height, 0], 3);
      if (z > 0 && !solid(x, z - 1)) quad([x0, 0, z0], [tile, 0, 0], [0, height, 0], 3);
    }
  }
  const count = positions.length / 3;
  const walls: Mesh = {
    name: 'tile map',
    positions: new Float32Array(positions),
    uvs: new Float32Array(uvs),
    indices: Uint32Array.from({ length: count }, (_, i) => i),
    materialIds: new Uint32Array(materialIds),
  };
  // An open tile near the middle for the camera and the door.
  let open = 0;
  for (let k = 0; k < n * n; k++) {
    const c = ((n * n) >> 1) + (k % 2 ? -1 : 1) * (k >> 1);
    if (!solid(c % n, Math.floor(c / n))) {
      open = c;
      break;
    }
  }
  const ox = (open % n) * tile + tile / 2, oz = Math.floor(open / n) * tile + tile / 2;
  const meshes: Mesh[] = [walls];
  const instances: Scene['instances'][number][] = [{ id: 0, mesh: 0, worldFromObject: IDENTITY }];
  // A static sphere on the floor (analytic primitives in the grid too).
  meshes.push({ name: 'ball', positions: new Float32Array(), indices: new Uint32Array(), materialIds: new Uint32Array(), spheres: { centers: new Float32Array([ox + tile, 0.3, oz]), radii: new Float32Array([0.3]), materialIds: new Uint32Array([4]) } });
  instances.push({ id: 1, mesh: 1, worldFromObject: IDENTITY });
  if (options.moving) {
    const door: Mesh = {
      name: 'door',
      positions: new Float32Array([0, 0, 0, tile, 0, 0, tile, height, 0, 0, 0, 0, tile, height, 0, 0, height, 0]),
      indices: Uint32Array.from({ length: 6 }, (_, i) => i),
      materialIds: new Uint32Array([4, 4]),
    };
    meshes.push(door);
    instances.push({ id: 2, mesh: 2, worldFromObject: translation([ox - tile / 2, 0, oz + tile * 0.25]), moves: true });
    instances.push({ id: 3, mesh: 1, worldFromObject: fromTrs([-tile, 0.5, tile], [0, 0, 0, 1], [1, 1, 1]), moves: true });
  }
  return {
    name: 'tile map',
    meshes,
    instances,
    materials: [diffuse('floor', [0.4, 0.4, 0.4]), diffuse('ceiling', [0.7, 0.7, 0.7], [1.5, 1.4, 1.2]), diffuse('wall ns', [0.6, 0.3, 0.2]), diffuse('wall ew', [0.3, 0.15, 0.1]), diffuse('ball', [0.2, 0.3, 0.8])],
    camera: { position: [ox, height * 0.5, oz], forward: [1, -0.1, 0.7], up: [0, 1, 0], vfovDegrees: 75 },
    environment: { kind: 'constant', radiance: [1, 1, 1] },
    tileGrid: { origin: [0, 0, 0], cellSize: [tile, height, tile], dims: [n, 1, n] },
  };
}
