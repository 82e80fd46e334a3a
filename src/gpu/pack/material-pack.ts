/**
 * Materials → the `materials` and `texture_refs` arrays and the two texture atlases of bind group 0
 * (shaders/scene/types.wgsl Material, TextureRef). Pure CPU. Each kind of the scene/types.ts union
 * fills the fields its BSDF case reads; a material's texture uses become TextureRef records (one per
 * distinct texture + transform + filter), colour textures go to the sRGB atlas and data textures to
 * the linear one.
 */
import { LanternError } from '../../errors.ts';
import { luminance, type Vec3 } from '../../math/vec3.ts';
import { packDispersion, type Dispersion } from '../../scene/dispersion.ts';
import { coverageOf, type Material, type MaterialKind, type Scene, type Texture, type TextureRef } from '../../scene/types.ts';
import type { StructLayout } from '../wgsl/reflect.ts';
import { StructArray } from './struct-array.ts';
import { fitForMips, mipLevelCount, withMipChain } from './mip-chain.ts';
import { MAX_PAGE_SIDE, meanLinearColor, packTextureAtlas, type TextureAtlas } from './texture-atlas.ts';

/** Sentinels and flag bits shared with shaders/scene/types.wgsl and lib/constants.wgsl. */
export const NO_TEXTURE = 0xffffffff;
export const MATERIAL_KINDS: readonly MaterialKind[] = ['diffuse', 'metallic-roughness', 'dielectric', 'emissive'];
export const MATERIAL_ALPHA_MASK = 1;
export const MATERIAL_EMISSION_PANORAMA = 2;
export const MATERIAL_ALPHA_BLEND = 4;
export const MATERIAL_THIN_WALLED = 16;
export const MATERIAL_SCATTER_IN_PLANE = 32;
export const MATERIAL_TWO_SIDED_EMISSION = 64;
/** shaders/scene/types.wgsl DISPERSION_*, by position. */
export const DISPERSION_LAWS = ['none', 'sellmeier', 'cauchy'] as const;
export const TEXTURE_LINEAR = 1;
export const TEXTURE_BILINEAR = 2;
export const TEXTURE_UV1 = 4;

export interface PackedMaterials {
  readonly materials: ArrayBuffer;
  readonly textureRefs: ArrayBuffer;
  /** sRGB colour textures (rgba8unorm-srgb pages) and linear data textures (rgba8unorm pages). */
  readonly atlas: TextureAtlas;
  readonly linearAtlas: TextureAtlas;
  /** Per material: luminance of its emission texture's mean linear colour (1 without one). */
  readonly emissionMean: readonly number[];
  /** Per material: whether its coverage can make holes (alpha mask or blend with something to test). */
  readonly hasHitFilter: readonly boolean[];
  /** Whether any material needs more than the Lambertian path (MATERIALS_GENERAL of SCENE_MATERIALS, shaders/scene/bsdf.wgsl). */
  readonly general: boolean;
  /** Whether any material reads per-vertex tangents (a normal map) or the second uv set. */
  readonly needsVertexAttributes: boolean;
  readonly textureRefCount: number;
  /** Per material: each texture field it uses → the texture and its transform (transformKey) as packed. */
  readonly textureUses: readonly ReadonlyMap<string, { readonly texture: number; readonly transform: string }>[];
  /**
   * Per animated material (world/material-animation.ts): per texture field, every texture its
   * animation can show → the material's own texture reference to it.
   */
  readonly animatedRefs: ReadonlyMap<number, ReadonlyMap<string, ReadonlyMap<number, number>>>;
  readonly warnings: readonly string[];
}

/** The texture uses of a material, by the WGSL field that holds each, and whether it is colour. */
function textureUses(m: Material): { field: string; ref: TextureRef; srgb: boolean }[] {
  const uses: { field: string; ref: TextureRef | undefined; srgb: boolean }[] = [
    { field: 'emission_texture', ref: m.emissionTexture, srgb: true },
    { field: 'normal_texture', ref: m.normalTexture, srgb: false },
  ];
  switch (m.kind) {
    case 'diffuse':
      uses.push({ field: 'base_color_texture', ref: m.albedoTexture, srgb: true });
      break;
    case 'metallic-roughness':
      uses.push(
        { field: 'base_color_texture', ref: m.baseColorTexture, srgb: true },
        { field: 'metallic_roughness_texture', ref: m.metallicRoughnessTexture, srgb: false },
        { field: 'specular_texture', ref: m.specularTexture, srgb: false },
        { field: 'specular_color_texture', ref: m.specularColorTexture, srgb: true },
        { field: 'transmission_texture', ref: m.transmissionTexture, srgb: false },
      );
      break;
    case 'dielectric':
    case 'emissive':
      break;
  }
  return uses.filter((u): u is { field: string; ref: TextureRef; srgb: boolean } => u.ref !== undefined);
}

