#!/usr/bin/env python3
"""
Lantern's built-in `materials` scene rebuilt in Mitsuba 3, rendered under a uniform white
environment, and compared with Lantern's EXR of the same scene (docs/materials.md).

    python3 -m venv /tmp/mtsvenv && /tmp/mtsvenv/bin/pip install mitsuba numpy
    PY=/tmp/mtsvenv/bin/python S=scripts/compare/mitsuba_materials.py
    $PY $S --write-env const.hdr
    VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json node dist/cli/lantern.mjs render materials \
        --width 192 --height 108 --spp 64 --bounces 8 --env const.hdr --exr lantern.exr
    $PY $S --width 192 --height 108 --spp 4096 --bounces 8 --noise-spp 64 --noise-out mitsuba64.exr --out mitsuba.exr
    node dist/cli/lantern.mjs diff lantern.exr mitsuba.exr --json --heatmap heat.png --heatmap-scale 0.5
    $PY $S --from-exr mitsuba.exr --lantern lantern.exr --json compare.json --figure compare.png --heatmap heat.png

Everything the scene is made of is written here from the constants of
src/loaders/builtin/materials.ts (keep them in step):

- spheres: Mitsuba `sphere` shapes (exact); Lantern tessellates them as 96 x 48 UV spheres with
  interpolated normals;
- floor: Lantern's 80 x 80 square with a 2 x 2 sRGB checker (200 / 120, nearest) repeated 20 times
  over it, times albedo 0.8. Here it is written as two meshes of 2 x 2 tiles, one per tone, each a
  plain `diffuse` (so no texture convention, v flip or filtering can differ);
- metals (F0 = base colour through Schlick, GGX with alpha = roughness^2): `principled` with
  metallic 1, whose metallic Fresnel is Schlick with F0 = base colour, i.e. the same Fresnel as
  Lantern (a `conductor` would need an eta/k per channel and has the exact conductor Fresnel
  curve, not Schlick's). Mitsuba has no multiple-scattering compensation;
- glass: `dielectric` / `roughdielectric` (GGX, alpha = 0.35^2), ior 1.5;
- red plastic: `principled` metallic 0, specular 0.5 (F0 0.04, eta 1.5), roughness 0.25;
  Lantern's is the glTF layer (specular over an albedo-scaled Lambertian base), Mitsuba's the
  Disney-style mix (its diffuse has a retro-reflection term and no albedo scaling);
- diffuse reference: `diffuse` 0.8;
- environment: `constant` emitter of radiance 1 (Lantern: --env with a constant .hdr);
- camera: position (0, 4, 15), forward (0, -0.22, -1), up (0, 1, 0), vertical fov 40 deg; box
  pixel filter; `path` integrator with max_depth = bounces + 1 (Lantern's bounces 0 = emitters only).
"""
import argparse
import json
import math
import os
import struct
import sys
import zlib

import numpy as np

SPHERE_RADIUS = 1.0
SPACING = 2.3
FLOOR_HALF = 40.0
FLOOR_TILES = 20  # uv repeats over the floor; the texture is 2 x 2, so 40 tiles of 2 units a side
SILVER = (0.95, 0.93, 0.88)
GOLD = (1.0, 0.766, 0.336)
CAMERA = dict(position=(0.0, 4.0, 15.0), forward=(0.0, -0.22, -1.0), up=(0.0, 1.0, 0.0), vfov=40.0)

# name, kind, params (left to right, as MATERIAL_SPHERES)
SPHERES = [
    ('mirror', 'metal', dict(color=SILVER, roughness=0.0)),
    ('metal, roughness 0.25', 'metal', dict(color=SILVER, roughness=0.25)),
    ('metal, roughness 0.5', 'metal', dict(color=SILVER, roughness=0.5)),
    ('metal, roughness 1', 'metal', dict(color=SILVER, roughness=1.0)),
    ('gold, roughness 0.3', 'metal', dict(color=GOLD, roughness=0.3)),
    ('glass', 'glass', dict(ior=1.5, roughness=0.0)),
    ('frosted glass', 'glass', dict(ior=1.5, roughness=0.35)),
    ('red plastic', 'plastic', dict(color=(0.7, 0.06, 0.05), roughness=0.25)),
    ('diffuse reference', 'diffuse', dict(color=(0.8, 0.8, 0.8))),
]


def sphere_centers():
    n = len(SPHERES)
    return [((i - (n - 1) / 2) * SPACING, SPHERE_RADIUS, 0.0) for i in range(n)]


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


# --- tiny file writers ---------------------------------------------------------------------------

