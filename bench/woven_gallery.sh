#!/usr/bin/env bash
# The woven pictures of docs/woven.md (issue 29): the bundled exemplar set made once, then designs synthesized and
# rendered whole and close up, the ablations of Zhao 2012 Figs. 4 and 9 (no randomization, no edge fixing), and
# the 2/1 twill synthesized beside the same twill relaxed directly.
# Usage: bench/woven_gallery.sh [FOLDER]   (default docs/images/woven; about 10 minutes on 2 cores)
source "$(dirname "$0")/common.sh"
out=${1:-docs/images/woven}
mkdir -p "$out" "$tmp/ex"
"$skein" -q weave-exemplar patterns/{plain-weave,twill-3-2,twill-4-1,satin-5-2,basket-2x2}.weave -o "$tmp/ex"
volume() { "$skein" -q weave-volume --exemplars "$tmp/ex" "$@"; }
whole="--width 480 --height 320 --samples 8"
close="--width 400 --height 300 --samples 12 --field 6 --tilt 20"
volume patterns/plain-weave.weave --size 24x16 --png "$out/plain.png" $whole
volume patterns/plain-weave.weave --png "$out/plain-close.png" $close
volume patterns/wif/twill-2-2.wif --size 24x16 --png "$out/twill-2-2.png" $whole --warp-colors "#1d2f6f" --weft-colors "#c8c8c0"
volume patterns/wif/twill-2-2.wif --png "$out/twill-2-2-close.png" $close --warp-colors "#1d2f6f" --weft-colors "#c8c8c0"
volume patterns/woven/herringbone.weave --size 32x20 --png "$out/herringbone.png" $whole --warp-colors "#303030" --weft-colors "#b0a890"
volume patterns/satin-5-2.weave --size 24x16 --png "$out/satin.png" $whole --warp-colors "#602020" --weft-colors "#e8d8a0"
volume patterns/satin-5-2.weave --png "$out/satin-close.png" $close --warp-colors "#602020" --weft-colors "#e8d8a0"
volume --picture patterns/woven/jacquard.png --weaves patterns/wif/twill-2-2.wif,patterns/satin-5-2.weave,patterns/woven/satin-5-2-warp.weave \
  --png "$out/jacquard.png" $whole --warp-colors "#8a1c1c" --weft-colors "#e0c060"
volume --picture patterns/woven/jacquard.png --weaves patterns/wif/twill-2-2.wif,patterns/satin-5-2.weave,patterns/woven/satin-5-2-warp.weave \
  --png "$out/jacquard-close.png" $close --warp-colors "#8a1c1c" --weft-colors "#e0c060"
# Ablations (Zhao Fig. 4 and 9): the herringbone close up as the dynamic program leaves it, randomized, and edge-fixed.
volume patterns/woven/herringbone.weave --size 32x20 --no-randomize --edge-rank 0 --png "$out/herringbone-plain-dp.png" $close
volume patterns/woven/herringbone.weave --size 32x20 --edge-rank 0 --png "$out/herringbone-randomized.png" $close
volume patterns/woven/herringbone.weave --size 32x20 --png "$out/herringbone-fixed.png" $close
# Synthesis against truth: the 2/1 twill (in no exemplar) synthesized (left) and relaxed as one patch (right).
volume patterns/twill-2-1.weave --size 16x16 --compare-truth --png "$tmp/truth.png" --width 320 --height 320 --samples 8 --tilt 0
cp "$tmp/truth-truth.png" "$out/twill-2-1-against-truth.png"
ls "$out"