/** The WGSL field of each animation edit's texture (scene/material-edit.ts MaterialAnimationEdit). */
export const ANIMATED_TEXTURE_FIELDS = { albedoTexture: 'base_color_texture', emissionTexture: 'emission_texture' } as const;

/**
 * Per animated material: the textures each field may show besides its own (a cycle's frames), and
 * an entry (possibly empty) for every material a scroll moves.
 */
function animatedTextureSets(scene: Scene): Map<number, Map<string, number[]>> {
  const a = scene.dynamics?.materialAnimations;
  const out = new Map<number, Map<string, number[]>>();
  const entry = (m: number) => {
    let e = out.get(m);
    if (!e) out.set(m, (e = new Map()));
    return e;
  };
  const add = (e: Map<string, number[]>, field: string, ts: readonly number[]) => e.set(field, [...(e.get(field) ?? []), ...ts]);
  for (const c of a?.cycles ?? []) {
    const e = entry(c.material);
    add(e, ANIMATED_TEXTURE_FIELDS.albedoTexture, c.frames);
    if (c.emissionFrames) add(e, ANIMATED_TEXTURE_FIELDS.emissionTexture, c.emissionFrames);
  }
  for (const s of a?.scrolls ?? []) entry(s.material);
  return out;
}

/** A texture reference's transform as a comparable key. */
const transformKey = (ref: TextureRef): string => JSON.stringify(ref.transform ?? null);

/** Writes a TextureRef record's transform rows: KHR_texture_transform, uv' = T · R · S · uv, R counter-clockwise in uv space. */
function transformWriter(textureRefs: StructArray): (i: number, ref: TextureRef) => void {
  const tu = textureRefs.vec3('transform_u'), tv = textureRefs.vec3('transform_v');
  return (i, ref) => {
    const t = ref.transform;
    const [ox, oy] = t?.offset ?? [0, 0];
    const [sx, sy] = t?.scale ?? [1, 1];
    const c = Math.cos(t?.rotation ?? 0), s = Math.sin(t?.rotation ?? 0);
    tu(i, c * sx, s * sy, ox);
    tv(i, -s * sx, c * sy, oy);
  };
}

/** Beer–Lambert coefficient −ln(colour)/distance per channel (0 for a clear volume). */
function absorptionOf(color: Vec3, distance: number): Vec3 {
  if (!(distance > 0 && Number.isFinite(distance))) return [0, 0, 0];
  return color.map((c) => -Math.log(Math.max(c, 1e-6)) / distance) as unknown as Vec3;
}

