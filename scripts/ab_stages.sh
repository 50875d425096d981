#!/usr/bin/env bash
# Interleaved comparison of dyngi_sample option sets by their fenced stage times (each pass submitted and
# waited for on its own: on lavapipe GPU timestamps bracket compute dispatches loosely). Each round runs
# every set once, in turn, so this machine's drift hits them alike; prints one row per set: the medians
# over the rounds of each stage's median, and of the frame median (fenced frames are slower than plain
# ones: compare frames with scripts/ab_options.sh).
#   scripts/ab_stages.sh ROUNDS SIZE "LABEL|ARGS" ["LABEL|ARGS" ...]
# e.g. a change against the binary before it (ARGS starting with @PATH run the dyngi_sample at PATH):
#   scripts/ab_stages.sh 4 512 "before|@/tmp/base/dyngi_sample --gi vct" "after|--gi vct"
# env: BIN (build/bin/dyngi_sample), FRAMES (24), WARMUP (6), STAGES (the stages to print, space-separated;
# default every stage any set reported)
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: scripts/ab_stages.sh ROUNDS SIZE \"LABEL|ARGS\" ..." >&2
  exit 2
fi
cd "$(dirname "$0")/.."
rounds=$1 size=$2
shift 2
bin=${BIN:-build/bin/dyngi_sample} frames=${FRAMES:-24} warmup=${WARMUP:-6}
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
    "$setBin" --headless --size "${size}x${size}" --frames "$frames" --warmup "$warmup" --stage-times fenced $args \
      --stats "$out/${i}_$r.json" >/dev/null 2>&1
    i=$((i + 1))
  done
done
STAGES=${STAGES:-} python3 - "$out" "$rounds" "$@" <<'PY'
import json, os, statistics, sys
out, rounds, sets = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
runs = [[json.load(open(f"{out}/{i}_{r}.json")) for r in range(1, rounds + 1)] for i in range(len(sets))]
stages = os.environ["STAGES"].split() or sorted({k for rs in runs for d in rs for k in d["stages_ms"]})
print("| set | " + " | ".join(stages) + " | frame (fenced) |")
print("| --- " * (len(stages) + 2) + "|")
for s, rs in zip(sets, runs):
    cells = [statistics.median(d["stages_ms"].get(k, 0.0) for d in rs) for k in stages]
    frame = statistics.median(d["frame_ms"]["median"] for d in rs)
    print(f"| {s.split('|')[0]} | " + " | ".join(f"{c:.2f}" for c in cells) + f" | {frame:.1f} |")
PY
