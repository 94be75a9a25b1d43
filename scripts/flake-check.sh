#!/usr/bin/env bash
# scripts/flake-check.sh N [--busy]
# Runs the ctest tests labelled `realtime` (real processes over LCM, paced by the wall clock:
# physical system tests, LCM run/batch/CLI tests) N times in a row, never retrying a failure,
# and prints each test's pass count. With --busy one CPU-bound process (`yes > /dev/null`) runs
# beside them the whole time and is killed at the end. Logs of each pass: $BUILD_DIR/flake-check/.
# Exit status 0 only when every test passed every time.
# Environment: BUILD_DIR (default build), CTEST_ARGS (extra ctest arguments, e.g. -R Physical).
set -euo pipefail
cd "$(dirname "$0")/.."

usage() { echo "usage: scripts/flake-check.sh N [--busy]" >&2; exit 2; }
[[ $# -ge 1 && $# -le 2 ]] || usage
[[ "$1" =~ ^[1-9][0-9]*$ ]] || usage
n=$1
busy=0
if [[ $# -eq 2 ]]; then
  [[ "$2" == "--busy" ]] || usage
  busy=1
fi
build=${BUILD_DIR:-build}
[[ -f "$build/CTestTestfile.cmake" ]] || { echo "flake-check: no ctest tree in '$build' (build first)" >&2; exit 2; }
logs="$build/flake-check"
mkdir -p "$logs"
rm -f "$logs"/pass-*.log

busy_pid=""
cleanup() { if [[ -n "$busy_pid" ]]; then kill "$busy_pid" 2>/dev/null || true; wait "$busy_pid" 2>/dev/null || true; fi; }
trap cleanup EXIT INT TERM
if [[ $busy -eq 1 ]]; then
  yes > /dev/null &
  busy_pid=$!
  echo "flake-check: busy process pid $busy_pid (yes > /dev/null)"
fi

read -r load1 load5 load15 _ < /proc/loadavg
echo "flake-check: $n pass(es) of ctest -L realtime in $build; load average at start $load1 $load5 $load15; $(nproc) CPUs"
start=$(date +%s)
for ((i = 1; i <= n; ++i)); do
  # ctest's exit status is read from the summary below; a failing pass does not stop the loop.
  (cd "$build" && ctest -L realtime --output-on-failure --timeout 900 ${CTEST_ARGS:-}) > "$logs/pass-$i.log" 2>&1 || true
  read -r l1 _ < /proc/loadavg
  echo "pass $i/$n: $(grep -E 'tests passed|No tests were found' "$logs/pass-$i.log" | tail -1) (load $l1)"
done
read -r load1 load5 load15 _ < /proc/loadavg
echo "flake-check: $(( $(date +%s) - start )) s; load average at end $load1 $load5 $load15"

# One line per test: passes/N, from ctest's per-test lines ("  3/40 Test  #7: Name ....   Passed").
awk -v n="$n" '
  match($0, /Test +#[0-9]+: [^ ]+/) {
    name = substr($0, RSTART, RLENGTH); sub(/Test +#[0-9]+: /, "", name)
    if (!(name in seen)) { seen[name] = 1; order[++count] = name; pass[name] = 0 }
    if ($0 ~ / Passed +[0-9.]+ sec/) pass[name]++
  }
  END {
    bad = 0
    for (i = 1; i <= count; ++i) {
      printf "%3d/%d  %s\n", pass[order[i]], n, order[i]
      if (pass[order[i]] != n) bad = 1
    }
    if (count == 0) { print "flake-check: no test carries the label realtime"; bad = 1 }
    exit bad
  }' "$logs"/pass-*.log