def write_constant_hdr(path, radiance=1.0, width=4, height=2):
    """A Radiance RGBE (.hdr) image of one constant radiance, flat (uncompressed) scanlines."""
    m, e = math.frexp(radiance)  # radiance = m * 2^e, 0.5 <= m < 1
    pixel = bytes([int(m * 256)] * 3 + [e + 128])
    with open(path, 'wb') as f:
        f.write(b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n')
        f.write(b'-Y %d +X %d\n' % (height, width))
        f.write(pixel * (width * height))


def write_exr(path, rgb):
    """An uncompressed scanline OpenEXR of float32 R, G, B (what `lantern diff` reads)."""
    h, w, _ = rgb.shape

    def attr(name, typ, data):
        return name.encode() + b'\0' + typ.encode() + b'\0' + struct.pack('<i', len(data)) + data

    chlist = b''.join(c.encode() + b'\0' + struct.pack('<iBBBBii', 2, 0, 0, 0, 0, 1, 1) for c in 'BGR') + b'\0'
    header = b''.join([
        struct.pack('<ii', 20000630, 2),
        attr('channels', 'chlist', chlist),
        attr('compression', 'compression', b'\0'),
        attr('dataWindow', 'box2i', struct.pack('<iiii', 0, 0, w - 1, h - 1)),
        attr('displayWindow', 'box2i', struct.pack('<iiii', 0, 0, w - 1, h - 1)),
        attr('lineOrder', 'lineOrder', b'\0'),
        attr('pixelAspectRatio', 'float', struct.pack('<f', 1.0)),
        attr('screenWindowCenter', 'v2f', struct.pack('<ff', 0.0, 0.0)),
        attr('screenWindowWidth', 'float', struct.pack('<f', 1.0)),
        b'\0',
    ])
    line_bytes = 8 + w * 3 * 4
    start = len(header) + 8 * h
    offsets = struct.pack('<%dQ' % h, *[start + y * line_bytes for y in range(h)])
    body = bytearray()
    data = np.ascontiguousarray(rgb, dtype='<f4')
    for y in range(h):
        body += struct.pack('<ii', y, w * 3 * 4)
        for c in (2, 1, 0):  # channels in alphabetical order: B, G, R
            body += data[y, :, c].tobytes()
    with open(path, 'wb') as f:
        f.write(header + offsets + bytes(body))


def write_ply(path, vertices, faces):
    with open(path, 'wb') as f:
        f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
                 'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'
                 % (len(vertices), len(faces))).encode())
        f.write(np.asarray(vertices, dtype='<f4').tobytes())
        for face in faces:
            f.write(struct.pack('<Biii', 3, *face))


def floor_meshes(directory):
    """Lantern's checker: texel (i, j) = floor((x + 40) / 2) mod 2, floor((z + 40) / 2) mod 2 (u along
    x, v along z, 2 texels per uv unit, 20 uv units over 80); tone 200 where i + j is even, else 120."""
    tile = 2 * FLOOR_HALF / (2 * FLOOR_TILES)
    n = int(round(2 * FLOOR_HALF / tile))
    paths = {}
    for parity in (0, 1):
        verts, faces = [], []
        for i in range(n):
            for j in range(n):
                if (i + j) % 2 != parity:
                    continue
                x0, z0 = -FLOOR_HALF + i * tile, -FLOOR_HALF + j * tile
                k = len(verts)
                # counter-clockwise seen from above (+y normal)
                verts += [(x0, 0, z0), (x0, 0, z0 + tile), (x0 + tile, 0, z0 + tile), (x0 + tile, 0, z0)]
                faces += [(k, k + 1, k + 2), (k, k + 2, k + 3)]
        p = os.path.join(directory, 'floor_%d.ply' % parity)
        write_ply(p, verts, faces)
        paths[parity] = p
    return paths


# --- the scene -----------------------------------------------------------------------------------

