#!/usr/bin/env bash
# Runs a fixed set of jobs on the twin (--simulate, virtual time, seed 1) with the hidden --sim-wire flight recorder and
# writes, per job, the digests of the bytes sent and received on each port, so that two builds can be compared:
#   tools/wire-capture.sh OUT          # OUT: a new folder (e.g. /work/wire-before)
#   diff -r /work/wire-before/digests OUT/digests
# Per job JOB: digests/JOB.txt (per port and direction: byte count and SHA-256 of the bytes; then the SHA-256 of the
# whole timed recording), digests/JOB.json (the --json summary without wall time and paths), digests/JOB.progress (the
# progress lines), wire/JOB.jsonl (the recording itself, to find a difference). Build first: dotnet build src/LaserEngrave.Cli
# Environment: CLI (laserengrave.dll; default: this tree's Debug build); SIM_OPTIONS (a --sim-options file for every job,
# e.g. a never-late host to compare the protocol alone across a change of the twin's defaults); NORMALIZE_ONLY=1 re-derives the .json and
# .progress digests of an earlier capture in OUT from its raw output (when this filter has changed).
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
CLI=${CLI:-$root/src/LaserEngrave.Cli/bin/Debug/net10.0/laserengrave.dll}
out=${1:?give the output folder}
mkdir -p "$out/digests" "$out/wire" "$out/logs"
cd "$root"
a=assets

digest() { # JOB: the digests of wire/JOB.jsonl
  python3 - "$out/wire/$1.jsonl" > "$out/digests/$1.txt" <<'EOF'
import hashlib, json, sys
streams = {}
timed = hashlib.sha256()
for line in open(sys.argv[1]):
    e = json.loads(line)
    if "x" not in e:
        continue
    key = ("stage" if e["p"] == "s" else "laser") + (" sent" if e["d"] == "w" else " received")
    h, n = streams.setdefault(key, [hashlib.sha256(), 0]), bytes.fromhex(e["x"])
    h[0].update(n); h[1] += len(n)
    timed.update(line.encode())
for key in sorted(streams):
    print(f"{key}: {streams[key][1]} bytes sha256 {streams[key][0].hexdigest()}")
print(f"timed recording sha256 {timed.hexdigest()}")
EOF
}

normalize() { # JOB: the --json summary and the progress lines without what differs from run to run
  local job=$1
  python3 - "$out/$job.stdout" > "$out/digests/$job.json" <<'EOF'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
except Exception:
    print(open(sys.argv[1]).read()); sys.exit()
def strip(o):
    if isinstance(o, dict):
        # What differs from run to run of the same build: wall time, clock dates, the build's version, file paths.
        return {k: strip(v) for k, v in o.items() if k not in ("wallSeconds", "startedAt", "endedAt", "softwareVersion") and not k.endswith("Path")}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
print(json.dumps(strip(j), indent=1, sort_keys=True))
EOF
  grep -v "^preflight" "$out/$job.stderr" | tr '\r' '\n' | sed -E 's/\(log: [^)]*\)/(log: LOG)/' > "$out/digests/$job.progress"
}

run() { # JOB COMMAND ARGS...: runs one job on the twin, records its wire traffic and digests it
  local job=$1; shift
  rm -f "$out/wire/$job.jsonl"
  dotnet "$CLI" "$@" --simulate ${SIM_OPTIONS:+--sim-options "$SIM_OPTIONS"} --log-dir "$out/logs" --sim-wire "$out/wire/$job.jsonl" --json \
    > "$out/$job.stdout" 2> "$out/$job.stderr"
  echo "exit $?" > "$out/digests/$job.exit"
  normalize "$job"
  digest "$job"
  echo "$job: $(head -c 200 "$out/digests/$job.exit")"
}

if [ "${NORMALIZE_ONLY:-0}" = 1 ]; then
  # Re-derives digests/*.json and *.progress of an earlier capture from its raw output (after this filter changed).
  for f in "$out"/*.stdout; do normalize "$(basename "$f" .stdout)"; done
  exit 0
fi

logof() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['logPath'])" "$out/$1.stdout"; }

# Every sample image, raster (timed switching), and the QR step by step (paper) and in dot mode.
run qr engrave $a/qr-code.bmp --width-mm 5
run text-banner engrave $a/text-banner.png --width-mm 8
run line-drawing engrave $a/line-drawing.png --width-mm 6
run qr-paper engrave $a/qr-code.bmp --width-mm 3 --strategy paper
run qr-unidirectional-2passes engrave $a/qr-code.bmp --width-mm 3 --unidirectional --passes 2
run qr-dots engrave $a/qr-code.bmp --width-mm 2 --mode dots --pulses-per-dot 3 --dot-settle-ms 2
# Drawings: DXF and SVG, outline and fill.
run hexagons-dxf engrave $a/drawings/hexagons.dxf --origin-mm 5,5
run curves-dxf-both engrave $a/drawings/curves.dxf --width-mm 30 --fill both --fill-pitch-um 100 --origin-mm 2,2
run every-command-svg engrave $a/drawings/every-command.svg --width-mm 40 --origin-mm 2,2
run text-svg-fill engrave $a/drawings/text-as-paths.svg --fill fill --fill-pitch-um 50 --origin-mm 2,2
# A job of layers (drawing layers and a raster).
run plate-layers engrave --job $a/jobs/plate.json
# Sweeps: raster cells with labels, dot cells.
run sweep-raster sweep --rows speed=0.5,1,2 --columns frequency=500,1000,2000 --labels
run sweep-dots sweep --mode dots --pattern dots --rows pulses-per-dot=1,2 --columns frequency=500,1000
# Resumes from a log: a raster, a drawing and a job of layers stopped by a silent stage, then continued.
run qr-stopped engrave $a/qr-code.bmp --width-mm 5 --fault silent:stage:after=400
run qr-resumed engrave --from-log "$(logof qr-stopped)" --resume
run hexagons-stopped engrave $a/drawings/hexagons.dxf --origin-mm 5,5 --fault silent:stage:after=7000
run hexagons-resumed engrave --from-log "$(logof hexagons-stopped)" --resume
run plate-stopped engrave --job $a/jobs/plate.json --fault silent:stage:after=2500
run plate-resumed engrave --from-log "$(logof plate-stopped)" --resume
run qr-dots-stopped engrave $a/qr-code.bmp --width-mm 2 --mode dots --fault silent:stage:after=400
run qr-dots-resumed engrave --from-log "$(logof qr-dots-stopped)" --resume
