#!/usr/bin/env python3
"""Where the suite's time goes (issue 38): each TRX file's wall time and the slowest test classes by the sum of their
tests' durations.  tools/suite-times.py FOLDER_WITH_TRX_FILES [N]"""
import collections
import glob
import re
import sys
from datetime import datetime


def seconds(duration):
    h, m, s = duration.split(":")
    return int(h) * 3600 + int(m) * 60 + float(s)


def when(stamp):
    # TRX stamps carry 7 decimal places; Python's fromisoformat takes at most 6.
    return datetime.fromisoformat(re.sub(r"(\.\d{6})\d+", r"\1", stamp))


classes = collections.Counter()
for trx in sorted(glob.glob(sys.argv[1] + "/*.trx")):
    text = open(trx, encoding="utf-8").read()
    times = re.search(r'<Times [^>]*start="([^"]+)"[^>]*finish="([^"]+)"', text)
    wall = (when(times.group(2)) - when(times.group(1))).total_seconds() if times else 0
    print(f"suite time: {wall:6.1f} s  {trx.rsplit('/', 1)[1][:-4]} (wall)")
    for name, duration in re.findall(r'<UnitTestResult [^>]*testName="([^"]+)"[^>]*duration="([^"]+)"', text):
        classes[name.split("(")[0].rsplit(".", 1)[0]] += seconds(duration)
for name, total in classes.most_common(int(sys.argv[2]) if len(sys.argv) > 2 else 12):
    print(f"suite time: {total:6.1f} s  {name}")
