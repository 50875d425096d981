#!/usr/bin/env bash
# Interleaved comparison of dyngi_sample option sets (one binary): each round runs every set once, in
# turn, so this machine's drift (10-30% over minutes) hits them alike; prints each set's per-round frame
# medians and their median. Headless, the main job's scene unless a set names another.
#   scripts/ab_options.sh ROUNDS SIZE "LABEL|ARGS" ["LABEL|ARGS" ...]
# e.g. the trace spread over frames against the temporal VPL technique at 768^2:
#   scripts/ab_options.sh 3 768 "off|--gi off" "vct 1|--gi vct --trace-frames 1" "vct 4|--gi vct" "temporal|--gi temporal"
# A set's arguments may start with @PATH: that set runs the dyngi_sample at PATH (another build), e.g.
#   scripts/ab_options.sh 5 512 "old vct|@/tmp/base/build/bin/dyngi_sample --gi vct" "vct|--gi vct" "temporal|--gi temporal"
# env: BIN (build/bin/dyngi_sample), FRAMES (24), WARMUP (6); REPORT=stages (what scripts/ab_stages.sh
# sets): fenced stage times instead, one row per set with each stage's median over the rounds (STAGES:
# the stages to print, space-separated; default every stage a set reported)
set -euo pipefail
report=${REPORT:-frames}
if [ $# -lt 3 ]; then
  [ "$report" = stages ] && name=ab_stages.sh || name=ab_options.sh
  echo "usage: scripts/$name ROUNDS SIZE \"LABEL|ARGS\" ..." >&2
  exit 2
fi
cd "$(dirname "$0")/.."
rounds=$1 size=$2
shift 2
bin=${BIN:-build/bin/dyngi_sample} frames=${FRAMES:-24} warmup=${WARMUP:-6}
timing=""
[ "$report" = stages ] && timing="--stage-times fenced"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 "$rounds"); do
  i=0
  for set in "$@"; do
    args=${set#*|} setBin=$bin
    if [[ $args == @* ]]; then
      setBin=${args%% *} args=${args#* }
      setBin=${setBin#@}
    fi
    # shellcheck disable=SC2086
    "$setBin" --headless --size "${size}x${size}" --frames "$frames" --warmup "$warmup" $timing $args --stats "$out/${i}_$r.json" >/dev/null 2>&1
    i=$((i + 1))
  done
done
REPORT=$report STAGES=${STAGES:-} python3 - "$out" "$rounds" "$@" <<'PY'
import json, os, statistics, sys
out, rounds, sets = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
runs = [[json.load(open(f"{out}/{i}_{r}.json")) for r in range(1, rounds + 1)] for i in range(len(sets))]
if os.environ["REPORT"] != "stages":
    for s, rs in zip(sets, runs):
        frames = [d["frame_ms"]["median"] for d in rs]
        print(f"| {s.split('|')[0]} | `{s.split('|', 1)[1]}` | {', '.join(f'{f:.1f}' for f in frames)} | {statistics.median(frames):.1f} |")
    sys.exit(0)
stages = os.environ["STAGES"].split() or sorted({k for rs in runs for d in rs for k in d["stages_ms"]})
print("| set | " + " | ".join(stages) + " | frame (fenced) |")
print("| --- " * (len(stages) + 2) + "|")
for s, rs in zip(sets, runs):
    cells = [statistics.median(d["stages_ms"].get(k, 0.0) for d in rs) for k in stages]
    frame = statistics.median(d["frame_ms"]["median"] for d in rs)
    print(f"| {s.split('|')[0]} | " + " | ".join(f"{c:.2f}" for c in cells) + f" | {frame:.1f} |")
PY
