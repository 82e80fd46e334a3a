/** The parts of draco3dgltf (Google's Emscripten build of the Draco glTF codec) Lantern uses. */
interface DracoModuleOptions {
  /** The module's .wasm; given, the module never reads or fetches it. */
  wasmBinary?: Uint8Array;
}

declare module 'draco3dgltf' {
  export function createDecoderModule(options?: DracoModuleOptions): Promise<unknown>;
  export function createEncoderModule(options?: DracoModuleOptions): Promise<unknown>;
}

/** The decoder alone (the package's main file also pulls in the encoder). */
declare module 'draco3dgltf/draco_decoder_gltf_nodejs.js' {
  const createDecoderModule: (options?: DracoModuleOptions) => Promise<unknown>;
  export default createDecoderModule;
}
