#!/usr/bin/env bash
# Prints the GI quality tables, technique by metric, as the render tests measure them
# (tests/render/quality_test.cpp; deterministic: fixed time step and seeds): flicker and settle time
# after a change, flicker under a slow camera pan, light leaking through a thin wall, ghosting behind a
# moving box. docs/QUALITY.md keeps the last tables. Needs a build with tests:
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDYNGI_BUILD_TESTS=ON && cmake --build build -j"$(nproc)"
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/bin/dyngi_render_tests}
[ -x "$BIN" ] || { echo "quality_report.sh: $BIN not built (see the comment at the top)" >&2; exit 2; }
cmd="$BIN --gtest_filter=RenderTest.Quality*"
echo "command: $cmd"
out=$(DYNGI_REPORT=1 $cmd 2>&1) || { echo "$out" >&2; exit 1; }
table() {  # the lines the tests print with prefix $1, as a Markdown table
  echo "$out" | sed -n "s/^$1| //p" |
    awk 'NR == 1 { print "| " $0 " |"; n = split($0, f, "|"); s = "|"; for (i = 0; i < n; ++i) s = s " --- |"; print s; next } { print "| " $0 " |" }'
}
echo
table quality
echo
table quality-pan
echo
table quality-leak
echo
table quality-ghost
