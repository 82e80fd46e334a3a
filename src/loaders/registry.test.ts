import { gzipSync } from 'fflate';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../errors.ts';
import { expectLanternError } from '../expect-lantern-error.ts';
import { squareRoomWad, squareRoomsWad } from './doom/test-wad.ts';
import { acceptedExtensions, describeFormats, FORMATS, formatOfSet, identify, NO_SIBLINGS, parseSceneReference, sortFiles, type FileHead } from './registry.ts';
import { formatSceneLocation, parseSceneLocation } from './scene-link.ts';

/** A two-triangle square: the smallest PLY that loads. */
const PLY = new TextEncoder().encode(
  ['ply', 'format ascii 1.0', 'element vertex 4', 'property float x', 'property float y', 'property float z', 'element face 2', 'property list uchar int vertex_indices', 'end_header', '0 0 0', '1 0 0', '1 1 0', '0 1 0', '3 0 1 2', '3 0 2 3', ''].join('\n'),
);
const file = (name: string, bytes: Uint8Array): FileHead & { bytes: Uint8Array } => ({ name, head: bytes, bytes });
const id = (f: FileHead) => identify(f)?.id;

describe('identifying formats', () => {
  it('knows each entry by its extension when the bytes say nothing', () => {
    const nothing = new Uint8Array(16);
    expect(id(file('E1.WAD', nothing))).toBe('doom-wad');
    expect(id(file('bunny.ply', nothing))).toBe('ply');
    expect(id(file('bunny.PLY.gz', nothing))).toBe('ply');
    expect(id(file('notes.txt', nothing))).toBeUndefined();
    expect(id(file('archive.gz', nothing))).toBeUndefined();
  });

  it('knows each entry by its magic bytes whatever the name', () => {
    expect(id(file('level.bin', squareRoomWad('MAP01', 'IWAD')))).toBe('doom-wad');
    expect(id(file('level.bin', squareRoomWad('MAP01', 'PWAD')))).toBe('doom-wad');
    expect(id(file('mesh', PLY))).toBe('ply');
    expect(id(file('mesh', new TextEncoder().encode('ply\r\nformat ascii 1.0\r\n')))).toBe('ply');
    // A gzip stream is claimed only when what it holds starts like a PLY.
    expect(id(file('download', gzipSync(PLY)))).toBe('ply');
    expect(id(file('download', gzipSync(new TextEncoder().encode('plywood\n'))))).toBeUndefined();
  });

  it('lets the content beat a wrong extension', () => {
    expect(id(file('mesh.wad', PLY))).toBe('ply');
    expect(id(file('map.ply', squareRoomWad()))).toBe('doom-wad');
    expect(id(file('mesh.wad', gzipSync(PLY)))).toBe('ply');
  });

  it('sniffs from the first bytes alone', async () => {
    const { SNIFF_BYTES } = await import('./registry.ts');
    const big = gzipSync(new Uint8Array([...PLY, ...new Uint8Array(200_000).map((_, i) => (i * 31) & 0xff)]));
    expect(id(file('x', big.subarray(0, SNIFF_BYTES)))).toBe('ply');
    expect(id(file('x', squareRoomWad().subarray(0, SNIFF_BYTES)))).toBe('doom-wad');
  });

  it('gives every entry a distinct id, link parameter and extensions that are lower case with a dot', () => {
    expect(new Set(FORMATS.map((f) => f.id)).size).toBe(FORMATS.length);
    expect(new Set(FORMATS.map((f) => f.linkParam)).size).toBe(FORMATS.length);
    for (const f of FORMATS) for (const e of f.extensions) expect(e).toMatch(/^\.[a-z0-9.]+$/);
  });

  it('offers every extension to the file picker and names every format in messages', () => {
    // A glTF's siblings (.bin, textures) are offered too: a user picks the .gltf with its files.
    expect(acceptedExtensions().split(',').sort()).toEqual(['.bin', '.glb', '.gltf', '.gz', '.jpeg', '.jpg', '.ktx2', '.mol', '.ply', '.png', '.sd', '.sdf', '.wad', '.webp', '.wl1', '.wl6']);
    expect(describeFormats()).toBe('Doom WADs (.wad), glTF 2.0 scenes (.glb, .gltf), PLY meshes (.ply.gz, .ply), MDL molecules (.mol, .sdf, .sd) and Wolfenstein 3D data files (.wl6, .wl1)');
  });
});