def bsdf_for(kind, p):
    if kind == 'metal':
        return {'type': 'principled', 'base_color': {'type': 'rgb', 'value': list(p['color'])},
                'metallic': 1.0, 'roughness': p['roughness'], 'specular': 0.5}
    if kind == 'glass':
        if p['roughness'] == 0:
            return {'type': 'dielectric', 'int_ior': p['ior'], 'ext_ior': 1.0}
        return {'type': 'roughdielectric', 'distribution': 'ggx', 'alpha': p['roughness'] ** 2,
                'int_ior': p['ior'], 'ext_ior': 1.0}
    if kind == 'plastic':
        return {'type': 'principled', 'base_color': {'type': 'rgb', 'value': list(p['color'])},
                'metallic': 0.0, 'roughness': p['roughness'], 'specular': 0.5}
    if kind == 'diffuse':
        return {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': list(p['color'])}}
    raise ValueError(kind)


def build_scene(mi, width, height, spp, bounces, seed, tmpdir):
    pos = np.array(CAMERA['position'])
    fwd = np.array(CAMERA['forward']) / np.linalg.norm(CAMERA['forward'])
    floors = floor_meshes(tmpdir)
    tones = {0: 0.8 * srgb_to_linear(200 / 255), 1: 0.8 * srgb_to_linear(120 / 255)}
    scene = {
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': bounces + 1, 'hide_emitters': False},
        'sensor': {
            'type': 'perspective',
            'fov_axis': 'y',
            'fov': CAMERA['vfov'],
            'to_world': mi.ScalarTransform4f().look_at(origin=list(pos), target=list(pos + fwd), up=list(CAMERA['up'])),
            'sampler': {'type': 'independent', 'sample_count': spp, 'seed': seed},
            'film': {'type': 'hdrfilm', 'width': width, 'height': height, 'rfilter': {'type': 'box'},
                     'pixel_format': 'rgb', 'component_format': 'float32'},
        },
        'env': {'type': 'constant', 'radiance': {'type': 'rgb', 'value': [1.0, 1.0, 1.0]}},
    }
    for parity, path in floors.items():
        scene['floor_%d' % parity] = {'type': 'ply', 'filename': path, 'face_normals': True,
                                      'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [tones[parity]] * 3}}}
    for i, ((name, kind, p), c) in enumerate(zip(SPHERES, sphere_centers())):
        scene['sphere_%d' % i] = {'type': 'sphere', 'center': list(c), 'radius': SPHERE_RADIUS, 'bsdf': bsdf_for(kind, p)}
    return scene


# --- masks and statistics --------------------------------------------------------------------------

def sphere_masks(width, height):
    """Per sphere, the pixels whose centre and four corners all see that sphere first (pinhole camera,
    screen right = forward x up, as Lantern's), so edges and the floor never leak into a mean."""
    pos = np.array(CAMERA['position'])
    fwd = np.array(CAMERA['forward']) / np.linalg.norm(CAMERA['forward'])
    right = np.cross(fwd, CAMERA['up']); right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = math.tan(math.radians(CAMERA['vfov']) / 2)
    aspect = width / height
    centers = sphere_centers()

    def first_hit(px, py):
        sx = (2 * px / width - 1) * t * aspect
        sy = (1 - 2 * py / height) * t
        d = fwd[None, None, :] + sx[..., None] * right + sy[..., None] * up
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        best = np.full(px.shape, np.inf); which = np.full(px.shape, -1)
        for k, c in enumerate(centers):
            oc = pos - np.array(c)
            b = (d * oc).sum(-1)
            disc = b * b - (oc @ oc - SPHERE_RADIUS ** 2)
            hit = disc > 0
            tt = np.where(hit, -b - np.sqrt(np.maximum(disc, 0)), np.inf)
            closer = hit & (tt > 0) & (tt < best)
            best = np.where(closer, tt, best); which = np.where(closer, k, which)
        return which

    ys, xs = np.mgrid[0:height, 0:width].astype(float)
    samples = [first_hit(xs + 0.5, ys + 0.5)] + [first_hit(xs + dx, ys + dy) for dx in (0, 1) for dy in (0, 1)]
    return [np.all([s == k for s in samples], axis=0) for k in range(len(centers))]


def luminance(rgb):
    return 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]


def rel_mse(img, ref):
    return float(np.mean((img - ref) ** 2 / (ref ** 2 + 0.01)))


def read_exr(mi, path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False), dtype=np.float64)


def compare(mi, lantern_path, mitsuba_rgb, extra_mitsuba=None):
    lan = read_exr(mi, lantern_path)
    mts = mitsuba_rgb
    h, w, _ = mts.shape
    if lan.shape != mts.shape:
        sys.exit('size mismatch: lantern %s, mitsuba %s' % (lan.shape, mts.shape))
    masks = sphere_masks(w, h)
    rows = []
    for (name, kind, _), m in zip(SPHERES, masks):
        l_mean = lan[m].mean(0); m_mean = mts[m].mean(0)
        row = dict(material=name, pixels=int(m.sum()), lantern=l_mean.tolist(), mitsuba=m_mean.tolist(),
                   lantern_lum=float(luminance(l_mean)), mitsuba_lum=float(luminance(m_mean)))
        row['rel_diff'] = (row['lantern_lum'] - row['mitsuba_lum']) / row['mitsuba_lum']
        if extra_mitsuba is not None:  # a second, independent Mitsuba render: the noise floor of the mean
            e = float(luminance(extra_mitsuba[m].mean(0)))
            row['mitsuba_noise_rel_diff'] = (e - row['mitsuba_lum']) / row['mitsuba_lum']
        rows.append(row)
    floor = ~np.any(masks, axis=0)
    noise = {} if extra_mitsuba is None else dict(noise_rel_mse=rel_mse(extra_mitsuba, mts))
    return dict(**noise, rel_mse=rel_mse(lan, mts), rel_mse_outside_spheres=float(np.mean(((lan - mts) ** 2 / (mts ** 2 + 0.01))[floor])),
                spheres=rows, masks=masks)


