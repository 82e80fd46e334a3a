// Named constants shared by every module: sentinels instead of bare magic numbers, and π.
// Expects nothing. WGSL lets implementations assume no infinities or NaNs at run time, so "no hit"
// is a large finite distance, never inf.

const PI: f32 = 3.14159265358979;
const INV_PI: f32 = 0.318309886183791;

// A distance beyond anything in a scene: "no hit yet" and "box missed".
const T_MISS: f32 = 3.0e38;
// Triangle index meaning "the ray hit nothing".
const NO_TRIANGLE: u32 = 0xffffffffu;
// Texture index meaning "no texture".
const NO_TEXTURE: u32 = 0xffffffffu;
