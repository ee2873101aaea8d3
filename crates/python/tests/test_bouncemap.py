"""The Python module against the command line and closed forms.

Run on the module built from the checkout (``maturin develop`` or ``pip install
crates/python``), with ``BOUNCEMAP_BIN`` the ``bouncemap`` binary of the same
checkout (default: ``target/release/bouncemap``).
"""

import _thread
import csv
import io
import json
import math
import os
import pathlib
import subprocess
import threading
import time

import numpy as np
import pytest

import bouncemap

ROOT = pathlib.Path(__file__).resolve().parents[3]
BIN = os.environ.get("BOUNCEMAP_BIN", str(ROOT / "target" / "release" / "bouncemap"))


def command(*args):
    """The binary's (status, stdout, stderr) for ``args``."""
    p = subprocess.run([BIN, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def test_the_one_one_orbit_is_fixeds_closed_form():
    # The (1, 1) solution in closed form: v* = k/2 = 1/2 (a flight of one period) and
    # its phase t* where alpha F'(t*) = (1 - r)/(1 + r) v*, as `fixed` solves it; an
    # orbit started near it converges to it (stable at this alpha).
    f = bouncemap.fixed(table="fd:0.1", alpha=0.45, r=0.8)
    stable = [s for s in f["solutions"] if s["classification"] == "stable"]
    assert len(stable) == 1
    t, v = stable[0]["phase"], stable[0]["v"]
    assert v == 0.5
    o = bouncemap.orbit(table="fd:0.1", alpha=0.45, r=0.8, t0=t + 1e-3, v0=0.5 + 1e-3, bounces=4000)
    assert o["halt"] is None
    assert len(o["phase"]) == 4000
    assert set(o["kind"][-100:]) == {"impact"}
    assert abs(o["phase"][-1] - t) < 1e-9
    assert abs(o["v"][-1] - v) < 1e-9
    # One period per flight on the cycle.
    assert np.all(np.diff(o["period"][-100:]) == 1)


def test_orbit_arrays_equal_the_commands_csv():
    flags = dict(table="cubic", alpha=0.47, r=0.8, t0=0.1, v0=0.7, bounces=3000)
    o = bouncemap.orbit(**flags)
    status, out, err = command(
        "orbit", "--table", "cubic", "--alpha", "0.47", "--r", "0.8", "--t0", "0.1",
        "--v0", "0.7", "--bounces", "3000", "--format", "csv",
    )
    assert status == 0, err
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == len(o["phase"])
    for i, row in enumerate(rows):
        assert int(row["period"]) == o["period"][i]
        assert float(row["phase"]) == o["phase"][i]
        assert float(row["v"]) == o["v"][i]
        assert float(row["vrel"]) == o["vrel"][i]
        assert row["kind"] == o["kind"][i]


def test_sweep_arrays_equal_the_commands_csv_value_for_value():
    args = ["--table", "fd:0.1", "--alpha", "0.45..0.6", "--steps", "40",
            "--transient", "2000", "--keep", "8", "--lyapunov"]
    d = bouncemap.sweep(table="fd:0.1", alpha=(0.45, 0.6), steps=40, transient=2000,
                        keep=8, lyapunov=True)
    status, out, err = command("sweep", *args, "--format", "csv")
    assert status == 0, err
    text = "\n".join(line for line in out.splitlines() if not line.startswith("#"))
    rows = list(csv.DictReader(io.StringIO(text)))
    assert len(rows) == len(d["index"]) > 40

    def num(s, empty):
        return empty if s == "" else float(s)

    for i, row in enumerate(rows):
        assert int(row["index"]) == d["index"][i]
        assert float(row["alpha"]) == d["alpha"][i]
        for key in ("phase", "v", "growth_decades"):
            a, b = num(row[key], math.nan), d[key][i]
            assert (math.isnan(a) and math.isnan(b)) or a == b, (key, i)
        lyap = row["lyapunov"]
        got = d["lyapunov"][i]
        if lyap == "":
            assert math.isnan(got)
        elif lyap == "-inf":
            assert got == -math.inf
        else:
            assert float(lyap) == got
        assert row["kind"] == d["kind"][i]
        assert row["status"] == d["status"][i]
        assert int(num(row["period"], 0)) == d["period"][i]
        assert int(num(row["table_periods"], 0)) == d["table_periods"][i]
        assert (row["sticking"] == "true") == bool(d["sticking"][i])
        assert {"true": 1, "false": 0, "": -1}[row["resolved"]] == d["resolved"][i]


def test_basins_fractions_sum_to_one_and_equal_the_commands():
    b = bouncemap.basins(table="cubic", alpha=0.47, r=0.8, grid="40x30")
    fractions = [a["fraction"] for a in b["attractors"]]
    assert len(fractions) >= 2
    assert abs(sum(fractions) - 1.0) < 1e-12
    status, out, err = command("basins", "--table", "cubic", "--alpha", "0.47", "--r", "0.8",
                               "--grid", "40x30", "--format", "json")
    assert status == 0, err
    theirs = json.loads(out)
    assert [a["fraction"] for a in theirs["attractors"]] == fractions
    assert [a["kind"] for a in theirs["attractors"]] == [a["kind"] for a in b["attractors"]]
    # The labels: each attractor's share of the grid is its fraction, and the grid is
    # the command's csv, start by start.
    labels = b["labels"]
    assert labels.shape == (30, 40)
    for a in b["attractors"]:
        assert np.count_nonzero(labels == a["id"]) == round(a["fraction"] * 1200)
    status, out, err = command("basins", "--table", "cubic", "--alpha", "0.47", "--r", "0.8",
                               "--grid", "40x30", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [int(r["attractor"] or 0) for r in rows] == labels.ravel().tolist()
    w = b["w_max"]
    assert float(rows[41]["t0"]) == pytest.approx(1.5 / 40)
    assert float(rows[41]["w0"]) == pytest.approx(1.5 * w / 30)


@pytest.mark.parametrize(
    "call, args",
    [
        (lambda: bouncemap.orbit(r=1.5), ["orbit", "--r", "1.5"]),
        (lambda: bouncemap.sweep(alpha=(0.6, 0.4)), ["sweep", "--alpha", "0.6..0.4"]),
        (lambda: bouncemap.basins(grid="0x10"), ["basins", "--grid", "0x10"]),
        (lambda: bouncemap.fixed(table="nosuch"), ["fixed", "--table", "nosuch"]),
        (lambda: bouncemap.sweep(stepz=3), ["sweep", "--stepz", "3"]),
    ],
)
def test_a_bad_argument_raises_value_error_with_the_commands_message(call, args):
    status, _, err = command(*args)
    assert status == 2
    message = err.strip()
    assert message.startswith("error: ")
    with pytest.raises(ValueError) as e:
        call()
    assert str(e.value) == message[len("error: "):]


@pytest.mark.parametrize(
    "long_job",
    [
        lambda: bouncemap.sweep(table="sine", alpha=(0.3, 0.6), steps=200000,
                                transient=1000000),
        lambda: bouncemap.plane(table="fd", x="alpha:0.45..0.6", y="d:0..1",
                                size="400x400", transient=1000000),
    ],
)
def test_a_long_job_stops_at_ctrl_c_within_a_second(long_job):
    fired = []

    def interrupt():
        fired.append(time.monotonic())
        _thread.interrupt_main()

    timer = threading.Timer(0.5, interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        long_job()
    stopped = time.monotonic()
    timer.join()
    assert fired and stopped - fired[0] < 1.0


def test_the_readme_example_runs(tmp_path, monkeypatch, capsys):
    text = (ROOT / "README.md").read_text()
    section = text.split("## From Python", 1)[1]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    first = capsys.readouterr().out.splitlines()[0].split()
    phase, v, closed = (float(x) for x in first)
    assert abs(phase - closed) < 1e-9 and abs(v - 0.5) < 1e-9


@pytest.mark.parametrize(
    "call, args",
    [
        (lambda: bouncemap.two_cycle(table="fd:0.1", alpha=0.52, r=0.8),
         ["two-cycle", "--table", "fd:0.1", "--alpha", "0.52", "--r", "0.8"]),
        (lambda: bouncemap.lyapunov(table="cubic", alpha=0.47, near_fixed_point=True),
         ["lyapunov", "--table", "cubic", "--alpha", "0.47", "--near-fixed-point"]),
        (lambda: bouncemap.continue_branches(table="fd:0.1", alpha=(0.45, 0.55), from_="fixed"),
         ["continue", "--table", "fd:0.1", "--alpha", "0.45..0.55", "--from", "fixed"]),
        (lambda: bouncemap.manifolds(table="fd:0.1", alpha=0.45, length=0.5),
         ["manifolds", "--table", "fd:0.1", "--alpha", "0.45", "--length", "0.5"]),
        (lambda: bouncemap.manifolds(table="cubic", alpha=0.47, length=0.3, which="stable"),
         ["manifolds", "--table", "cubic", "--alpha", "0.47", "--length", "0.3",
          "--which", "stable"]),
        (lambda: bouncemap.certify(table="fd:1", alpha=0.52, n=2, k=2),
         ["certify", "--table", "fd:1", "--alpha", "0.52", "--n", "2", "--k", "2"]),
        (lambda: bouncemap.cascade(table="sine", depth=2, certify=True),
         ["cascade", "--table", "sine", "--depth", "2", "--certify"]),
    ],
)
def test_the_json_commands_give_the_commands_json(call, args):
    status, out, err = command(*args, "--format", "json")
    assert status == 0, err
    assert call() == json.loads(out)


def test_plane_arrays_equal_the_commands_csv():
    p = bouncemap.plane(table="fd", x="alpha:0.45..0.6", y="d:0..1", size="12x5",
                        transient=2000)
    status, out, err = command("plane", "--table", "fd", "--x", "alpha:0.45..0.6", "--y",
                               "d:0..1", "--size", "12x5", "--transient", "2000",
                               "--format", "csv")
    assert status == 0, err
    text = "\n".join(line for line in out.splitlines() if not line.startswith("#"))
    rows = list(csv.DictReader(io.StringIO(text)))
    assert p["class"].shape == (5, 12) and len(rows) == 60
    for k, row in enumerate(rows):
        j, i = divmod(k, 12)
        assert float(row["alpha"]) == p["x_values"][i]
        assert float(row["D"]) == p["y_values"][j]
        assert row["class"] == p["class"][j, i]
        assert int(row["period"] or 0) == p["period"][j, i]
        lyap = {"": math.nan, "-inf": -math.inf}.get(row["lyapunov"])
        got = p["lyapunov"][j, i]
        if lyap is None:
            assert float(row["lyapunov"]) == got
        else:
            assert (math.isnan(lyap) and math.isnan(got)) or lyap == got


def test_format_and_out_are_the_commands_own():
    with pytest.raises(ValueError, match="format: the function returns"):
        bouncemap.two_cycle(format="csv")


def test_a_system_is_checked_once_and_its_methods_are_the_functions():
    s = bouncemap.System("fd:0.1", alpha=0.45, r=0.8)
    assert (s.table_name, s.alpha, s.r) == ("fd:0.1", 0.45, 0.8)
    assert s.kappa_c == bouncemap.fixed(table="fd:0.1", alpha=0.45, r=0.8)["kappa_c"]
    a = s.orbit(t0=0.19, v0=0.51, bounces=500)
    b = bouncemap.orbit(table="fd:0.1", alpha=0.45, r=0.8, t0=0.19, v0=0.51, bounces=500)
    assert np.array_equal(a["phase"], b["phase"]) and np.array_equal(a["v"], b["v"])
    status, _, err = command("fixed", "--r", "1.5")
    with pytest.raises(ValueError) as e:
        bouncemap.System(r=1.5)
    assert str(e.value) == err.strip()[len("error: "):]
    with pytest.raises(ValueError, match="alpha: the system's own"):
        s.orbit(alpha=0.5)


def test_the_tables_named_are_the_ones_the_functions_take():
    # The piecewise quadratic and cubic tables are F_D's ends, named so in outputs.
    names = bouncemap.tables()
    for name, shown in (("sine", "sine"), ("quad", "fd:0"), ("cubic", "fd:1")):
        assert name in names
        assert bouncemap.System(name, alpha=0.3).table_name == shown
    assert "fd:D" in names
    assert bouncemap.System("fd:0.25", alpha=0.3).table_name == "fd:0.25"
