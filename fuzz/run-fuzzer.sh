#!/usr/bin/env bash
# Runs one libFuzzer harness for a bounded number of inputs from its seed corpus, as a CTest:
#   run-fuzzer.sh FUZZER SEEDS WORKDIR RUNS
# New inputs go to WORKDIR (emptied first), so the seeds in the build tree stay as generated and
# every run starts from the same place; a crash leaves its input in WORKDIR/crash-*.
set -euo pipefail
fuzzer="$1" seeds="$2" work="$3" runs="$4"
rm -rf "$work"
mkdir -p "$work/corpus"
exec "$fuzzer" -seed=1 -runs="$runs" -max_len=4096 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/" "$work/corpus" "$seeds"