describe('file sets', () => {
  it('refuses a file no format reads, in one line naming the formats', () => {
    let e: LanternError | undefined;
    try {
      sortFiles([file('notes.txt', new TextEncoder().encode('hello'))]);
    } catch (thrown) {
      e = thrown as LanternError;
    }
    expect(e).toBeInstanceOf(LanternError);
    expect(e!.message).toBe("cannot open 'notes.txt': not a format Lantern reads");
    expect(e!.hint).toBe(`Lantern reads ${describeFormats()}`);
    expect(`${e!.message} ${e!.hint}`).not.toContain('\n');
  });

  it('puts IWADs before PWADs and keeps the PWADs in the order given', () => {
    const pwadA = file('a.wad', squareRoomWad('MAP02', 'PWAD'));
    const iwad = file('doom.wad', squareRoomWad('MAP01', 'IWAD'));
    const pwadB = file('b.wad', squareRoomWad('MAP03', 'PWAD'));
    const { format, main, siblings } = sortFiles([pwadA, iwad, pwadB]);
    expect(format.id).toBe('doom-wad');
    expect(main.map((f) => f.name)).toEqual(['doom.wad', 'a.wad', 'b.wad']);
    expect(siblings).toEqual([]);
  });

  it('keeps files no format claims as siblings of the scene (a glTF folder: .bin, textures)', () => {
    const texture = file('textures/wall.png', new Uint8Array([0x89, 0x50, 0x4e, 0x47]));
    const { format, main, siblings } = sortFiles([texture, file('mesh.ply', PLY)]);
    expect(format.id).toBe('ply');
    expect(main.map((f) => f.name)).toEqual(['mesh.ply']);
    expect(siblings).toEqual([texture]);
  });

  it('refuses two formats at once, and two files of a format that holds one scene per file', () => {
    expectLanternError(() => sortFiles([file('doom.wad', squareRoomWad()), file('mesh.ply', PLY)]), /doom\.wad and mesh\.ply as one scene: they are Doom WADs and PLY meshes/);
    expectLanternError(() => formatOfSet([file('a.ply', PLY), file('b.ply', PLY)]), /a\.ply, b\.ply together: PLY meshes are one file each/);
  });

  it('opens a WAD stack with its maps as parts and builds the map asked for', async () => {
    const { format, files } = formatOfSet([file('rooms.wad', squareRoomsWad([{ name: 'MAP01' }, { name: 'MAP02', size: 512 }]))]);
    const opened = await format.open({ files, resolve: NO_SIBLINGS });
    expect(opened.description).toBe('rooms.wad');
    expect(opened.parts).toEqual([{ name: 'MAP01', loadable: true }, { name: 'MAP02', loadable: true }]);
    expect((await opened.scene('MAP02')).name).toBe('MAP02');
    expect((await opened.scene()).name).toBe('MAP01');
    await expect(opened.scene('MAP09')).rejects.toThrow(/has no map 'MAP09'/);
  });

  it('opens a PLY as one scene named after its file', async () => {
    const { format, files } = formatOfSet([file('square.ply', PLY)]);
    const opened = await format.open({ files, resolve: NO_SIBLINGS });
    expect(opened.parts).toEqual([]);
    const scene = await opened.scene();
    expect(scene.name).toBe('square.ply');
    expect(scene.meshes[0]!.indices).toHaveLength(6);
  });
});

describe('scene arguments and links', () => {
  it('splits WAD stacks and maps, and leaves other paths whole', () => {
    expect(parseSceneReference('freedoom1.wad#E1M1')).toMatchObject({ paths: ['freedoom1.wad'], part: 'E1M1', format: { id: 'doom-wad' } });
    expect(parseSceneReference('iwad.wad+pwad.wad#map01')).toMatchObject({ paths: ['iwad.wad', 'pwad.wad'], part: 'MAP01' });
    expect(parseSceneReference('dir/mesh#1.ply')).toEqual({ paths: ['dir/mesh#1.ply'] });
    expect(() => parseSceneReference('notes.txt+pwad.wad#E1M1')).toThrow(/'notes\.txt' is not a \.wad file/);
  });

  it('keeps the link parameters: wad= (repeated) with map=, ply=, scene=', () => {
    const wad = parseSceneLocation(new URLSearchParams('wad=files/0/a.wad&wad=files/1/b.wad&map=e1m1'));
    expect(wad).toEqual({ kind: 'files', format: 'doom-wad', urls: ['files/0/a.wad', 'files/1/b.wad'], part: 'E1M1' });
    expect(formatSceneLocation(wad!).toString()).toBe('wad=files%2F0%2Fa.wad&wad=files%2F1%2Fb.wad&map=E1M1');
    const ply = parseSceneLocation(new URLSearchParams('ply=files/0/dragon.ply.gz&ply=ignored.ply&map=E1M1'));
    expect(ply).toEqual({ kind: 'files', format: 'ply', urls: ['files/0/dragon.ply.gz'] });
    expect(formatSceneLocation(ply!).toString()).toBe('ply=files%2F0%2Fdragon.ply.gz');
    expect(parseSceneLocation(new URLSearchParams('scene=furnace'))).toEqual({ kind: 'builtin', name: 'furnace' });
    expect(parseSceneLocation(new URLSearchParams('spf=2'))).toBeUndefined();
  });
});

describe('help', () => {
  it('names the built-ins, the aliases and every format with its extensions', async () => {
    const { describeSceneArguments } = await import('./registry.ts');
    const help = describeSceneArguments(['dragon']);
    expect(help).toMatch(/^a built-in scene \(cornell, furnace, bvh-teaching, materials, spheres, rtiow, orb, golden-grid, hex-grid, caffeine, dungeon, many-lights, prism\), 'dragon', or a file: /);
    for (const f of FORMATS) for (const e of f.extensions) expect(help).toContain(e);
    expect(help).toContain("Doom WADs (.wad, '+' joins files, '#map' picks one: iwad.wad+pwad.wad#MAP01)");
    expect(help).toContain("MDL molecules (.mol, .sdf, .sd, '#model' picks one: caffeine.mol#space-filling)");
  });
});
