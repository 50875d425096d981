#!/usr/bin/env bash
# How many frames the GI takes to settle after a light appears: the static Cornell box, a point light
# added at frame 20 (an input script: the cursor on the floor, key L), each technique and setting
# rendered headless to 20 + n frames for several n and compared with the image 64 frames after (the
# settled one; the fixed 1/60 s step makes every run the same up to then). Prints relMSE per n and the
# settle time: the first n from which the relMSE stays under 0.002 (about 4.5 percent RMS). The rows
# "one-off work spread" set a GI budget that lowers nothing (10 s): the work a budget spreads over frames
# (Technique::spreadOneOffWork) is spread, every knob stays at full quality.
# docs/QUALITY.md keeps the table. Not in CI (about 3 minutes here).
#   scripts/settle_time.sh        env: SIZE (128x128)
set -euo pipefail
cd "$(dirname "$0")/.."
SIZE="${SIZE:-128x128}"
BIN=build/bin
[ -x $BIN/dyngi_sample ] && [ -x $BIN/dyngi_imgcmp ] || { echo "settle_time.sh: build dyngi_sample and dyngi_imgcmp first" >&2; exit 2; }
out=out/settle_time
mkdir -p $out
EVENT=20
AFTER=(1 2 3 4 6 8 12 16 24 32)
SETTLED=64
W=${SIZE%x*}
H=${SIZE#*x}
printf "%d move %d %d\n%d key L\n" $EVENT $((W / 2)) $((H * 85 / 100)) $EVENT >$out/add_light.txt
configs=(
  "temporal|default|"
  "many-lights|default|"
  "vct|default|"
  "vct|radiance over 2 frames|--radiance-frames 2"
  "vct|radiance over 4 frames|--radiance-frames 4"
  "temporal|one-off work spread|--gi-budget-ms 10000"
  "vct|one-off work spread|--gi-budget-ms 10000"
)
echo "| technique | setting | relMSE at n = ${AFTER[*]} frames after | settles after (frames) |"
echo "| --- | --- | --- | --- |"
i=0
for c in "${configs[@]}"; do
  IFS='|' read -r gi name opts <<<"$c"
  i=$((i + 1))
  render() {  # render FRAMES FILE
    # shellcheck disable=SC2086
    $BIN/dyngi_sample --headless --scene cornell --size "$SIZE" --gi "$gi" $opts --input-script $out/add_light.txt --frames "$1" \
      --hdr-out "$2" >/dev/null 2>&1
  }
  render $((EVENT + SETTLED)) $out/$i-settled.exr
  errs=()
  for n in "${AFTER[@]}"; do
    render $((EVENT + n)) $out/$i-$n.exr
    errs+=("$($BIN/dyngi_imgcmp $out/$i-settled.exr $out/$i-$n.exr | tail -1 | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['rel_mse'])")")
  done
  settle=$(python3 -c "
import sys
after, errs = [int(a) for a in sys.argv[1].split()], [float(e) for e in sys.argv[2].split()]
first = next((a for k, a in enumerate(after) if all(e < 0.002 for e in errs[k:])), None)
print(first if first is not None else '> %d' % after[-1])" "${AFTER[*]}" "${errs[*]}")
  echo "| $gi | $name | ${errs[*]} | $settle |"
done