export function packMaterials(scene: Scene, layouts: { material: StructLayout; textureRef: StructLayout }, maxTextureSide: number): PackedMaterials {
  const textures = scene.textures ?? [];
  const warnings: string[] = [];
  // Every texture is placed in the atlas of each encoding it is used with (usually one), with its
  // mip chain where it is filtered (mip-chain.ts), halved first if that would not fit on a page.
  const pageSide = Math.min(maxTextureSide, MAX_PAGE_SIDE);
  const placed = new Map<string, { slot: number; levels: number; width: number; height: number }>();
  const srgbTextures: Texture[] = [];
  const linearTextures: Texture[] = [];
  const place = (index: number, srgb: boolean, bilinear: boolean) => {
    const key = `${index}:${srgb}:${bilinear}`;
    let entry = placed.get(key);
    if (!entry) {
      const t = textures[index];
      if (!t) throw new LanternError(`scene '${scene.name}' refers to texture ${index} of ${textures.length}`);
      const encoded: Texture = { ...t, encoding: srgb ? 'srgb' : 'linear' };
      const fitted = bilinear ? fitForMips(encoded, pageSide) : fitNearest(encoded, pageSide);
      if (fitted.width !== t.width) warnings.push(`texture '${t.name}' (${t.width}×${t.height}) is drawn at ${fitted.width}×${fitted.height} to fit an atlas page${bilinear ? ' with its mip levels' : ''}`);
      const stored = bilinear ? withMipChain(fitted) : fitted;
      const slot = (srgb ? srgbTextures : linearTextures).push(stored) - 1;
      entry = { slot, levels: bilinear ? mipLevelCount(fitted.width, fitted.height) : 1, width: fitted.width, height: fitted.height };
      placed.set(key, entry);
    }
    return entry;
  };

  const refs: { ref: TextureRef; srgb: boolean; placement: ReturnType<typeof place>; bilinear: boolean }[] = [];
  const refIndex = new Map<string, number>();
  const addRef = (ref: TextureRef, srgb: boolean, shared: boolean): number => {
    const bilinear = (textures[ref.texture]?.filter ?? 'bilinear') === 'bilinear';
    const placement = place(ref.texture, srgb, bilinear);
    const key = `${srgb}:${placement.slot}:${bilinear}:${ref.texCoord ?? 0}:${JSON.stringify(ref.transform ?? null)}`;
    if (!shared) return refs.push({ ref, srgb, placement, bilinear }) - 1;
    let index = refIndex.get(key);
    if (index === undefined) {
      index = refs.push({ ref, srgb, placement, bilinear }) - 1;
      refIndex.set(key, index);
    }
    return index;
  };
  // Animated materials (world/material-animation.ts) get texture references of their own, one per
  // texture each field can show, so a step of a cycle only rewrites the record's ref index and a
  // scroll rewrites only its own refs' transforms.
  const animatedTextures = animatedTextureSets(scene);
  const animatedRefs = new Map<number, Map<string, Map<number, number>>>();
  const materialRefs = scene.materials.map((m, i) => {
    const animated = animatedTextures.get(i);
    return textureUses(m).map((u) => {
      if (!animated) return { field: u.field, index: addRef(u.ref, u.srgb, true), texture: u.ref.texture, transform: transformKey(u.ref) };
      let fields = animatedRefs.get(i);
      if (!fields) animatedRefs.set(i, (fields = new Map()));
      const byTexture = new Map<number, number>();
      fields.set(u.field, byTexture);
      for (const k of new Set([u.ref.texture, ...(animated.get(u.field) ?? [])])) byTexture.set(k, addRef({ ...u.ref, texture: k }, u.srgb, false));
      return { field: u.field, index: byTexture.get(u.ref.texture)!, texture: u.ref.texture, transform: transformKey(u.ref) };
    });
  });

  const atlas = packTextureAtlas(srgbTextures, maxTextureSide);
  const linearAtlas = packTextureAtlas(linearTextures, maxTextureSide);
  const textureRefs = new StructArray(layouts.textureRef, refs.length);
  {
    const origin = textureRefs.vec2u('origin'), size = textureRefs.vec2u('size'), page = textureRefs.u32Field('page'), flags = textureRefs.u32Field('flags'), levels = textureRefs.u32Field('levels');
    const writeTransform = transformWriter(textureRefs);
    refs.forEach((r, i) => {
      const rect = (r.srgb ? atlas : linearAtlas).rects[r.placement.slot]!;
      origin(i, rect.x, rect.y);
      // The size of level 0; the rectangle holds the mip chain beside it.
      size(i, r.placement.width, r.placement.height);
      levels(i, r.placement.levels);
      page(i, rect.page);
      flags(i, (r.srgb ? 0 : TEXTURE_LINEAR) | (r.bilinear ? TEXTURE_BILINEAR : 0) | (r.ref.texCoord === 1 ? TEXTURE_UV1 : 0));
      writeTransform(i, r.ref);
    });
  }

  const textureMean = new Map<number, number>();
  const meanOf = (index: number) => {
    let v = textureMean.get(index);
    if (v === undefined) textureMean.set(index, (v = luminance(meanLinearColor(textures[index]!))));
    return v;
  };
  const emissionMean = scene.materials.map((m) => (m.emissionTexture === undefined ? 1 : meanOf(m.emissionTexture.texture)));

  const out = new StructArray(layouts.material, scene.materials.length);
  const writeRecord = materialRecordWriter(out);
  const textureFields = ['base_color_texture', 'emission_texture', 'metallic_roughness_texture', 'specular_texture', 'specular_color_texture', 'transmission_texture', 'normal_texture'];
  const textureWriters = new Map(textureFields.map((f) => [f, out.u32Field(f)]));
  const mean = out.f32Field('emission_texture_mean');
  const hasHitFilter: boolean[] = [];
  let general = false;

  scene.materials.forEach((m, i) => {
    for (const w of textureWriters.values()) w(i, NO_TEXTURE);
    for (const { field, index } of materialRefs[i]!) textureWriters.get(field)!(i, index);
    mean(i, emissionMean[i]!);
    hasHitFilter.push(writeRecord(i, m));
    if (m.kind === 'metallic-roughness' || m.kind === 'dielectric' || m.normalTexture || (m.kind === 'diffuse' && m.scatterPlaneNormal)) general = true;
  });

  return {
    materials: out.bytes,
    textureRefs: textureRefs.bytes,
    atlas,
    linearAtlas,
    emissionMean,
    hasHitFilter,
    general: general || refs.some((r) => r.ref.texCoord === 1),
    needsVertexAttributes: scene.materials.some((m) => m.normalTexture !== undefined) || refs.some((r) => r.ref.texCoord === 1),
    textureRefCount: refs.length,
    textureUses: materialRefs.map((uses) => new Map(uses.map((u) => [u.field, { texture: u.texture, transform: u.transform }]))),
    animatedRefs,
    warnings: [...new Set(warnings)],
  };
}

