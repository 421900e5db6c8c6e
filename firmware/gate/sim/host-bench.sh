#!/usr/bin/env bash
# The project's own host against the AVR gate image in simavr, on the wall clock (docs/gate-firmware.md):
#   firmware/gate/sim/host-bench.sh OUT [WIDTH_MM]
# Builds the image and gate_pty, starts the image on a pty (/tmp/simavr-uart0), the stages on `laserengrave simulator`
# through socat ptys, then runs `laser identify`, `laser on 1000 --seconds 1`, `machine check` (its watchdog step
# included), `machine latency --write` into OUT/profile.json and a timed engrave of the QR sample at WIDTH_MM (5 by
# default) with that profile; then `replay` of the run's flight recorder gives what the twin burns for the same stream.
# Every pulse edge of the image goes to OUT/edges.txt ("CYCLE 0|1") and every line it received to OUT/lines.txt ("CYCLE
# TEXT", its last byte's receive-complete). The engrave's part of them is cut into OUT/gate-stream.txt and
# OUT/avr-bursts.txt (sim/pty_bursts.py: every FREQ/OFF/BURST line's pulses and first pulse), which the cycle-exact
# replay in gate_sim must reproduce (differential.py --check) and the twin's differential test compares with the twin
# (GateFirmwareDifferentialTests, when the two files are committed as sim/differential/qr5mm-pty-*). OUT/summary.txt
# gives the outcome, the time and the pulses.
# Needs: make -C firmware/gate, socat, a build of src/LaserEngrave.Cli. Everything it starts is stopped at the end.
set -u
root=$(cd "$(dirname "$0")/../../.." && pwd)
out=${1:?give the output folder}; width=${2:-5}
mkdir -p "$out"; out=$(cd "$out" && pwd)
CLI=${CLI:-$root/src/LaserEngrave.Cli/bin/Debug/net10.0/laserengrave.dll}
le() { dotnet "$CLI" "$@"; }
make -s -C "$root/firmware/gate" avr pty build/gate_sim >/dev/null || exit 1
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; }
trap cleanup EXIT
# The simulated gate and stages stand for a chip and controllers, which never pause, and a lab's host computer runs
# nothing else: real-time priority for them and the engrave when allowed (RT_PRIO=0 to run without), so that other
# processes on a shared computer do not hold up a reply (the socat relays too) (gate.log says how far the gate ever fell behind the wall
# clock). The kernel keeps 5 % of the CPU for the others whatever happens (sched_rt_runtime_us).
prio=(); [ "${RT_PRIO:-1}" = 1 ] && chrt -f 10 true 2>/dev/null && prio=(chrt -f 10)
rr=(); [ ${#prio[@]} -gt 0 ] && rr=(chrt -r 5)
le() { "${rr[@]}" dotnet "$CLI" "$@"; }
"${prio[@]}" "$root/firmware/gate/build/gate_pty" "$root/firmware/gate/build/atmega328p/gate.elf" "$out/edges.txt" "$out/lines.txt" 2> "$out/gate.log" & pids+=($!)
"${prio[@]}" socat pty,raw,echo=0,link=/tmp/hb-stage pty,raw,echo=0,link=/tmp/hb-stage-host 2>/dev/null & pids+=($!)
"${prio[@]}" socat pty,raw,echo=0,link=/tmp/hb-laser pty,raw,echo=0,link=/tmp/hb-laser-host 2>/dev/null & pids+=($!)
sleep 1
echo '{"startMm": 1}' > "$out/sim.json"
# Not through le: a function in the background is a subshell, and killing it would leave the simulator running.
"${rr[@]}" dotnet "$CLI" simulator --stage-port /tmp/hb-stage --laser-port /tmp/hb-laser --sim-options "$out/sim.json" > "$out/simulator.log" 2>&1 & pids+=($!)
sleep 4
gate=/tmp/simavr-uart0
{
  le laser --port $gate identify
  le laser --port $gate on 1000 --seconds 1
  le machine check --stage-port /tmp/hb-stage-host --laser-port $gate --yes --count 20
  le machine latency --stage-port /tmp/hb-stage-host --laser-port $gate --profile "$out/profile.json" --write
} 2>&1 | tee "$out/commands.txt"
first=$(wc -l < "$out/lines.txt")
started=$(date +%s.%N)
le engrave "$root/assets/qr-code.bmp" --width-mm "$width" --origin-mm 10,10 --stage-port /tmp/hb-stage-host \
  --laser-port $gate --profile "$out/profile.json" --json --log-dir "$out/logs" > "$out/engrave.json" 2> "$out/engrave.err"
echo "engrave took $(echo "$(date +%s.%N) - $started" | bc) s (wall clock, process start to exit)" > "$out/engrave-time.txt"
log=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['logPath'])" "$out/engrave.json" 2>/dev/null)
[ -n "$log" ] && le replay "$log" --json > "$out/replay.json" 2> "$out/replay.err"
sleep 2
python3 "$root/firmware/gate/sim/pty_bursts.py" "$out/lines.txt" "$out/edges.txt" "$first" "$out/gate-stream.txt" \
  "$out/avr-bursts.txt" "gate lines of engrave assets/qr-code.bmp --width-mm $width with the gate image on gate_pty (sim/host-bench.sh)" \
  | tee "$out/bursts.txt"
# The same stream replayed cycle-exact in gate_sim must fire the same pulses (the first pulse may differ by a few
# instructions: on the pty a byte enters the UART when the pty thread hands it over, in gate_sim at its scripted cycle).
python3 "$root/firmware/gate/sim/differential.py" "$root/firmware/gate/build/gate_sim" \
  "$root/firmware/gate/build/atmega328p/gate.elf" "$out/gate-stream.txt" "$out/replay-bursts.txt" >/dev/null
python3 - "$out" <<'PY' | tee -a "$out/bursts.txt"
import sys
out = sys.argv[1]
rows = lambda p: [l.split() for l in open(p) if not l.startswith("#")]
a, b = rows(f"{out}/avr-bursts.txt"), rows(f"{out}/replay-bursts.txt")
same = len(a) == len(b) and all(x[:3] == y[:3] for x, y in zip(a, b))
d = [abs(int(x[3]) - int(y[3])) for x, y in zip(a, b) if x[3] != "-" and y[3] != "-"]
bursts = [(int(x[1].split("_")[1]), int(x[2])) for x in a if x[1].startswith("BURST")]
print(f"gate_pty against the cycle-exact replay: pulses {'the same for every line' if same else 'DIFFERENT'}, first pulses at most {max(d, default=0)} cycles apart")
print(f"{len(bursts)} bursts: {sum(f == n for n, f in bursts)} fired their count, {sum(f < n for n, f in bursts)} ended sooner by the host's OFF (up to {max((n - f for n, f in bursts), default=0)} pulses), {sum(f > n for n, f in bursts)} more than their count")
PY
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
rows = [l.split() for l in open(f"{out}/edges.txt") if len(l.split()) == 2]
rises = [int(c) for c, v in rows if v == "1"]
run = json.load(open(f"{out}/engrave.json"))
try:
    replay = json.load(open(f"{out}/replay.json"))
except Exception:
    replay = {}
lines = [f"engrave: {run.get('outcome')} {run.get('fault') or ''}".strip(),
         open(f"{out}/engrave-time.txt").read().strip(),
         "the engrave's part: " + open(f"{out}/bursts.txt").read().strip().replace("\n", "; "),
         f"pulses the gate image fired in all (identify, on 1 s, machine check, engrave): {len(rises)}",
         f"the twin's replay of the run's recorded stream: {replay.get('simulation', replay).get('pulses') if replay else 'none'} pulses"]
open(f"{out}/summary.txt", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
