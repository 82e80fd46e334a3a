// wgsl_reflect's "main" is a CommonJS file inside a "type": "module" package, which Node refuses;
// Lantern imports its ES module build directly, with the package's own types.
declare module 'wgsl_reflect/wgsl_reflect.module.js' {
  export * from 'wgsl_reflect';
}
