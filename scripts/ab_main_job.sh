#!/usr/bin/env bash
# Interleaved A/B of the main job's frame time (scripts/run.sh's headless command: --gi temporal, the default
# scene and size): two dyngi_sample binaries run in turn, RUNS times each, so this machine's drift
# (10-30% over minutes) hits both alike; prints each run and the medians of the runs' frame medians.
#   scripts/ab_main_job.sh A_BIN B_BIN [RUNS=5] [extra dyngi_sample arguments...]
# e.g. a build of an older commit against this one:
#   git worktree add /tmp/base REV && cmake -S /tmp/base -B /tmp/base/build -DCMAKE_BUILD_TYPE=Release \
#     -DDYNGI_BUILD_TESTS=OFF && cmake --build /tmp/base/build -j2 --target dyngi_sample
#   scripts/ab_main_job.sh /tmp/base/build/bin/dyngi_sample build/bin/dyngi_sample
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: scripts/ab_main_job.sh A_BIN B_BIN [RUNS] [dyngi_sample arguments...]" >&2
  exit 2
fi
a=$1 b=$2 runs=${3:-5}
shift $(( $# >= 3 ? 3 : 2 ))
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq 1 "$runs"); do
  for who in a b; do
    bin=$a; [ "$who" = b ] && bin=$b
    "$bin" --headless --gi temporal --out "$out/$who.png" --stats "$out/${who}_$i.json" "$@" >/dev/null 2>&1
  done
done
python3 - "$out" "$runs" <<'PY'
import json, statistics, sys
out, runs = sys.argv[1], int(sys.argv[2])
for who in "ab":
    frame = [json.load(open(f"{out}/{who}_{i}.json"))["frame_ms"]["median"] for i in range(1, runs + 1)]
    gi = [json.load(open(f"{out}/{who}_{i}.json")).get("gi_ms", {}).get("median", 0) for i in range(1, runs + 1)]
    print(f"{who}: frame ms per run {[round(x, 1) for x in frame]}  median {statistics.median(frame):.1f}  "
          f"(GI median {statistics.median(gi):.1f})")
PY
