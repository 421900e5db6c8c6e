#!/usr/bin/env bash
# Engraves the QR sample through socat ptys against `laserengrave simulator` (both on the wall clock), N times, and
# prints one line per job: exit code, outcome, the error if any, wall time, dropped partial frames (the log's
# lineWarnings) and the pulses on white of its replay; then the totals.
#   tools/ports-bench.sh [N] [WIDTH_MM]
# Environment: CLI (laserengrave.dll to run; default: this tree's Release build), LOOPS=1 (two CPU-busy loops meanwhile),
# PIECES=3 (the simulator delivers every reply in two pieces this many ms apart, as a USB adapter does; 0: whole),
# NICE=-10 (socat and the simulator at that niceness: they stand in for a USB adapter and the devices' firmware, which
# never wait for the CPU; needs root or CAP_SYS_NICE; the host keeps the normal priority), MEASURE=0 (the default profile
# instead of one measured through the ptys first),
# VERBOSE=1 (socat -x -v: every transfer with its time in OUT/socat-*.log, to see which process held a reply),
# OUT (work folder; default a fresh one under /tmp).
# Build first: dotnet build -c Release src/LaserEngrave.Cli
set -u
N=${1:-1}; W=${2:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
CLI=${CLI:-$root/src/LaserEngrave.Cli/bin/Release/net10.0/laserengrave.dll}
out=${OUT:-$(mktemp -d /tmp/ports-bench.XXXXXX)}
mkdir -p "$out"
pids=()
cleanup() { kill "${pids[@]}" 2>/dev/null; }
trap cleanup EXIT
if [ "${LOOPS:-0}" = 1 ]; then
  ( while :; do :; done ) & pids+=($!)
  ( while :; do :; done ) & pids+=($!)
fi
verbose=(); [ "${VERBOSE:-0}" = 1 ] && verbose=(-x -v)
hw=(); [ -n "${NICE:-}" ] && hw=(nice -n "$NICE")
"${hw[@]}" socat "${verbose[@]}" pty,raw,echo=0,link="$out/s" pty,raw,echo=0,link="$out/sh" 2>"$out/socat-s.log" & pids+=($!)
"${hw[@]}" socat "${verbose[@]}" pty,raw,echo=0,link="$out/l" pty,raw,echo=0,link="$out/lh" 2>"$out/socat-l.log" & pids+=($!)
sleep 1
pieces=${PIECES:-3}
if [ "$pieces" != 0 ]; then
  echo "{ \"homeSpeedData\": 30000, \"replyPieces\": { \"probability\": 1, \"gapMs\": $pieces } }" > "$out/sim.json"
else
  echo '{ "homeSpeedData": 30000, "replyPieces": { "probability": 0, "gapMs": 0 } }' > "$out/sim.json"
fi
"${hw[@]}" dotnet "$CLI" simulator --stage-port "$out/s" --laser-port "$out/l" --sim-options "$out/sim.json" > "$out/sim.log" 2>&1 & pids+=($!)
sleep 3
# The host plans timed switching with the profile's latencies: measured here, through the ptys and this computer's
# scheduling (docs/machine-profile.md), as on a real machine; the default profile describes a USB adapter instead.
profile=(--profile "$out/profile.json")
if [ "${MEASURE:-1}" = 1 ]; then
  dotnet "$CLI" machine latency --stage-port "$out/sh" --laser-port "$out/lh" --profile "$out/profile.json" --write > "$out/latency.txt" 2>&1
  grep -E "adapter|round trips" "$out/latency.txt"
else
  profile=()
fi
completed=0; white=0
for j in $(seq 1 "$N"); do
  start=$(date +%s.%N)
  dotnet "$CLI" engrave "$root/assets/qr-code.bmp" --width-mm "$W" --origin-mm 10,10 --stage-port "$out/sh" --laser-port "$out/lh" "${profile[@]}" \
    --json --log-dir "$out/logs" > "$out/run$j.json" 2> "$out/run$j.err"
  rc=$?
  end=$(date +%s.%N)
  log=$(grep -o '"logPath": "[^"]*"' "$out/run$j.json" | head -1 | cut -d'"' -f4)
  dropped=0; onwhite="?"
  if [ -n "$log" ] && [ -f "$log" ]; then
    dropped=$(grep -c 'unfinished frame' "$log")
    dotnet "$CLI" replay "$log" --json > "$out/replay$j.json" 2> "$out/replay$j.err"
    onwhite=$(grep -o '"laserOnTravelCount": [0-9]*' "$out/replay$j.json" | head -1 | grep -o '[0-9]*$')
  fi
  grep -q '"outcome": "completed"' "$out/run$j.json" && completed=$((completed + 1))
  [ -n "$onwhite" ] && [ "$onwhite" != "?" ] && white=$((white + onwhite))
  echo "job $j exit $rc $(grep -o '"outcome": "[a-z]*"' "$out/run$j.json" | head -1) $(grep '^laserengrave:' "$out/run$j.err" | cut -c1-160) wall $(echo "$end - $start" | bc) s, dropped frames $dropped, replay on white ${onwhite:-?}"
done
echo "completed $completed of $N, pulses on white (replay) $white, in $out"
