#!/usr/bin/env bash
# The GI budget's reach per technique: on the rotating-object Cornell box (ANIMATE: another scripted
# scene, e.g. moving-spot, where only a light moves; SIZE 256x256), each technique
# unbudgeted, then with budgets at 1/4, 1/2 and 3/4 of its unbudgeted GI median. The unbudgeted run has
# a budget of 10 s, which lowers nothing but reads the cost as a budget does (fenced frames where the
# timestamps miss work: VCT on lavapipe), so the fractions are of a cost the device spends. For each budget: the
# GI's median and p95 after the warm-up (the controller's descent left out), what the budget read
# (timestamps or fenced frames) and the knobs at the end, and a verdict: the median within 15 percent
# of the budget. Not in CI (timing; ~6 minutes here); docs/QUALITY.md keeps its last result.
#   scripts/budget_reach.sh [TECHNIQUE...]     env: ANIMATE (rotating-object), SIZE (256x256), FRAMES (200), WARMUP (60),
#                                              EXTRA (more options for every run, e.g. "--bounce-frames 4")
set -euo pipefail
cd "$(dirname "$0")/.."
ANIMATE="${ANIMATE:-rotating-object}"
SIZE="${SIZE:-256x256}"
FRAMES="${FRAMES:-200}"
WARMUP="${WARMUP:-60}"
read -r -a EXTRA_ARGS <<< "${EXTRA:-}"
TECHNIQUES=("$@")
[ ${#TECHNIQUES[@]} -gt 0 ] || TECHNIQUES=(temporal many-lights vct)
BIN=build/bin/dyngi_sample
[ -x $BIN ] || { echo "budget_reach.sh: build dyngi_sample first" >&2; exit 2; }
out=out/budget_reach/$ANIMATE
mkdir -p $out
field() {  # field FILE EXPR: a value from a stats JSON
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"
}
status=0
echo "| technique | budget | GI ms median | p95 | read from | knobs at the end | verdict |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for gi in "${TECHNIQUES[@]}"; do
  run() {  # run BUDGET_MS NAME
    $BIN --headless --scene cornell --animate "$ANIMATE" --gi "$gi" --size "$SIZE" --frames "$FRAMES" --warmup "$WARMUP" \
      --gi-budget-ms "$1" --stats "$out/$gi-$2.json" "${EXTRA_ARGS[@]}" >/dev/null 2>&1
  }
  run 10000 none
  full=$(field "$out/$gi-none.json" "d['gi_ms']['median']")
  echo "| $gi | none | $(printf %.1f "$full") | $(printf %.1f "$(field "$out/$gi-none.json" "d['gi_ms']['p95']")") | | | |"
  for f in 0.25 0.5 0.75; do
    budget=$(python3 -c "print('%.2f' % ($full * $f))")
    run "$budget" "$f"
    j="$out/$gi-$f.json"
    median=$(field "$j" "d['gi_ms']['median']")
    p95=$(field "$j" "d['gi_ms']['p95']")
    timing=$(field "$j" "d['budget'].get('timing', '')")
    knobs=$(field "$j" "', '.join('%s %g' % kv for kv in d['budget']['knobs'].items())")
    verdict=$(python3 -c "m = $median / $budget - 1; print('%+.0f%%: %s' % (100 * m, 'ok' if abs(m) <= 0.15 else 'FAIL'))")
    case "$verdict" in *FAIL) status=1 ;; esac
    echo "| $gi | $f x = $budget ms | $(printf %.1f "$median") | $(printf %.1f "$p95") | $timing | $knobs | $verdict |"
  done
done
exit $status
