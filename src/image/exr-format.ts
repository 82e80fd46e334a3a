/**
 * Constants of the OpenEXR 2.0 file layout shared by the encoder and decoder. A single-part scanline
 * file is: magic, version field, header (attributes until an empty name), line offset table (one
 * uint64 per chunk), then chunks of `int32 y, int32 byte count, pixel data`. Everything is
 * little-endian; within a chunk, each scanline holds every channel's samples for that line, channels
 * in the header's (alphabetical) order.
 */

/** 20000630 as a little-endian int32. */
export const EXR_MAGIC = 20000630;
/** Low byte of the version field; the flag bits above it mark tiled, long-name, deep and multi-part files. */
export const EXR_VERSION = 2;
export const FLAG_TILED = 0x200;
export const FLAG_LONG_NAMES = 0x400;
export const FLAG_DEEP = 0x800;
export const FLAG_MULTIPART = 0x1000;

export const PIXEL_UINT = 0;
export const PIXEL_HALF = 1;
export const PIXEL_FLOAT = 2;
export const PIXEL_SIZE: readonly number[] = [4, 2, 4];

export const COMPRESSION_NONE = 0;
export const COMPRESSION_RLE = 1;
export const COMPRESSION_ZIPS = 2;
export const COMPRESSION_ZIP = 3;

/** Names and scanlines per chunk of every compression in the OpenEXR 2 spec, by code. */
export const COMPRESSIONS: readonly { name: string; linesPerChunk: number }[] = [
  { name: 'NO_COMPRESSION', linesPerChunk: 1 },
  { name: 'RLE', linesPerChunk: 1 },
  { name: 'ZIPS', linesPerChunk: 1 },
  { name: 'ZIP', linesPerChunk: 16 },
  { name: 'PIZ', linesPerChunk: 32 },
  { name: 'PXR24', linesPerChunk: 16 },
  { name: 'B44', linesPerChunk: 32 },
  { name: 'B44A', linesPerChunk: 32 },
  { name: 'DWAA', linesPerChunk: 32 },
  { name: 'DWAB', linesPerChunk: 256 },
];

export const compressionName = (code: number): string => COMPRESSIONS[code]?.name ?? `unknown compression ${code}`;
