#!/usr/bin/env bash
# Every recipe's images from two builds of the CLI, compared byte for byte, PNGs by their pixels where
# their bytes differ (issue #28: a refactor of
# the frame must leave every estimator's images as they were). Renders the same small cases with
# each bundle, the same seeds and settings, and reports each output as identical or not:
#   progressive (RGB and spectral, PNG and EXR), real-time frames (raw; temporal + à-trous with the
#   megakernel, the wavefront and ReSTIR), the hybrid recipe, and every debug view; and on Doom's
#   E1M1 (textures, torch, automatic exposure) progressive and real-time, where freedoom1.wad is.
#     scripts/compare-recipes.sh OLD/lantern.mjs NEW/lantern.mjs [out folder] [freedoom1.wad]
# Exits 1 if any output differs. Bit-exact equality holds on one machine and driver (the GPU's
# compiler decides float contraction): run both bundles where they are compared. Progressive cases
# take 2 samples: the dispatch planner batches more by timing, and a batch's float sums differ in
# their last bits from another batching's (tests/gpu/determinism.test.ts), while 2 are always 1 + 1.
set -euo pipefail
old=${1:?the old bundle}
new=${2:?the new bundle}
out=${3:-out/compare-recipes}
wad=${4:-/usr/share/games/doom/freedoom1.wad}
size=(-W "${W:-32}" -H "${H:-24}")
rm -rf "$out"
mkdir -p "$out/old" "$out/new"
differ=0 same=0

# same_pixels A.png B.png: whether two PNGs decode to the same size and pixels (a build may compress
# them differently: frames are written through Node's zlib since issue #31's frame writer).
same_pixels() {
  node --input-type=module -e "
    import { decode } from 'fast-png'; import { readFileSync } from 'node:fs';
    const [a, b] = [process.argv[1], process.argv[2]].map((f) => decode(readFileSync(f)));
    process.exit(a.width === b.width && a.height === b.height && Buffer.from(a.data.buffer, a.data.byteOffset, a.data.byteLength).equals(Buffer.from(b.data.buffer, b.data.byteOffset, b.data.byteLength)) ? 0 : 1);
  " "$1" "$2"
}

# case NAME ARGS...: renders with both bundles, outputs under old/NAME* and new/NAME*.
run_case() {
  local name=$1; shift
  for build in old new; do
    local cli=$old; [ "$build" = new ] && cli=$new
    local args=("$@")
    args=("${args[@]//@OUT@/$out/$build/$name}")
    if ! node "$cli" render "${args[@]}" "${size[@]}" > "$out/$build/$name.log" 2>&1; then
      echo "$name: $build build failed: $(tail -1 "$out/$build/$name.log")"
      differ=$((differ + 1))
      return
    fi
  done
  local files
  files=$(cd "$out/old" && find . -path "./$name*" -type f \( -name '*.exr' -o -name '*.png' \) | sort)
  [ -n "$files" ] || { echo "$name: no output"; differ=$((differ + 1)); return; }
  for f in $files; do
    if cmp -s "$out/old/$f" "$out/new/$f"; then same=$((same + 1));
    elif [[ $f == *.png ]] && same_pixels "$out/old/$f" "$out/new/$f"; then echo "$name: ${f#./} has the same pixels (compressed differently)"; same=$((same + 1));
    else echo "$name: ${f#./} differs"; differ=$((differ + 1)); fi
  done
  echo "$name: $(echo "$files" | wc -l) file(s) compared"
}

run_case progressive cornell --spp 2 --seed 3 --exr @OUT@.exr --out @OUT@.png
run_case progressive-spectral prism --spp 2 --spectral --exr @OUT@.exr
run_case progressive-materials materials --spp 2 --exr @OUT@.exr
run_case raw-frames cornell --frames 3 --exr @OUT@-exr --out @OUT@-png
run_case real-time cornell --temporal --denoise --frames 3 --exr @OUT@-exr --out @OUT@-png
run_case real-time-wavefront cornell --temporal --denoise --integrator wavefront --frames 3 --exr @OUT@-exr
run_case real-time-restir cornell --temporal --denoise --restir --frames 3 --exr @OUT@-exr
run_case real-time-spectral cornell --temporal --denoise --spectral --frames 2 --exr @OUT@-exr
run_case hybrid cornell --mode hybrid --frames 3 --exr @OUT@-exr --out @OUT@-png
for view in heat-nodes heat-triangles wireframe leaf-size bvh-depth normals albedo barycentrics triangle-id; do
  run_case "debug-$view" cornell --debug "$view" --exr @OUT@.exr --out @OUT@.png
done
run_case debug-side-by-side cornell --spp 2 --debug heat-nodes --debug-layout side-by-side --out @OUT@.png
if [ -f "$wad" ]; then
  run_case doom-progressive "$wad#E1M1" --spp 2 --exr @OUT@.exr --out @OUT@.png
  run_case doom-real-time "$wad#E1M1" --temporal --denoise --frames 2 --exr @OUT@-exr --out @OUT@-png
else
  echo "doom: skipped (no $wad)"
fi
echo "identical: $same; different or failed: $differ"
[ "$differ" -eq 0 ]
