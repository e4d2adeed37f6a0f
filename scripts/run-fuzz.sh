#!/usr/bin/env bash
# Runs libFuzzer harnesses: run-fuzz.sh BUILD_DIR SECONDS TARGET... (targets without the fuzz_ prefix).
# Each target starts from the seed corpus fuzz/corpus/<target>/ (left untouched: new inputs go to
# BUILD_DIR/corpus/<target>/), runs SECONDS under ASan + UBSan and fails on any finding, whose reproducer
# is kept in BUILD_DIR/findings/. Prints libFuzzer's last status line (execs, cov, ft) per target.
set -uo pipefail
cd "$(dirname "$0")/.."
build=$(cd "$1" && pwd) seconds=$2
shift 2
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1:abort_on_error=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build/findings"
failed=0
for t in "$@"; do
  bin="$build/fuzz_$t"
  seeds="$PWD/fuzz/corpus/$t"
  work="$build/corpus/$t"
  mkdir -p "$work"
  log="$build/fuzz_$t.log"
  # -close_fd_mask=3: the commands' own messages are silenced, libFuzzer's report is kept.
  "$bin" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -malloc_limit_mb=1024 -close_fd_mask=3 \
         -print_final_stats=1 -artifact_prefix="$build/findings/$t-" "$work" "$seeds" >"$log" 2>&1
  rc=$?
  stats=$(grep -E '^#[0-9]+' "$log" | tail -1)
  execs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
  if [ $rc -ne 0 ]; then
    echo "fuzz_$t: FINDING (exit $rc), see $log and $build/findings/"
    grep -E 'ERROR|SUMMARY|runtime error|deadly signal|out-of-memory|timeout' "$log" | head -5
    failed=1
  else
    echo "fuzz_$t: ${seconds}s, ${execs:-?} execs, last: ${stats:-none}"
  fi
done
exit $failed