def figure(mi, panels_linear, heatmap_png, out_png, scale=2):
    """Lantern | Mitsuba | heat map, side by side: both renders through one tone curve (clamp to 1,
    sRGB), so what differs is the radiance; each panel enlarged `scale` times (nearest)."""
    def srgb(x):
        x = np.clip(x, 0, 1)
        return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)
    panels = [srgb(p) for p in panels_linear]
    if heatmap_png:
        heat = np.array(mi.Bitmap(heatmap_png).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False), dtype=np.float64)
        panels.append(srgb(heat))  # back to the PNG's own (display) values
    gap = np.ones((panels[0].shape[0], 2, 3))
    row = np.concatenate(sum(([p, gap] for p in panels), [])[:-1], axis=1)
    row = row.repeat(scale, 0).repeat(scale, 1)
    mi.Bitmap(np.ascontiguousarray(row, dtype=np.float32)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=False).write(out_png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--width', type=int, default=192)
    ap.add_argument('--height', type=int, default=108)
    ap.add_argument('--spp', type=int, default=1024)
    ap.add_argument('--bounces', type=int, default=8)
    ap.add_argument('--seed', type=int, default=0)
    ap.add_argument('--variant', default='scalar_rgb')
    ap.add_argument('--out', help='Mitsuba EXR to write')
    ap.add_argument('--noise-spp', type=int, default=0,
                    help='also render another seed at this many spp (e.g. Lantern\'s) and report its per-sphere difference: the noise floor')
    ap.add_argument('--noise-out', help='write the --noise-spp render here (EXR)')
    ap.add_argument('--lantern', help="Lantern's EXR of the same scene to compare with")
    ap.add_argument('--json', help='write the comparison here')
    ap.add_argument('--mask-png', help='write the sphere masks as a PNG (a check of the projection)')
    ap.add_argument('--figure', help='write Lantern | Mitsuba | heat map as a PNG here (needs --lantern)')
    ap.add_argument('--heatmap', help="a heat map PNG from `lantern diff --heatmap` for --figure")
    ap.add_argument('--from-exr', help='compare this Mitsuba EXR instead of rendering')
    ap.add_argument('--write-env', help='only write the constant radiance-1 .hdr for Lantern here')
    ap.add_argument('--tmp', default='/tmp/lantern-mitsuba')
    a = ap.parse_args()

    if a.write_env:
        write_constant_hdr(a.write_env)
        return

    import mitsuba as mi
    mi.set_variant(a.variant)
    os.makedirs(a.tmp, exist_ok=True)

    def render(seed, spp=a.spp):
        scene = mi.load_dict(build_scene(mi, a.width, a.height, spp, a.bounces, seed, a.tmp))
        return np.array(mi.render(scene, seed=seed), dtype=np.float64)[..., :3]

    img = read_exr(mi, a.from_exr) if a.from_exr else render(a.seed)
    if a.out:
        write_exr(a.out, img.astype(np.float32))
    extra = render(a.seed + 1, a.noise_spp) if a.noise_spp else None
    if extra is not None and a.noise_out:
        write_exr(a.noise_out, extra.astype(np.float32))
    if a.lantern:
        result = compare(mi, a.lantern, img, extra)
        masks = result.pop('masks')
        if a.mask_png:
            mi.Bitmap((np.any(masks, axis=0)[..., None] * np.ones(3)).astype(np.float32)).convert(
                mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(a.mask_png)
        print('relMSE (whole image) %.5f, outside the spheres %.5f' % (result['rel_mse'], result['rel_mse_outside_spheres']))
        if 'noise_rel_mse' in result:
            print('relMSE of a %d-spp Mitsuba render against this one (noise floor) %.5f' % (a.noise_spp, result['noise_rel_mse']))
        print('%-24s %6s %10s %10s %9s %s' % ('material', 'pixels', 'lantern', 'mitsuba', 'rel.diff', '(mitsuba, %d spp, other seed)' % a.noise_spp if extra is not None else ''))
        for r in result['spheres']:
            print('%-24s %6d %10.4f %10.4f %+8.2f%% %s' % (r['material'], r['pixels'], r['lantern_lum'], r['mitsuba_lum'], 100 * r['rel_diff'],
                                                         ('%+.2f%%' % (100 * r['mitsuba_noise_rel_diff'])) if extra is not None else ''))
        if a.figure:
            figure(mi, [read_exr(mi, a.lantern), img], a.heatmap, a.figure)
        if a.json:
            with open(a.json, 'w') as f:
                json.dump(dict(width=a.width, height=a.height, spp=a.spp, bounces=a.bounces, variant=a.variant, **result), f, indent=1)


if __name__ == '__main__':
    main()
