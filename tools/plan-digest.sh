#!/usr/bin/env bash
# Prints one line per planning case: the SHA-256 of `plan --json` (stdout and warnings) and of `--segments` (every
# move as CSV), so that two builds can be compared line by line: a change to the planner or the estimate that keeps
# the output must print the same lines (docs/execution.md, "Planning speed").
#   tools/plan-digest.sh CLI [RINGS.bmp] > digests.txt
# CLI is the laserengrave executable (src/LaserEngrave.Cli/bin/Release/net10.0/laserengrave); RINGS.bmp, when given,
# adds the 20000 x 20000 rings of tools/make-rings.py (13 M moves, ~10 s a build). Random masks are made here, seeded.
set -u
cli=$1
rings=${2:-}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d /tmp/plan-digest.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$root" || exit 1

# A profile with scan offsets and a calibration (shear and scale), so the right-to-left rows' offset and the sheared edges are covered.
cat > "$work/profile.json" <<'EOF'
{
  "scanOffsets": [ { "speedMmPerS": 0.5, "offsetUm": 1.5 }, { "speedMmPerS": 1, "offsetUm": 3 }, { "speedMmPerS": 4, "offsetUm": 11 } ],
  "calibration": { "squarenessDegrees": 0.3, "scaleXPpm": 120, "scaleYPpm": -80 }
}
EOF

# Random masks: noise of several densities and blocky runs (short and long gaps, so some are crossed, flown or travelled).
python3 - "$work" <<'EOF'
import random, struct, sys
def bmp(path, w, h, black):
    stride = ((w + 31) // 32) * 4
    px = bytearray()
    for y in range(h - 1, -1, -1):
        row = bytearray(stride)
        for x in range(w):
            if not black(x, y):
                row[x // 8] |= 0x80 >> (x % 8)
        px += row
    pal = bytes([0, 0, 0, 0, 255, 255, 255, 0])
    off = 14 + 40 + len(pal)
    with open(path, "wb") as f:
        f.write(b"BM" + struct.pack("<IHHI", off + len(px), 0, 0, off))
        f.write(struct.pack("<IiiHHIIiiII", 40, w, h, 1, 1, 0, len(px), 2835, 2835, 2, 2))
        f.write(pal + px)
for seed, (w, h, p) in enumerate([(257, 129, 0.5), (300, 200, 0.05), (300, 200, 0.95), (1000, 64, 0.3), (64, 64, 0.5), (130, 3, 0.5)]):
    r = random.Random(seed)
    cells = [[r.random() < p for _ in range(w)] for _ in range(h)]
    bmp(f"{sys.argv[1]}/noise-{seed}.bmp", w, h, lambda x, y: cells[y][x])
for seed in range(4):
    r = random.Random(100 + seed)
    w, h = r.choice([(400, 120), (777, 90), (2048, 40)])
    rows = []
    for y in range(h):
        row, x, black = [], 0, r.random() < 0.5
        while x < w:
            n = int(r.expovariate(1 / r.choice([1, 3, 12, 60, 250]))) + 1
            row += [black] * n
            x += n
            black = not black
        rows.append(row[:w])
    bmp(f"{sys.argv[1]}/runs-{seed}.bmp", w, h, lambda x, y: rows[y][x])
EOF

digest() {
  local name=$1; shift
  local json csv
  if [ "$1" = --job ]; then
    "$cli" plan "$@" --json > "$work/out.txt" 2>&1
  else
    "$cli" plan "$@" --json --segments "$work/moves.csv" > "$work/out.txt" 2>&1
  fi
  echo "exit $?" >> "$work/out.txt"
  # The random masks' folder differs from run to run; the output names it.
  json=$(sed "s#$work#WORK#g" "$work/out.txt" | sha256sum | cut -c1-16)
  csv=$( [ -f "$work/moves.csv" ] && sha256sum < "$work/moves.csv" | cut -c1-16 || echo none)
  rm -f "$work/moves.csv"
  echo "$name json $json moves $csv"
}

variants() {
  local name=$1; shift
  digest "$name" "$@"
  digest "$name paper" "$@" --strategy paper
  digest "$name unidirectional" "$@" --unidirectional
  digest "$name overscan" "$@" --overscan-mm 0.2
  digest "$name fast" "$@" --speed-mm-s 2 --travel-speed-mm-s 4
  digest "$name slow" "$@" --speed-mm-s 0.2 --travel-speed-mm-s 2 --acceleration-mm-s2 5
  digest "$name profile" "$@" --profile "$work/profile.json"
  digest "$name profile paper" "$@" --profile "$work/profile.json" --strategy paper
  digest "$name dots" "$@" --mode dots
}

variants "qr-code 5" assets/qr-code.bmp --width-mm 5 --origin-mm 10,10
variants "qr-code 30" assets/qr-code.bmp --width-mm 30 --origin-mm 3,4
variants "line-drawing 20" assets/line-drawing.png --width-mm 20 --origin-mm 10,10
variants "text-banner 40" assets/text-banner.png --width-mm 40 --origin-mm 5,20
for f in "$work"/noise-*.bmp "$work"/runs-*.bmp; do
  variants "$(basename "$f") 8" "$f" --width-mm 8 --origin-mm 10,10
  digest "$(basename "$f") 40" "$f" --width-mm 40 --origin-mm 2,2
  digest "$(basename "$f") 40 fast" "$f" --width-mm 40 --origin-mm 2,2 --speed-mm-s 3 --travel-speed-mm-s 4 --acceleration-mm-s2 50
done
for f in assets/drawings/*.dxf assets/drawings/*.svg; do
  digest "$(basename "$f")" "$f" --width-mm 20 --origin-mm 10,10
done
digest "job plate" --job assets/jobs/plate.json
if [ -n "$rings" ]; then
  digest "rings" "$rings" --width-mm 50 --origin-mm 5,5
  digest "rings paper" "$rings" --width-mm 50 --origin-mm 5,5 --strategy paper
fi
