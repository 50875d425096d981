#!/usr/bin/env bash
# Interleaved comparison of dyngi_sample option sets by their fenced stage times (each pass submitted and
# waited for on its own: on lavapipe GPU timestamps bracket compute dispatches loosely): the rounds of
# scripts/ab_options.sh, reported per stage. Prints one row per set: the medians over the rounds of each
# stage's median, and of the frame median (fenced frames are slower than plain ones: compare frames with
# scripts/ab_options.sh).
#   scripts/ab_stages.sh ROUNDS SIZE "LABEL|ARGS" ["LABEL|ARGS" ...]
# e.g. a change against the binary before it (ARGS starting with @PATH run the dyngi_sample at PATH):
#   scripts/ab_stages.sh 4 512 "before|@/tmp/base/dyngi_sample --gi vct" "after|--gi vct"
# env: as scripts/ab_options.sh's, and STAGES (the stages to print, space-separated; default every stage
# any set reported)
set -euo pipefail
REPORT=stages exec bash "$(dirname "$0")/ab_options.sh" "$@"