/**
 * A writer of every field of the WGSL Material record that comes from the material alone: kind,
 * flags, coverage, emission and the kind's constant factors. Texture references and the emission
 * texture's mean are left as they are (they come from the atlases). Returns whether the material
 * filters hits (alpha mask or blend).
 */
function materialRecordWriter(out: StructArray): (i: number, m: Material) => boolean {
  const u32 = (f: string) => out.u32Field(f), f32 = (f: string) => out.f32Field(f), v3 = (f: string) => out.vec3(f);
  const kind = u32('kind'), flags = u32('flags'), cutoff = f32('alpha_cutoff'), opacity = f32('opacity');
  const base = v3('base_color'), emission = v3('emission');
  const metallic = f32('metallic'), roughness = f32('roughness'), ior = f32('ior'), transmission = f32('transmission'), specular = f32('specular');
  const specularColor = v3('specular_color'), absorption = v3('absorption'), normalScale = f32('normal_scale');
  const dispersionLaw = u32('dispersion_law'), dispersionScale = f32('dispersion_scale'), dispersionB = v3('dispersion_b'), dispersionC = v3('dispersion_c');
  const writeDispersion = (i: number, ior: number, d: Dispersion | undefined) => {
    if (!d) return;
    const p = packDispersion(ior, d);
    dispersionLaw(i, DISPERSION_LAWS.indexOf(p.law));
    dispersionScale(i, p.scale);
    dispersionB(i, ...p.b);
    dispersionC(i, ...p.c);
  };
  const scatterPlane = v3('scatter_plane_normal');
  const repeats = f32('panorama_repeats'), horizon = f32('panorama_horizon_v'), vPerRadian = f32('panorama_v_per_radian');
  return (i, m) => {
    kind(i, MATERIAL_KINDS.indexOf(m.kind));
    emission(i, ...m.emission);
    const coverage = coverageOf(m);
    opacity(i, coverage.opacity);
    cutoff(i, m.alphaCutoff ?? 0.5);
    normalScale(i, m.normalTexture?.scale ?? 1);
    let f = 0;
    const alpha = m.alphaMode ?? 'opaque';
    const filter = alpha !== 'opaque' && (coverage.texture !== undefined || coverage.opacity < 1);
    if (filter) f |= alpha === 'mask' ? MATERIAL_ALPHA_MASK : MATERIAL_ALPHA_BLEND;
    if (m.twoSidedEmission) f |= MATERIAL_TWO_SIDED_EMISSION;
    const mapping = m.emissionMapping;
    if (mapping?.kind === 'panorama') {
      f |= MATERIAL_EMISSION_PANORAMA;
      repeats(i, mapping.repeats);
      horizon(i, mapping.horizonV);
      vPerRadian(i, mapping.vPerRadian);
    }
    switch (m.kind) {
      case 'diffuse':
        base(i, ...m.albedo);
        if (m.scatterPlaneNormal) {
          f |= MATERIAL_SCATTER_IN_PLANE;
          scatterPlane(i, ...m.scatterPlaneNormal);
        }
        break;
      case 'metallic-roughness':
        base(i, ...m.baseColor);
        metallic(i, m.metallic);
        roughness(i, m.roughness);
        ior(i, m.ior);
        transmission(i, m.transmission);
        specular(i, m.specular);
        specularColor(i, ...m.specularColor);
        absorption(i, ...absorptionOf(m.attenuationColor, m.attenuationDistance));
        if (!(m.thickness > 0)) f |= MATERIAL_THIN_WALLED;
        // KHR_materials_dispersion acts on volumetric refraction only: without it there is nothing to disperse.
        if (m.thickness > 0 && m.transmission > 0) writeDispersion(i, m.ior, m.dispersion);
        break;
      case 'dielectric':
        base(i, ...m.tint);
        roughness(i, m.roughness);
        ior(i, m.ior);
        writeDispersion(i, m.ior, m.dispersion);
        transmission(i, 1);
        absorption(i, ...absorptionOf(m.attenuationColor, m.attenuationDistance));
        break;
      case 'emissive':
        break;
    }
    flags(i, f);
    return filter;
  };
}

