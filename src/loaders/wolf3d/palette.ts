/**
 * Wolfenstein 3D's colours. Neither is in the data files: the game compiles them into its
 * executable, so they are data tables here.
 *
 * - The game palette, GAMEPAL: 256 colours as the 6-bit values (0–63) the game writes to the VGA
 *   DAC. The values are those of the released source's palette (id Software's 1995 source release,
 *   OBJ/GAMEPAL.OBJ; as text in the source ports' `wolfpal.inc`, e.g. Wolf4SDL and Chocolate
 *   Wolfenstein 3D), also documented on the ModdingWiki's "Wolfenstein 3-D" palette pages.
 *   Colours 0–15 are the standard EGA colours; 0x19 is the floor's grey, 0x1D the usual ceiling's.
 * - The ceiling colour of each map, `vgaCeiling[]` in the released source's WL_DRAW.C (60 entries
 *   for Wolf3D's six episodes, indexed episode · 10 + map), and the floor colour 0x19 that
 *   VGAClearScreen in the same file draws under every map.
 *
 * Pure.
 */

/** GAMEPAL, 8 colours a line, each colour six hex digits: the 6-bit red, green and blue. */
const GAMEPAL_6BIT = [
  '000000 00002a 002a00 002a2a 2a0000 2a002a 2a1500 2a2a2a',
  '151515 15153f 153f15 153f3f 3f1515 3f153f 3f3f15 3f3f3f',
  '3b3b3b 373737 343434 303030 2d2d2d 2a2a2a 262626 232323',
  '1f1f1f 1c1c1c 191919 151515 121212 0e0e0e 0b0b0b 080808',
  '3f0000 3b0000 380000 350000 320000 2f0000 2c0000 290000',
  '260000 220000 1f0000 1c0000 190000 160000 130000 100000',
  '3f3636 3f2e2e 3f2727 3f1f1f 3f1717 3f1010 3f0808 3f0000',
  '3f2a17 3f2610 3f2208 3f1e00 391b00 331800 2d1500 271300',
  '3f3f36 3f3f2e 3f3f27 3f3f1f 3f3e17 3f3d10 3f3d08 3f3d00',
  '393600 333100 2d2b00 272700 212100 1c1b00 161500 101000',
  '343f17 313f10 2d3f08 283f00 243900 203300 1d2d00 182700',
  '363f36 2f3f2e 273f27 203f1f 183f17 103f10 083f08 003f00',
  '003f00 003b00 003800 003500 013200 012f00 012c00 012900',
  '012600 012200 011f00 011c00 011900 011600 011300 011000',
  '363f3f 2e3f3f 273f3f 1f3f3e 173f3f 103f3f 083f3f 003f3f',
  '003939 003333 002d2d 002727 002121 001c1c 001616 001010',
  '172f3f 102c3f 082a3f 00273f 002339 001f33 001b2d 001727',
  '36363f 2e2f3f 27273f 1f203f 17183f 10103f 08093f 00013f',
  '00003f 00003b 000038 000035 000032 00002f 00002c 000029',
  '000026 000022 00001f 00001c 000019 000016 000013 000010',
  '0a0a0a 3f380d 3f3509 3f3306 3f3002 3f2d00 2d083f 2a003f',
  '260039 200033 1d002d 180027 140021 11001c 0d0016 0a0010',
  '3f363f 3f2e3f 3f273f 3f1f3f 3f173f 3f103f 3f083f 3f003f',
  '380039 320033 2d002d 270027 210021 1b001c 160016 100010',
  '3f3a37 3f3834 3f3631 3f352f 3f332c 3f3129 3f2f27 3f2e24',
  '3f2c20 3f291c 3f2718 3c2517 3a2316 372215 342014 321f13',
  '2f1e12 2d1c11 2a1a10 28190f 27180e 24170d 22160c 20140b',
  '1d130a 1b1209 171008 150f07 120e06 100c06 0e0b05 0a0803',
  '180019 001919 001818 000007 00000b 0c0904 120012 140014',
  '00000d 070707 131313 171717 101010 0c0c0c 0d0d0d 363d3d',
  '2e3a3a 273737 1d3232 123030 082d2d 082c2c 002929 002626',
  '002323 002121 001f1f 001e1e 001d1d 001c1c 001b1b 260022',
];

/**
 * `vgaCeiling[]` of WL_DRAW.C (non-SPEAR build): the palette index of each map's ceiling. The game
 * stores each twice in a word (0x1d1d) to fill two pixels at once; one byte is the colour.
 */
const VGA_CEILING = [
  0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0xbf,
  0x4e, 0x4e, 0x4e, 0x1d, 0x8d, 0x4e, 0x1d, 0x2d, 0x1d, 0x8d,
  0x1d, 0x1d, 0x1d, 0x1d, 0x1d, 0x2d, 0xdd, 0x1d, 0x1d, 0x98,
  0x1d, 0x9d, 0x2d, 0xdd, 0xdd, 0x9d, 0x2d, 0x4d, 0x1d, 0xdd,
  0x7d, 0x1d, 0x2d, 0x2d, 0xdd, 0xd7, 0x1d, 0x1d, 0x1d, 0x2d,
  0x1d, 0x1d, 0x1d, 0x1d, 0xdd, 0xdd, 0x7d, 0xdd, 0xdd, 0xdd,
];

/** The floor's palette index under every map (VGAClearScreen in WL_DRAW.C). */
export const FLOOR_COLOUR_INDEX = 0x19;

/** The ceiling's palette index of map `mapIndex` (0-based, MAPHEAD's slot); maps past the table get the usual 0x1D. */
export function ceilingColourIndex(mapIndex: number): number {
  return VGA_CEILING[mapIndex] ?? 0x1d;
}

/** A 6-bit VGA DAC value as 8 bits: ×255/63, rounded (63 → 255, 0 → 0). */
export function vgaTo8Bit(value: number): number {
  return Math.round((value * 255) / 63);
}

/** The game palette: 768 bytes, 256 colours × 8-bit RGB (a new array each call). */
export function gamePalette(): Uint8Array {
  const out = new Uint8Array(768);
  let i = 0;
  for (const line of GAMEPAL_6BIT) {
    for (const colour of line.split(' ')) {
      for (let c = 0; c < 3; c++) out[i++] = vgaTo8Bit(parseInt(colour.slice(2 * c, 2 * c + 2), 16));
    }
  }
  return out;
}
