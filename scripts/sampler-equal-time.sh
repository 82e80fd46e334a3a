#!/usr/bin/env bash
# The sampler at equal GPU time (issue #27, docs/perf.md "The sampler at equal time"): for each scene,
# the GPU time per sample of Sobol and of PCG (`lantern bench`, 512 × 512, 8 bounces, clocks warmed),
# and the relMSE of each against a PCG reference of many samples and another seed (`render --exr`,
# `lantern diff`) at 16, 64 and 256 spp. Prints per scene and spp the efficiency ratio
#     (relMSE_pcg · t_pcg) / (relMSE_sobol · t_sobol)
# (> 1: Sobol gives less error in the same GPU time). Needs only the CLI bundle, as on the GPU machine:
#     scripts/sampler-equal-time.sh [dist/cli/lantern.mjs] [freedoom1.wad] [out folder]
set -euo pipefail
cli=${1:-dist/cli/lantern.mjs}
wad=${2:-/usr/share/games/doom/freedoom1.wad}
out=${3:-out/sampler-equal-time}
size=${SIZE:-512}
mkdir -p "$out"
lantern() { node "$cli" "$@"; }
scene_arg() { if [ "$1" = E1M1 ]; then echo "$wad#E1M1"; else echo "$1"; fi; }
for entry in cornell:16384 materials:8192 E1M1:4096 rtiow:8192; do
  name=${entry%%:*} refspp=${entry##*:}
  [ "$name" = E1M1 ] && [ ! -f "$wad" ] && { echo "$name: skipped (no $wad)"; continue; }
  arg=$(scene_arg "$name")
  for sampler in sobol random; do
    lantern bench "$arg" -W "$size" -H "$size" --sampler "$sampler" --json > "$out/bench-$name-$sampler.json"
  done
  lantern render "$arg" -W "$size" -H "$size" -s "$refspp" --sampler random --seed 9001 --exr "$out/ref-$name.exr" > /dev/null
  for spp in 16 64 256; do
    for sampler in sobol random; do
      lantern render "$arg" -W "$size" -H "$size" -s "$spp" --sampler "$sampler" --seed 1 --exr "$out/$name-$sampler-$spp.exr" > /dev/null
      lantern diff "$out/$name-$sampler-$spp.exr" "$out/ref-$name.exr" --json > "$out/diff-$name-$sampler-$spp.json"
    done
  done
  node --input-type=module -e '
    import { readFileSync } from "node:fs";
    const [out, name] = process.argv.slice(1);
    const read = (f) => JSON.parse(readFileSync(`${out}/${f}`, "utf8"));
    const t = (s) => read(`bench-${name}-${s}.json`).pathTracing.msPerSample;
    for (const spp of [16, 64, 256]) {
      const e = (s) => read(`diff-${name}-${s}-${spp}.json`).relMse;
      console.log(`${name} ${spp} spp: relMSE sobol ${e("sobol").toPrecision(4)} pcg ${e("random").toPrecision(4)}; ms/spp sobol ${t("sobol").toFixed(4)} pcg ${t("random").toFixed(4)}; efficiency sobol/pcg ${((e("random") * t("random")) / (e("sobol") * t("sobol"))).toFixed(3)}`);
    }' "$out" "$name"
done
