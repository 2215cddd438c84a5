#!/bin/bash
# Exit status, wall time and peak RSS of the inputs of docs/limits.md, one Markdown row
# each: benchmarks/limits_rss.sh [SCRATCH_DIR]  (ROCKARCH=path/to/rockarch to choose one)
OUT=${1:-$(mktemp -d)}; mkdir -p "$OUT"; cd "$OUT" || exit 2
RA=${ROCKARCH:-rockarch}
B="simulate block --alpha 0.15 --p 2 --ratio 2"
A="--shape catenary --span 10 --rise 3 --thickness 0.25 --blocks 20 --ratio 1.5"
# issue 22's files: records of 6e6 and 4.9e6 samples (two columns), 3000 stacked blocks
awk 'BEGIN { for (i = 0; i < 6000000; i++) printf "%.3f %.6f\n", i * 0.001, 3 * sin(i * 0.007) }' \
  > rec6e6.txt
head -n 4900000 rec6e6.txt > rec49e5.txt
awk 'BEGIN { printf "{\"blocks\": ["; for (k = 0; k < 3000; k++) printf "%s{\"polygon\": [[0, %g], [0.4, %g], [0.4, %g], [0, %g]]}", (k ? ", " : ""), k / 10, k / 10, (k + 1) / 10, (k + 1) / 10; print "]}" }' \
  > blocks3000.json
while IFS= read -r c; do
  [ -z "$c" ] && continue
  /usr/bin/time -f "%e %M" -o "$OUT/time.txt" $RA $c > "$OUT/out.txt" 2> "$OUT/err.txt"
  rc=$?
  read -r wall rss < <(tail -1 "$OUT/time.txt")
  msg=$(grep -v "^\s*$" "$OUT/err.txt" | tail -1 | cut -c1-110)
  [ -z "$msg" ] && msg=$(tail -1 "$OUT/out.txt" | cut -c1-110)
  printf '| `rockarch %s` | %s | %s | %.0f MB | %s |\n' "$c" "$rc" "$wall" "$(echo "$rss/1024" | bc -l)" "$msg"
done <<LIST
$B --signal harmonic --period 1 --cycles 1000000
$B --signal harmonic --period 1 --cycles 100000
$B --signal sine --period 1 --t-free 1e9
$B --signal sine --period 1e9
simulate block --alpha 0.15 --p 1e300 --ratio 2 --signal sine --period 1
simulate block --alpha 0.15 --p 5 --ratio 1.3 --signal harmonic --period 0.1 --cycles 4999 --t-free 20 --plot $OUT/th.png
simulate mdof $A --signal sine --period 1 --t-free 1e9
animate $A --signal sine --period 1e9 --out $OUT/m.gif
animate $A --signal sine --period 1 --t-free 1e9 --out $OUT/m.gif
oas --alpha 0.1 --signal sine --period 1 --p 1e300,1e301 --no-store
oas --alpha 0.15 --p 2,4 --ratio-steps 3 --signal harmonic --period 0.1 --cycles 4999 --no-store
oas --alpha 0.15 --p 2 --ratio-steps 3 --signal sine --period 1e300 --no-store
records synth $OUT/synth --n 1000000000
simulate mdof --wall 1000,1000 --block 0.4,0.2 --ratio 2 --signal sine --period 1
simulate mdof --assembly blocks3000.json --ratio 2 --signal sine --period 1
arch --shape catenary --span 10 --rise 3 --thickness 0.25 --blocks 1000000
arch --shape catenary --span 10 --rise 3 --thickness 0.25 --blocks 100000
$B --record rec6e6.txt --units m/s2
$B --record rec49e5.txt --units m/s2 --plot $OUT/th.png
LIST
