#!/usr/bin/env bash
# Woven appearance figures of docs/BENCHMARKS.md "Woven appearance" (issue 29): exemplar making, synthesis and
# edge fixing at Zhao's size (900 x 1500 crossings), rendering, and the synthesized volume against the design
# relaxed directly. Timings are medians of RUNS runs (default 3) on a quiet machine.
# Usage: bench/woven_runs.sh [RUNS]   (about 6 minutes on 2 cores)
source "$(dirname "$0")/common.sh"
runs=${1:-3}
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
mkdir -p "$tmp/ex"
for k in $(seq "$runs"); do
  "$skein" -q weave-exemplar patterns/{plain-weave,twill-3-2,twill-4-1,satin-5-2,basket-2x2}.weave -o "$tmp/ex" --report "$tmp/ex-$k.json"
done
echo "| exemplar (10 x 10 crossings, 240 x 240 voxels a layer) | relax steps | relax [s] | voxelize [s] | voxels | filled |"
echo "| --- | --- | --- | --- | --- | --- |"
for e in 0 1 2 3 4; do
  relax=$(for k in $(seq "$runs"); do field "$tmp/ex-$k.json" "r['exemplars'][$e]['relax_seconds']"; done | median)
  voxel=$(for k in $(seq "$runs"); do field "$tmp/ex-$k.json" "r['exemplars'][$e]['voxel_seconds']"; done | median)
  field "$tmp/ex-1.json" "'| {} | {} | {:.2f} | {:.2f} | {} x {} x {} | {:.0%} |'.format(r['exemplars'][$e]['pattern'], r['exemplars'][$e]['steps'], $relax, $voxel, *r['exemplars'][$e]['voxels'], r['exemplars'][$e]['filled'])"
done
echo
echo "| design | crossings | synthesis [s] | edge fixing [s] | whole run [s] | peak memory [MB] | effective voxels | seam step before / after [mm] |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for k in $(seq "$runs"); do
  /usr/bin/time -f "%e %M" -o "$tmp/time-$k" "$skein" -q weave-volume patterns/woven/herringbone.weave --exemplars "$tmp/ex" --size 900x1500 --report "$tmp/big-$k.json"
done
syn=$(for k in $(seq "$runs"); do field "$tmp/big-$k.json" "r['synthesis_seconds']"; done | median)
fix=$(for k in $(seq "$runs"); do field "$tmp/big-$k.json" "r['edge_fixing']['seconds']"; done | median)
wall=$(for k in $(seq "$runs"); do cut -d' ' -f1 "$tmp/time-$k"; done | median)
mem=$(for k in $(seq "$runs"); do cut -d' ' -f2 "$tmp/time-$k"; done | median)
field "$tmp/big-1.json" "'| herringbone | 900 x 1500 | {:.2f} | {:.2f} | {} | {:.0f} | {:.3g} | {:.4f} / {:.4f} |'.format($syn, $fix, $wall, $mem / 1024, r['effective_voxels'], r['edge_fixing']['seam_step_mm'], r['edge_fixing']['seam_step_fixed_mm'])"
echo
echo "| render | pixels | paths per pixel | seconds | seconds per megapixel and path |"
echo "| --- | --- | --- | --- | --- |"
for k in $(seq "$runs"); do
  "$skein" -q weave-volume patterns/satin-5-2.weave --exemplars "$tmp/ex" --size 48x32 --png "$tmp/r.png" --width 640 --height 400 --samples 16 --report "$tmp/render-$k.json"
done
sec=$(for k in $(seq "$runs"); do field "$tmp/render-$k.json" "r['render']['seconds']"; done | median)
python3 -c "print('| satin 48 x 32 crossings, whole | 640 x 400 | 16 | {:.1f} | {:.1f} |'.format($sec, $sec / (0.256 * 16)))"
echo
echo "| design (16 x 16 crossings) | in an exemplar | top yarn agrees: synthesized / relaxed again / another weave | density error | fibre angle [deg] | occupancy |"
echo "| --- | --- | --- | --- | --- | --- |"
for d in satin-5-2.weave:yes twill-2-1.weave:no satin-5-3.weave:no woven/herringbone.weave:no; do
  "$skein" -q weave-volume "patterns/${d%%:*}" --exemplars "$tmp/ex" --size 16x16 --compare-truth --report "$tmp/t.json"
  field "$tmp/t.json" "'| ${d%%:*} | ${d##*:} | ' + ' / '.join('{:.0%}'.format(r['truth'][k]['top_agreement']) for k in ('synthesized', 'relaxed_again', 'other_weave')) + ' | ' + ' / '.join('{:.2f}'.format(r['truth'][k]['density_error']) for k in ('synthesized', 'relaxed_again', 'other_weave')) + ' | ' + ' / '.join('{:.0f}'.format(r['truth'][k]['orientation_deg']) for k in ('synthesized', 'relaxed_again', 'other_weave')) + ' | ' + ' / '.join('{:.2f}'.format(r['truth'][k]['occupancy']) for k in ('synthesized', 'relaxed_again', 'other_weave')) + ' |'"
done
