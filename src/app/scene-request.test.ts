import { describe, expect, it } from 'vitest';
import { squareRoomsWad } from '../loaders/doom/test-wad.ts';
import { CAFFEINE_MOL } from '../loaders/molecule/caffeine.ts';
import { SceneRequests, siblingResolver } from './scene-request.ts';

const bytes = (...values: number[]) => new Uint8Array(values);

describe('SceneRequests', () => {
  it('opens a WAD set, lists its maps and loads the one asked for', async () => {
    const requests = new SceneRequests();
    const summary = await requests.openFiles({ format: 'doom-wad', files: [{ name: 'rooms.wad', bytes: squareRoomsWad([{ name: 'MAP01' }, { name: 'MAP02' }]) }], siblings: [] });
    expect(summary).toEqual({ format: 'doom-wad', description: 'rooms.wad', parts: [{ name: 'MAP01', loadable: true }, { name: 'MAP02', loadable: true }] });
    const loaded = await requests.load({ kind: 'part', part: 'MAP02' });
    expect(loaded.prepared.scene.name).toBe('MAP02');
    expect(loaded.prepared.triangles.count).toBeGreaterThan(0);
    // The request's skill reaches the Doom loader (which checks it).
    expect((await requests.load({ kind: 'part', part: 'MAP01', skill: 5 })).prepared.scene.name).toBe('MAP01');
    await expect(requests.load({ kind: 'part', part: 'MAP01', skill: 6 })).rejects.toThrow(/skill 6 is not a Doom skill level/);
  });

  it('opens a molecule: its styles are the parts the page picks from', async () => {
    const requests = new SceneRequests();
    const summary = await requests.openFiles({ format: 'molfile', files: [{ name: 'caffeine.mol', bytes: new TextEncoder().encode(CAFFEINE_MOL) }], siblings: [] });
    expect(summary.parts.map((p) => p.name)).toEqual(['ball-and-stick', 'space-filling']);
    const loaded = await requests.load({ kind: 'part', part: 'space-filling' });
    expect(loaded.prepared.scene.name).toBe('caffeine.mol#space-filling');
    expect(loaded.prepared.scene.meshes[0]!.spheres!.radii).toHaveLength(24);
  });

  it('names the file that is not what its format expects, and loads nothing before a set is open', async () => {
    const requests = new SceneRequests();
    await expect(requests.openFiles({ format: 'doom-wad', files: [{ name: 'garbage.wad', bytes: bytes(1, 2, 3) }], siblings: [] })).rejects.toThrow(/garbage\.wad: not a WAD file/);
    await expect(requests.load({ kind: 'part' })).rejects.toThrow(/no file is open/);
  });
});

describe('siblingResolver', () => {
  const fetched: string[] = [];
  const fetchFile = (url: string) => {
    fetched.push(url);
    return Promise.resolve(url.endsWith('/here.bin') ? bytes(9) : undefined);
  };

  it('finds given files by name or folder path before fetching beside the served file', async () => {
    const resolve = siblingResolver({ siblings: [{ name: 'helmet/textures/a.png', bytes: bytes(1) }, { name: 'b.bin', bytes: bytes(2) }], baseUrl: 'http://h/files/0/scene.gltf' }, fetchFile);
    expect(await resolve('textures/a.png')).toEqual(bytes(1));
    expect(await resolve('b.bin')).toEqual(bytes(2));
    expect(fetched).toEqual([]);
    expect(await resolve('here.bin')).toEqual(bytes(9));
    expect(await resolve('sub/missing.png')).toBeUndefined();
    expect(fetched).toEqual(['http://h/files/0/here.bin', 'http://h/files/0/sub/missing.png']);
  });

  it('answers undefined for a file neither given nor served', async () => {
    expect(await siblingResolver({ siblings: [] }, fetchFile)('a.png')).toBeUndefined();
  });
});

describe('siblingResolver with folder paths', () => {
  it('prefers the exact relative path over another file of the same name, and reads escaped URIs', async () => {
    const resolve = siblingResolver({ siblings: [{ name: '../other/a.png', bytes: bytes(1) }, { name: 'textures/a.png', bytes: bytes(2) }, { name: 'my wood.png', bytes: bytes(3) }] }, () => Promise.resolve(undefined));
    expect(await resolve('textures/a.png')).toEqual(bytes(2));
    expect(await resolve('./textures/a.png')).toEqual(bytes(2));
    expect(await resolve('my%20wood.png')).toEqual(bytes(3));
    expect(await resolve('../other/a.png')).toEqual(bytes(1));
  });
});

describe('SceneRequests warnings', () => {
  it('passes on the warnings a scene carries (a glTF missing a texture), each once', async () => {
    const { Document, NodeIO } = await import('@gltf-transform/core');
    const doc = new Document();
    doc.createBuffer();
    const position = doc.createAccessor().setType('VEC3').setArray(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]));
    const texture = doc.createTexture('wood').setURI('textures/wood.png').setMimeType('image/png').setImage(new Uint8Array([0x89, 0x50, 0x4e, 0x47]));
    const material = doc.createMaterial().setBaseColorTexture(texture);
    const mesh = doc.createMesh().addPrimitive(doc.createPrimitive().setAttribute('POSITION', position).setMaterial(material));
    doc.createScene().addChild(doc.createNode().setMesh(mesh));
    // The texture's bytes are left out of the set: only the .gltf and its .bin are given.
    const { json, resources } = await new NodeIO().writeJSON(doc);
    delete (resources as Record<string, Uint8Array>)['textures/wood.png'];
    const siblings = Object.entries(resources).map(([name, b]) => ({ name, bytes: b }));
    const requests = new SceneRequests();
    await requests.openFiles({ format: 'gltf', files: [{ name: 'tri.gltf', bytes: new TextEncoder().encode(JSON.stringify(json)) }], siblings });
    const loaded = await requests.load({ kind: 'part' });
    const named = loaded.warnings.filter((w) => w.includes('textures/wood.png'));
    expect(named).toHaveLength(1);
    expect(loaded.prepared.triangles.count).toBe(1);
  });
});
