#!/usr/bin/env bash
# Runs the whole test suite N times in a row while two CPU-busy loops keep both cores of a two-core machine busy, and
# prints one line per run: its wall time and the totals `.ci/run` would print (docs/simulator.md, "The suite under load").
#   tools/loaded-suite.sh [N]
# Builds once first (not timed), so that every run measures the tests alone; OUT (default a fresh /tmp folder) keeps
# each run's console output.
set -u
N=${1:-5}
root=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-$(mktemp -d /tmp/loaded-suite.XXXXXX)}
mkdir -p "$out"
cd "$root" || exit 1
dotnet build LaserEngrave.sln -v q -nologo > "$out/build.log" 2>&1 || { echo "build failed: $out/build.log"; exit 1; }
pids=()
cleanup() { kill "${pids[@]}" 2>/dev/null; }
trap cleanup EXIT
( while :; do :; done ) & pids+=($!)
( while :; do :; done ) & pids+=($!)
for run in $(seq 1 "$N"); do
  start=$(date +%s)
  dotnet test LaserEngrave.sln --no-build > "$out/run$run.log" 2>&1
  rc=$?
  end=$(date +%s)
  passed=0; failed=0
  while read -r f p; do failed=$((failed + f)); passed=$((passed + p)); done < <(
    sed -n 's/.*Failed: *\([0-9]*\), Passed: *\([0-9]*\),.*/\1 \2/p' "$out/run$run.log")
  echo "run $run: exit $rc, $passed passed, $failed failed, $((end - start)) s$(grep -m3 -o '^ *Failed [A-Za-z0-9_.]*' "$out/run$run.log" | tr -s ' ' | tr '\n' ';')"
done
echo "logs in $out"
