#!/usr/bin/env bash
# Fuzzes the glTF/GLB importer with libFuzzer (clang, ASan + UBSan) for a bounded time.
#   scripts/fuzz.sh [SECONDS]   default 60; CI runs it with 60
# Builds build-fuzz/ (clang), makes the seed corpus with the test support code (build-fuzz/corpus-seed),
# grows build-fuzz/corpus, and writes any crash, leak or timeout input to build-fuzz/findings/. Exits 1
# on a finding: copy the file into tests/fuzz/regressions/ (GltfFuzzRegressions replays them), fix, rerun.
# Prints the executions reached ("fuzz: N executions in S s, 0 findings").
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_TO_RUN="${1:-60}"
bash scripts/setup.sh >/dev/null
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDYNGI_FUZZ=ON \
  -DDYNGI_WARNINGS_AS_ERRORS=OFF -DDYNGI_BUILD_TESTS=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target dyngi_fuzz_gltf dyngi_make_fuzz_corpus >/dev/null
mkdir -p build-fuzz/corpus-seed build-fuzz/corpus build-fuzz/findings
build-fuzz/bin/dyngi_make_fuzz_corpus build-fuzz/corpus-seed >/dev/null
cp tests/fuzz/regressions/*.gltf tests/fuzz/regressions/*.glb build-fuzz/corpus-seed/ 2>/dev/null || true
log=build-fuzz/fuzz.log
# -timeout: an input that takes over 10 s is a hang; -rss_limit_mb: one that wants over 2 GB is a finding.
set +e
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  build-fuzz/bin/dyngi_fuzz_gltf build-fuzz/corpus build-fuzz/corpus-seed -max_total_time="$SECONDS_TO_RUN" \
  -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix=build-fuzz/findings/ >"$log" 2>&1
rc=$?
set -e
execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
findings=$(find build-fuzz/findings -type f | wc -l)
echo "fuzz: $execs executions in $SECONDS_TO_RUN s, $findings findings (corpus: $(ls build-fuzz/corpus | wc -l) inputs)"
if [ "$rc" -ne 0 ] || [ "$findings" -ne 0 ]; then
  tail -40 "$log"
  echo "fuzz: FAILED (libFuzzer exit $rc); inputs in build-fuzz/findings/"
  exit 1
fi
