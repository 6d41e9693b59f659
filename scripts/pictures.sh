#!/usr/bin/env bash
# Remakes the pictures under docs/images from the bundled models and the stitch library (after scripts/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
skein=build/bin/skein
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=docs/images
"$skein" -q stitch models/sweater.obj --labels models/sweater.skein -o "$tmp/sweater.skein" --png "$out/sweater-rows.png"
"$skein" -q edit "$tmp/sweater.skein" --fill rib2x2 --near-border 12 -o "$tmp/sweater.skein" --png-types "$out/sweater-stitch-types.png"
"$skein" -q relax-mesh "$tmp/sweater.skein" -o "$tmp/relaxed.skein" --png-before "$out/sweater-stretch-before.png" \
    --png "$out/sweater-stretch-after.png"
"$skein" -q render "$tmp/relaxed.skein" --yarn -o "$out/sweater-yarn.png"
build/bin/skein-sampler "$tmp" >/dev/null
"$skein" -q render "$tmp/sampler.skein" --views flat --color type -o "$out/sampler-stitch-types.png"
"$skein" -q render "$tmp/sampler.skein" --yarn --views flat -o "$out/sampler-yarn.png"
"$skein" -q render "$tmp/cable.skein" --yarn --views flat -o "$out/cable-yarn.png"
"$skein" -q stitch models/swatch.obj --auto-label --stitch-size 40 --stitch-height 33.4 -o "$tmp/close.skein"
"$skein" -q render "$tmp/close.skein" --yarn --views flat -o "$out/swatch-close-up.png"
# Yarn relaxation: a close-up of a 2 x 2 rib swatch, emitted and relaxed with 85% of its yarn length; the
# mitten relaxed (at most five minutes).
"$skein" -q stitch models/swatch.obj --auto-label --stitch-size 20 --stitch-height 16.7 -o "$tmp/rib.skein"
"$skein" -q edit "$tmp/rib.skein" --fill rib2x2 -o "$tmp/rib.skein"
"$skein" -q render "$tmp/rib.skein" --yarn --views flat -o "$out/swatch-rib-emitted.png"
"$skein" -q relax-yarn "$tmp/rib.skein" -o "$tmp/rib.bcc" --take-up 0.85 --png "$out/swatch-rib-relaxed.png" --views flat
# A periodic stand-in (a preview, not a relaxation) of a 2 x 2 rib swatch of 256 stitches, and its relaxation.
"$skein" -q stitch models/swatch.obj --auto-label --stitch-size 8 --stitch-height 6.7 -o "$tmp/rib8.skein"
"$skein" -q edit "$tmp/rib8.skein" --fill rib2x2 -o "$tmp/rib8.skein"
"$skein" -q relax-yarn "$tmp/rib8.skein" --stand-in -o "$tmp/rib8-preview.bcc" --png "$out/swatch-rib-stand-in.png" --views flat
"$skein" -q relax-yarn "$tmp/rib8.skein" -o "$tmp/rib8.bcc" --no-audit --png "$out/swatch-rib-stand-in-relaxed.png" --views flat
# The same for a four-stitch cable tiled over the swatch (8 whole repeats): the stand-in named the pattern.
"$skein" -q stitch models/swatch.obj --auto-label --stitch-size 8 --stitch-height 6.7 -o "$tmp/cable8.skein"
"$skein" -q pattern patterns/cable-4.knit --onto "$tmp/cable8.skein" -o "$tmp/cable8.skein"
"$skein" -q relax-yarn "$tmp/cable8.skein" --stand-in --stand-in-pattern patterns/cable-4.knit -o "$tmp/cable8-preview.bcc" \
  --png "$out/swatch-cable-stand-in.png" --views flat
"$skein" -q relax-yarn "$tmp/cable8.skein" -o "$tmp/cable8.bcc" --no-audit --png "$out/swatch-cable-stand-in-relaxed.png" --views flat
"$skein" -q stitch models/mitten.obj --labels models/mitten.skein -o "$tmp/mitten.skein"
"$skein" -q relax-yarn "$tmp/mitten.skein" -o "$tmp/mitten.bcc" --no-audit --max-seconds 300 --png "$out/mitten-yarn-relaxed.png" --views flat
echo "wrote $(ls $out | tr '\n' ' ')"
