import { describe, expect, it } from 'vitest';
import type { Texture } from '../../scene/types.ts';
import { LanternError } from '../../errors.ts';
import { DEFAULT_LIGHT_TABLE, FIRE_GLOW, FIRE_THING_STRENGTH, glowTexture, LAMP_GLOW, LAMP_STRENGTH, mergeLightTables, parseLightTable } from './light-table.ts';

describe('glowTexture', () => {
  it('keeps texels at least the threshold of the brightest luminance and blackens the rest', () => {
    // Linear luminances: 255 -> 1, 188 -> ~0.5, 128 -> ~0.216, 0 -> 0; a transparent white texel is ignored for the maximum.
    const rgba = new Uint8Array([255, 255, 255, 255, 188, 188, 188, 255, 128, 128, 128, 255, 0, 0, 0, 255]);
    const t: Texture = { name: 'LAMP', width: 4, height: 1, rgba };
    const glow = glowTexture(t, 0.4);
    expect([...glow.rgba]).toEqual([255, 255, 255, 255, 188, 188, 188, 255, 0, 0, 0, 255, 0, 0, 0, 255]);
    expect(glow.name).toBe('LAMP@glow');
    expect(t.rgba[8]).toBe(128);
  });

  it('measures the brightest texel among opaque ones only', () => {
    const rgba = new Uint8Array([255, 255, 255, 0, 128, 128, 128, 255]);
    const glow = glowTexture({ name: 'M', width: 2, height: 1, rgba }, 0.9);
    expect([...glow.rgba.subarray(4)]).toEqual([128, 128, 128, 255]);
  });
});

describe('parseLightTable', () => {
  it('accepts overrides and upper-cases names', () => {
    expect(parseLightTable({ textures: { lite3: { strength: 0 } }, flats: { NUKAGE1: { strength: 2, color: [0, 1, 0], glow: 0.5 } } })).toEqual({
      textures: { LITE3: { strength: 0 } },
      flats: { NUKAGE1: { strength: 2, color: [0, 1, 0], glow: 0.5 } },
    });
  });

  it('accepts things by sprite name', () => {
    expect(parseLightTable({ things: { colu: { strength: 0 }, TRED: { strength: 4, glow: 0.3 } } })).toEqual({ things: { COLU: { strength: 0 }, TRED: { strength: 4, glow: 0.3 } } });
  });

  it('lists the light-giving things by sprite in the default table, lamps as lamps and flames as flames', () => {
    expect(DEFAULT_LIGHT_TABLE.things['COLU']).toEqual({ strength: LAMP_STRENGTH, glow: LAMP_GLOW });
    expect(DEFAULT_LIGHT_TABLE.things['CBRA']).toEqual({ strength: FIRE_THING_STRENGTH, glow: FIRE_GLOW });
    expect(DEFAULT_LIGHT_TABLE.things['TROO']).toBeUndefined();
    expect(mergeLightTables(DEFAULT_LIGHT_TABLE, { things: { cbra: { strength: 0 } } }).things['CBRA']).toEqual({ strength: 0 });
  });

  it.each([
    [[], /not a JSON object/],
    [{ walls: {} }, /unknown key 'walls'/],
    [{ textures: { LITE3: { strength: -1 } } }, /textures\.LITE3\.strength/],
    [{ flats: { X: { strength: 1, color: [1, 2] } } }, /flats\.X\.color/],
    [{ flats: { X: { strength: 1, glow: 2 } } }, /flats\.X\.glow/],
  ])('refuses %j, naming the entry', (json, message) => {
    expect(() => parseLightTable(json, 'my.json')).toThrow(LanternError);
    expect(() => parseLightTable(json, 'my.json')).toThrow(message);
  });
});
