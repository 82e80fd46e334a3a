/**
 * The KHR_draco_mesh_compression decoder (draco3dgltf: Google's Emscripten build), made only when a
 * file uses the extension. Its .wasm comes in through Vite's `?url&inline` import as a data URL decoded
 * here, so neither Node nor a Web Worker reads or fetches a file for it (the loader never fetches);
 * the dynamic imports keep its ~250 kB out of bundles until a Draco file is opened.
 */
import { decodeDataUri } from './data-uri.ts';

let decoder: Promise<unknown> | undefined;

export function dracoDecoder(): Promise<unknown> {
  decoder ??= (async () => {
    // The decoder's own file: the package's main file would bring the encoder along.
    const [{ default: createDecoderModule }, wasm] = await Promise.all([
      import('draco3dgltf/draco_decoder_gltf_nodejs.js'),
      import('draco3dgltf/draco_decoder_gltf.wasm?url&inline'),
    ]);
    const wasmBinary = decodeDataUri(wasm.default);
    if (!wasmBinary) throw new Error('the bundled Draco decoder is damaged');
    return createDecoderModule({ wasmBinary });
  })();
  return decoder;
}
