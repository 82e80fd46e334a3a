/** OpenEXR reading and writing; see exr-format.ts for the file layout. */
export { encodeExr, type ExrEncodeOptions } from './exr-encode.ts';
export { decodeExr, decodeExrRgb, exrToRgb, type ExrImage } from './exr-decode.ts';
