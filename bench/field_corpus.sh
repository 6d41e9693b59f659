#!/usr/bin/env bash
# Stitch meshes traced from the knitting field on surfaces nobody labeled (issue 25, part 1; docs/BENCHMARKS.md
# "Any surface in"). The corpus is generated (bench/field_meshes.py): triangle meshes, a pole of valence 8, closed
# surfaces and the bundled garments fanned into triangles. Each mesh: `skein stitch --field` (from its lowest
# border, or from a point on a closed one), `skein relax-mesh` on the traced rows' limit surface, `skein yarn`.
# Prints a markdown table; a refusal prints its reason. About a minute on 2 cores.
# Usage: bench/field_corpus.sh [PNG_FOLDER]   (pictures of each stitch mesh and its yarn when given)
source "$(dirname "$0")/common.sh"
pictures=${1:-}
python3 bench/field_meshes.py "$tmp/corpus"
now() { date +%s.%N; }
echo "| mesh | faces in | start | stitch faces | rows | increases | decreases | trace [s] | relax-mesh [s] | yarn control points | result |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for obj in "$tmp"/corpus/*.obj; do
  name=$(basename "$obj" .obj)
  faces=$(grep -c '^f ' "$obj")
  start=() start_text="lowest border"
  case $name in
    sphere) start=(--start-point 0,60,0) start_text="point (0, 60, 0)" ;;
    torus) start=(--start-point 80,0,0) start_text="point (80, 0, 0)" ;;
  esac
  png=()
  [ -n "$pictures" ] && png=(--png "$pictures/$name-rows.png")
  t0=$(now)
  if ! "$skein" stitch "$obj" --field "${start[@]}" -o "$tmp/$name.skein" --stats "$tmp/$name.json" "${png[@]}" 2> "$tmp/$name.log"; then
    reason=$(grep -m1 -o 'error .*' "$tmp/$name.log" | sed "s|$tmp/corpus/||; s|^error ||")
    echo "| $name | $faces | $start_text | | | | | | | | refused: $reason |"
    continue
  fi
  t1=$(now)
  "$skein" -q relax-mesh "$tmp/$name.skein" -o "$tmp/$name-relaxed.skein"
  t2=$(now)
  png=()
  [ -n "$pictures" ] && png=(--png "$pictures/$name-yarn.png")
  "$skein" -q yarn "$tmp/$name-relaxed.skein" -o "$tmp/$name.bcc" "${png[@]}"
  points=$(python3 -c "import sys; sys.path.insert(0, 'bench'); import bcc; print(sum(len(c) for c in bcc.read_curves(sys.argv[1])[1]))" "$tmp/$name.bcc")
  read -r sf rows inc dec valid < <(field "$tmp/$name.json" "' '.join(str(r[k]) for k in ('faces', 'rows', 'increases', 'decreases', 'valid'))")
  printf "| %s | %s | %s | %s | %s | %s | %s | %.2f | %.2f | %s | %s |\n" "$name" "$faces" "$start_text" "$sf" "$rows" "$inc" "$dec" \
    "$(echo "$t1 - $t0" | bc)" "$(echo "$t2 - $t1" | bc)" "$points" "$([ "$valid" = True ] && echo "valid stitch mesh, yarn" || echo "INVALID")"
done
