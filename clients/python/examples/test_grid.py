#!/usr/bin/env python3
"""A speed x frequency test grid, run from a script: one small mark per cell, each cell's run log collected.

    python3 examples/test_grid.py --speeds 1,2,4 --frequencies 1000,2000,5000 --out grid-logs

Each cell is the same mark (a generated 12 x 12 px square with a cross, or --image FILE), --size mm wide, placed on a
grid from --origin with --gap mm between cells; row r takes the r-th burn speed, column c the c-th laser frequency.
The app must be running (its connection.json names it); --simulator connects the built-in simulator first, else the
machine must already be connected. Every cell's JSON record goes to --out as r{row}c{col}.json, with a summary.csv.
"""

import argparse
import csv
import json
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from laserengrave import ApiError, LaserEngrave, RunError  # noqa: E402


def numbers(text):
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': numbers separated by commas, e.g. 1,2,4") from None
    if not values:
        raise argparse.ArgumentTypeError(f"'{text}': at least one number")
    return values


def test_mark(folder, size=12):
    """A square outline with a cross as a plain PBM (black = burn): small, so each cell runs in seconds."""
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            edge = x in (0, size - 1) or y in (0, size - 1)
            cross = x == y or x == size - 1 - y
            row.append("1" if edge or cross else "0")
        rows.append(" ".join(row))
    path = os.path.join(folder, "grid-mark.pbm")
    with open(path, "w", encoding="ascii") as f:
        f.write(f"P1\n{size} {size}\n" + "\n".join(rows) + "\n")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--speeds", type=numbers, default=[1.0, 2.0], help="burn speeds, mm/s, one a row (default 1,2)")
    parser.add_argument("--frequencies", type=numbers, default=[1000.0, 5000.0], help="laser frequencies, Hz, one a column (default 1000,5000)")
    parser.add_argument("--size", type=float, default=1.0, help="each cell's width, mm (default 1)")
    parser.add_argument("--gap", type=float, default=0.5, help="space between cells, mm (default 0.5)")
    parser.add_argument("--origin", type=numbers, default=[1.0, 1.0], help="the first cell's top-left corner X,Y in mm (default 1,1)")
    parser.add_argument("--image", help="the mark to burn in each cell (default: a generated square with a cross)")
    parser.add_argument("--sample", default="grid", help="sample ID prefix; each cell's is PREFIX-r{row}c{col}")
    parser.add_argument("--simulator", action="store_true", help="connect the built-in simulator first")
    parser.add_argument("--connection", help="the app's connection.json (default: the app's data folder)")
    parser.add_argument("--out", default="grid-logs", help="folder for each cell's JSON record and summary.csv")
    args = parser.parse_args()
    if len(args.origin) != 2:
        parser.error("--origin: X,Y in mm")

    started = time.monotonic()
    try:
        app = LaserEngrave.from_connection_file(args.connection)
        with tempfile.TemporaryDirectory() as folder:
            app.upload(args.image or test_mark(folder))
        app.set_job(widthMm=args.size, originXMm=args.origin[0], originYMm=args.origin[1])
        if args.simulator:
            app.connect(simulator=True)
        os.makedirs(args.out, exist_ok=True)
        cells = []
        for r, speed in enumerate(args.speeds):
            for c, frequency in enumerate(args.frequencies):
                x = args.origin[0] + c * (args.size + args.gap)
                y = args.origin[1] + r * (args.size + args.gap)
                state = app.set_job(originXMm=round(x, 3), originYMm=round(y, 3), burnSpeedMmPerS=speed, laserFrequencyHz=frequency)
                sample = f"{args.sample}-r{r}c{c}"
                print(f"cell r{r}c{c}: {speed:g} mm/s, {frequency:g} Hz at X {x:g} Y {y:g} mm, estimated {state['estimate']['seconds']:.1f} s")

                shown = set()

                def progress(run, cell=f"r{r}c{c}", shown=shown):
                    # A line when the state changes and at each fifth of the way, so a log file stays readable.
                    step = (run["state"], int(run["percent"] // 20))
                    if step not in shown:
                        shown.add(step)
                        print(f"  {cell} {run['state'].lower()} {run['percent']:.0f} %", flush=True)

                try:
                    run = app.run(sample_id=sample, notes=f"test grid {speed:g} mm/s x {frequency:g} Hz", progress=progress)
                    outcome, error = run["outcome"], ""
                except RunError as e:
                    run, outcome, error = e.run, (e.run or {}).get("outcome", "not run"), str(e)
                print(f"  r{r}c{c} {outcome}{': ' + error if error else ''}")
                log = None
                if run:
                    log = os.path.join(args.out, f"r{r}c{c}.json")
                    with open(log, "w", encoding="utf-8") as f:
                        json.dump(app.export_log(run["path"]), f, indent=2)
                cells.append({"row": r, "column": c, "burnSpeedMmPerS": speed, "laserFrequencyHz": frequency,
                              "originXMm": round(x, 3), "originYMm": round(y, 3), "outcome": outcome,
                              "seconds": run["actualSeconds"] if run else "", "log": log or "", "error": error})
        with open(os.path.join(args.out, "summary.csv"), "w", newline="", encoding="utf-8") as f:
            writer = csv.DictWriter(f, fieldnames=list(cells[0]))
            writer.writeheader()
            writer.writerows(cells)
    except ApiError as e:
        print(f"test_grid: {e.message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ntest_grid: interrupted: aborting the run under way", file=sys.stderr)
        try:
            app.abort()
        except (ApiError, NameError):
            pass
        return 130

    done = sum(1 for c in cells if c["outcome"] == "completed")
    print(f"{done} of {len(cells)} cells completed in {time.monotonic() - started:.1f} s; logs in {args.out}")
    return 0 if done == len(cells) else 1


if __name__ == "__main__":
    sys.exit(main())
