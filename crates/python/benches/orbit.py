"""10^6 events of one orbit from Python against the command that writes them.

    python crates/python/benches/orbit.py [BOUNCEMAP_BIN]

Median of 5 runs each: `bouncemap orbit --bounces 1000000 --format csv` into
/dev/null (the process, start to end), and `bouncemap.orbit(bounces=1000000)` in this
interpreter (the call, arrays made). Prints both and their ratio.
"""

import os
import pathlib
import statistics
import subprocess
import sys
import time

import bouncemap

ROOT = pathlib.Path(__file__).resolve().parents[3]
BIN = sys.argv[1] if len(sys.argv) > 1 else os.environ.get(
    "BOUNCEMAP_BIN", str(ROOT / "target" / "release" / "bouncemap"))
FLAGS = dict(table="fd:0.5", alpha=0.6, r=0.8, bounces=1_000_000)
ARGS = ["orbit", "--table", "fd:0.5", "--alpha", "0.6", "--r", "0.8",
        "--bounces", "1000000", "--format", "csv"]


def timed(f, runs=5):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def command():
    with open(os.devnull, "w") as null:
        subprocess.run([BIN, *ARGS], stdout=null, check=True)


def python():
    o = bouncemap.orbit(**FLAGS)
    assert len(o["phase"]) == FLAGS["bounces"]


cmd, py = timed(command), timed(python)
print(f"command (csv to /dev/null): {cmd:.3f} s")
print(f"python  (numpy arrays):     {py:.3f} s")
print(f"python / command:           {py / cmd:.2f}")