/**
 * The materials packed again after edits (scene/material-edit.ts): the records of `changed` are
 * rewritten over a copy of the packed ones, so atlases and everything derived from textures are kept
 * as they are. Constant factors may change on any material; textures and uv offsets only on animated
 * materials (world/material-animation.ts), and only to textures their animation lists: those were
 * packed ahead with texture references of the material's own, so a texture swap rewrites the
 * record's reference index and a uv offset rewrites the material's own references' transforms (then
 * `textureRefs` is a new buffer: `texture_refs` must be written again). Kinds and coverage must be
 * those the materials were packed with. The emission texture means (the light table's powers) stay
 * those of the textures packed first.
 */
export function repackMaterialRecords(
  materials: readonly Material[],
  packed: PackedMaterials,
  layouts: { material: StructLayout; textureRef: StructLayout },
  changed: Iterable<number>,
): PackedMaterials {
  const out = new StructArray(layouts.material, materials.length);
  new Uint8Array(out.bytes).set(new Uint8Array(packed.materials));
  const writeRecord = materialRecordWriter(out);
  let refsOut: StructArray | undefined;
  const usesNow = [...packed.textureUses];
  for (const i of changed) {
    const m = materials[i];
    if (!m) throw new LanternError(`no material ${i} to repack (the scene has ${materials.length})`);
    if (writeRecord(i, m) !== packed.hasHitFilter[i]) throw new LanternError(`material '${m.name}' changed its coverage: prepare the scene again`);
    const before = packed.textureUses[i]!;
    const uses = textureUses(m);
    if (uses.length !== before.size || uses.some((u) => !before.has(u.field))) throw new LanternError(`material '${m.name}' changed which textures it uses: prepare the scene again`);
    const animated = packed.animatedRefs.get(i);
    for (const u of uses) {
      const was = before.get(u.field)!;
      if (!animated) {
        if (u.ref.texture !== was.texture || transformKey(u.ref) !== was.transform) {
          throw new LanternError(`material '${m.name}' changed the texture or uv transform of its ${u.field}, which only animated materials (world/material-animation.ts) may: prepare the scene again`);
        }
        continue;
      }
      const byTexture = animated.get(u.field)!;
      const ref = byTexture.get(u.ref.texture);
      if (ref === undefined) throw new LanternError(`material '${m.name}' shows texture ${u.ref.texture} in its ${u.field}, which its animation does not list (so it was not packed for it)`);
      out.u32Field(u.field)(i, ref);
      if (transformKey(u.ref) === was.transform) continue;
      if (!refsOut) {
        refsOut = new StructArray(layouts.textureRef, packed.textureRefCount);
        new Uint8Array(refsOut.bytes).set(new Uint8Array(packed.textureRefs));
      }
      const write = transformWriter(refsOut);
      for (const [texture, r] of byTexture) write(r, { ...u.ref, texture });
    }
    // What the record and the refs hold now, which the next repack compares against.
    if (animated) usesNow[i] = new Map(uses.map((u) => [u.field, { texture: u.ref.texture, transform: transformKey(u.ref) }]));
  }
  return { ...packed, materials: out.bytes, textureUses: usesNow, ...(refsOut ? { textureRefs: refsOut.bytes } : {}) };
}

/** A nearest-filtered texture halved (by dropping every other texel) until it fits a page. */
function fitNearest(t: Texture, side: number): Texture {
  let out = t;
  while (out.width > side || out.height > side) {
    const w = Math.max(1, out.width >> 1), h = Math.max(1, out.height >> 1);
    const rgba = new Uint8Array(w * h * 4);
    for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) rgba.set(out.rgba.subarray(((2 * y) * out.width + 2 * x) * 4, ((2 * y) * out.width + 2 * x) * 4 + 4), (y * w + x) * 4);
    out = { ...out, width: w, height: h, rgba };
  }
  return out;
}
