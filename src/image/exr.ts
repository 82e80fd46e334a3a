/** OpenEXR reading and writing; see exr-format.ts for the file layout. */
export { encodeExr, encodeExrAsync, type ChunkDeflate, type ExrEncodeOptions } from './exr-encode.ts';
export { decodeExr, decodeExrRgb, exrToRgb, type ExrImage } from './exr-decode.ts';
