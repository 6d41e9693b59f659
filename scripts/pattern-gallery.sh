#!/usr/bin/env bash
# The gallery of bundled patterns (docs/pattern-gallery.md): every pattern's periodic patch relaxed, tiled to
# about 12 x 12 stitches (--preview-png) and drawn from the front into docs/images/patterns/; then the corpus in
# designers' notation (patterns/written, charts, wif) the same way into docs/images/corpus/; then the fabrics
# issue 24 asks to see side by side relaxed by today's defaults and drawn front, back and three-quarter
# (--views three) into docs/images/fabrics/, and again under tension (--take-up 0.8, the width free by bracketing). Run after
# scripts/build.sh; about twenty minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
skein=build/bin/skein
images=docs/images/patterns
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$images"
page=docs/pattern-gallery.md
{
  echo "# Pattern gallery"
  echo
  echo "Every bundled pattern (\`patterns/\`), its periodic patch relaxed with \`skein pattern FILE --relax --method fire --stop-rule leaf\`"
  echo "(the defaults before L-BFGS under the force rule: quicker, and short of the minimum; docs/BENCHMARKS.md), then tiled to"
  echo "about 12 x 12 stitches or yarns (\`--tile NxM --preview-png\`: the relaxed repeat placed over the tiling's yarn; the"
  echo "cast-on, bind-off and side turns only follow it) and drawn from the front. Made by \`scripts/pattern-gallery.sh\`."
  echo
  echo "| pattern | repeat | steps | picture |"
  echo "| --- | --- | --- | --- |"
} >"$page"
# picture FILE FOLDER [PREFIX]: the file's periodic patch relaxed, tiled to about 12 x 12 and drawn into FOLDER as
# PREFIX + its name (.png), and its table row.
picture() {
  local f=$1 folder=$2 name tile
  name=$(basename "$f"); name=${3:-}${name%.*}
  "$skein" -q pattern "$f" -o "$tmp/out.bcc" --tile 1x1 --report "$tmp/size.json"
  if python3 -c "import json, sys; sys.exit(0 if json.load(open('$tmp/size.json')).get('shaped_piece') else 1)"; then
    # A shaped piece is knitted once: relaxed whole with its free borders.
    "$skein" -q pattern "$f" -o "$tmp/out.bcc" --relax --tiled --method fire --stop-rule leaf --no-audit --report "$tmp/r.json" \
      --png "docs/$folder/$name.png" --views front --png-size 360
  else
    tile=$(python3 -c "import json, math; w, h = json.load(open('$tmp/size.json'))['repeat']; print(f'{math.ceil(12 / w)}x{math.ceil(12 / h)}')")
    "$skein" -q pattern "$f" -o "$tmp/out.bcc" --relax --method fire --stop-rule leaf --no-audit --report "$tmp/r.json" --tile "$tile" \
      --preview-png "docs/$folder/$name.png" --views front --png-size 360
  fi
  python3 - "$f" "$tmp/r.json" "$name" "$folder" >>"$page" <<'PY'
import json, sys
f, report, name, folder = sys.argv[1:]
r = json.load(open(report))
comments = [l[1:].strip() for l in open(f) if l.startswith(("#", ";"))]
# A WIF draft has no "# name:" or "# source:": its title is the pattern's name, its leading comment the source.
title = next((l.split(":", 1)[1].strip() for l in comments if l.startswith("name:")), r["pattern"])
source = next((l.split(":", 1)[1].strip() for l in comments if l.startswith("source:")), " ".join(comments) if f.endswith(".wif") else "")
points = r['periodic']['real_points'] if 'periodic' in r else r['yarn']['control_points']  # a shaped piece: all of its yarn
print(f"| **{title}** (`{f}`): {source} | {points} control points | {r['steps']} | ![{title}]({folder}/{name}.png) |")
PY
}
for f in patterns/*.knit patterns/*.weave; do picture "$f" images/patterns; done
{
  echo
  echo "## Patterns as designers write them (issue 26)"
  echo
  echo "The corpus of written instructions, charts and WIF drafts (\`patterns/written/\`, \`patterns/charts/\`,"
  echo "\`patterns/wif/\`; patterns/FORMAT.md), each read by skein, relaxed and drawn as above."
  echo
  echo "| pattern | repeat | steps | picture |"
  echo "| --- | --- | --- | --- |"
} >>"$page"
mkdir -p docs/images/corpus
for f in patterns/written/*.txt patterns/charts/*.txt patterns/wif/*.wif; do
  picture "$f" images/corpus "$(basename "$(dirname "$f")")-"  # written-seed, charts-seed: one name each
done
{
  echo
  echo "## Front, back and three-quarter (issue 24)"
  echo
  echo "The fabrics issue 24 asks to see side by side, relaxed by \`skein pattern --relax\`'s defaults (L-BFGS, the force"
  echo "stop rule), tiled 4 x 4 and drawn front, back and three-quarter from above (\`--views three\`). What they show"
  echo "against real fabric (no rib pulls in, the cable's crossing lies flat, the eyelet's yarn-over tangles over its"
  echo "hole) is measured in docs/BENCHMARKS.md, \"Relaxed fabric against real fabric\"."
  echo
  echo "| pattern | stopped | steps | picture |"
  echo "| --- | --- | --- | --- |"
} >>"$page"
mkdir -p docs/images/fabrics
for name in stockinette garter rib-1x1 rib-2x2 seed cable-4 eyelet-lace honeycomb; do
  "$skein" -q pattern "patterns/$name.knit" --relax --tile 4x4 --preview-png "docs/images/fabrics/$name.png" --views three --png-size 450 \
    -o "$tmp/out.bcc" --report "$tmp/r.json"
  python3 -c "import json; r = json.load(open('$tmp/r.json')); print(f\"| \`$name\` | {r['stopped_by']} | {r['steps']} | ![$name, front, back and three-quarter](images/fabrics/$name.png) |\")" >>"$page"
done
{
  echo
  echo "## Under tension (issue 24)"
  echo
  echo "Fabrics, lace, a rope cable and feather and fan (written and charted where the corpus has them) with the yarn 20 %"
  echo "shorter than emitted and the width free, found by bracketing (\`skein pattern FILE --relax --free-period x"
  echo "--period-method bracket --take-up 0.8 --max-steps 40000 -o OUT.bcc\`), tiled and drawn front, back and three-quarter"
  echo "as above; feather and fan is one repeat wide, so its whole strip arches."
  echo "Under tension stockinette, garter and seed find their widths (seed nearly as wide as stockinette), the ribs close"
  echo "their knit wales over the purl ones, the yarn-overs open, the fan's rows"
  echo "arch and the cable's strands lean"
  echo "(docs/BENCHMARKS.md, \"The free width by bracketing\" and \"Structures under tension\"); the rope cable, the lace rib and"
  echo "feather and fan stop at the step cap (the lace rib's stress within a few thousandths of B/r³ of zero over a wide range of widths)."
  echo
  echo "| pattern | stopped | steps | repeat's width | a wale | picture |"
  echo "| --- | --- | --- | --- | --- | --- |"
} >>"$page"
for spec in stockinette.knit:4x4 garter.knit:4x4 rib-1x1.knit:6x4 rib-2x2.knit:3x4 seed.knit:3x4 written/rope-cable.txt:2x3 \
  written/eyelet-rows.txt:3x3 charts/lace-rib.txt:3x6 written/feather-and-fan.txt:1x3 honeycomb.knit:3x3; do
  f=patterns/${spec%:*} name=$(basename "${f%.*}")
  "$skein" -q pattern "$f" --relax --free-period x --period-method bracket --take-up 0.8 --max-steps 40000 --tile "${spec#*:}" \
    --preview-png "docs/images/fabrics/$name-tension.png" \
    --views three --png-size 450 -o "$tmp/out.bcc" --report "$tmp/r.json"
  python3 -c "import json; r = json.load(open('$tmp/r.json')); print(f\"| \`$f\` | {r['stopped_by']} | {r['steps']} | {r['free_period']['repeat_mm'][0]:.1f} mm | {r['free_period']['repeat_mm'][0] / r['periodic']['repeat'][0]:.2f} mm | ![$name under tension, front, back and three-quarter](images/fabrics/$name-tension.png) |\")" >>"$page"
done
echo "wrote $page, $images/ and docs/images/fabrics/"
