"""The bouncing ball system's exact impact map from Python.

Every function takes the flags of the ``bouncemap`` command of the same name as
keyword arguments (``--w-max`` is ``w_max=``; a window is a pair ``(lo, hi)``; a
flag without a value is ``True``), checked by the same rules as the command line: a
bad argument raises ``ValueError`` with the command's one-line message. Results come
back as numpy arrays and dicts. Long computations run on all cores with the GIL
released; Ctrl-C (KeyboardInterrupt) cancels them.

    >>> import bouncemap
    >>> o = bouncemap.orbit(table="fd:0.1", alpha=0.45, r=0.8, bounces=1000)
    >>> d = bouncemap.sweep(table="fd:0.1", alpha=(0.45, 0.6), steps=200)
"""

import json

import numpy as np

from . import _bouncemap

__all__ = [
    "tables",
    "System",
    "fixed",
    "two_cycle",
    "orbit",
    "lyapunov",
    "continue_branches",
    "cascade",
    "manifolds",
    "certify",
    "sweep",
    "plane",
    "basins",
    "curves",
    "KINDS",
    "__version__",
]

__version__ = _bouncemap.VERSION

#: The event kinds of an orbit, by their code in ``orbit(...)["kind_code"]``.
KINDS = ("impact", "stick", "release")


def tables():
    """The built-in tables, as ``table=`` names them: ``sine``, ``quad``, ``cubic``,
    and ``fd:D`` (the paper's F_D, D in [0, 1]). A table file is given by its path
    (``table="my.toml"``, its parameters as ``"my.toml:w=0.3"``; the file's format is
    in docs/commands.md)."""
    return _bouncemap.TABLES


def _value(v):
    """A keyword argument's value as the command line writes it."""
    if isinstance(v, (tuple, list)) and len(v) == 2:
        return f"{_value(v[0])}..{_value(v[1])}"
    if isinstance(v, float):
        # repr is the shortest text that reads back to the same double.
        return repr(v)
    return str(v)


def _argv(command, flags):
    """The command line of ``command`` with ``flags`` (keyword arguments)."""
    argv = [command]
    for key, v in flags.items():
        if v is None or v is False:
            continue
        # A trailing underscore frees a Python keyword: from_= is --from.
        flag = "--" + key.rstrip("_").replace("_", "-")
        if v is True:
            argv.append(flag)
        else:
            argv.extend([flag, _value(v)])
    return argv


def fixed(**flags):
    """The (1, k) solutions of one system, as ``bouncemap fixed --format json``.

    Flags: ``table``, ``alpha``, ``r``, ``k``. Returns a dict: ``kappa_c``,
    ``solutions`` (each with ``phase``, ``v``, ``stable``, eigenvalues),
    ``alpha_birth``, ``alpha_pd`` and the stability ``windows``.
    """
    return json.loads(_bouncemap.fixed(_argv("fixed", flags)))


def orbit(**flags):
    """Iterate the exact impact map: the events of one orbit.

    Flags as ``bouncemap orbit``: ``table``, ``alpha``, ``r``, ``t0``, ``v0``,
    ``bounces``, ``skip``, ``solver``. Returns a dict of arrays, one entry per event:
    ``period`` (int64, the integer part of the time), ``phase``, ``v`` (after the
    event), ``vrel`` (relative velocity at contact), ``kind_code`` (uint8: 0 impact,
    1 stick, 2 release; ``KINDS`` names them), ``kind`` (their names), and ``halt``:
    why the orbit ended before ``bounces`` events (the ball at rest for good, no
    landing), or None.
    """
    period, phase, v, vrel, kind, halt = _bouncemap.orbit(_argv("orbit", flags))
    return {
        "period": period,
        "phase": phase,
        "v": v,
        "vrel": vrel,
        "kind_code": kind,
        "kind": np.array(KINDS)[kind] if len(kind) else np.array([], dtype="<U7"),
        "halt": halt,
    }


def sweep(**flags):
    """A bifurcation diagram: the columns of ``bouncemap sweep --format csv``.

    Flags as ``bouncemap sweep`` (``table``, ``alpha`` or ``r`` or a table
    parameter as a window ``(lo, hi)``, ``steps``, ``transient``, ``keep``,
    ``preset``, ``starts``, ``lyapunov``, ``threads``, ...). Returns a dict of
    arrays, one entry per recorded point: ``index``, the swept parameter (``alpha``,
    ``r``, ``d``, ...), ``phase``, ``v``, ``kind``, ``period`` and ``table_periods``
    (0 where empty), ``status``, ``sticking``, ``resolved`` (1, 0, or -1 where
    empty), ``growth_decades`` (NaN where empty), and with ``lyapunov=True`` and
    ``starts`` their columns.
    """
    d = _bouncemap.sweep(_argv("sweep", flags))
    for key in ("kind", "status"):
        d[key] = np.array(d[key], dtype=str)
    return d


def basins(**flags):
    """Basins of attraction: which attractor each start ends on.

    Flags as ``bouncemap basins`` (``table``, ``alpha``, ``r``, ``grid`` as
    ``"NXxNY"``, ``w_max``, ``transient``, ``threads``). Returns a dict: ``labels``,
    a (ny, nx) array of attractor numbers (1 = the largest basin, 0 where a start
    was not run to an attractor), row j at w0 = (j + 1/2) W / ny and column i at
    t0 = (i + 1/2) / nx; and the fields of ``bouncemap basins --format json``
    (``attractors`` with each one's ``kind``, ``events``, ``periods``, ``fraction``,
    ...; ``w_max``, ``grid``, ...).
    """
    labels, doc = _bouncemap.basins(_argv("basins", flags))
    out = json.loads(doc)
    out["labels"] = labels
    return out


def _json(command, flags):
    """The json ``bouncemap COMMAND --format json`` writes for ``flags``, read."""
    for own in ("format", "out"):
        if own in flags:
            raise ValueError(
                f"{own}: the function returns the json's values; valid without {own}"
            )
    return json.loads(_bouncemap.run_command(_argv(command, flags) + ["--format", "json"]))


def two_cycle(**flags):
    """The (2, 2k) solution born at the (1, k) solution's period doubling, as
    ``bouncemap two-cycle --format json``: ``found``, ``two_cycle`` (its two impacts,
    multipliers, stability, and the map's confirming run), ``border_collision``.

    Flags: ``table``, ``alpha``, ``r``, ``k``.
    """
    return _json("two-cycle", flags)


def lyapunov(**flags):
    """The Lyapunov exponents of one orbit, as ``bouncemap lyapunov --format json``.

    Flags: ``table``, ``alpha``, ``r``, ``t0``, ``v0``, ``near_fixed_point``,
    ``transient``, ``impacts``, ... Returns the json's dict (``result`` with the
    exponents per impact and per period, their errors, the attractor found).
    """
    return _json("lyapunov", flags)


def continue_branches(**flags):
    """Periodic branches followed in α by pseudo-arclength continuation, as
    ``bouncemap continue --format json``: ``branches``, each with its points (α,
    phases, velocities, multipliers, stability) and special points (folds, period
    doublings, border collisions, grazings).

    Flags as ``bouncemap continue`` (``table``, ``r``, ``alpha`` window, ``from_``
    (``--from``: a Python keyword), ``k``, ``n``, ``t0``, ``v0``, ``max_period``).
    """
    return _json("continue", flags)


def cascade(**flags):
    """The period-doubling cascade and Feigenbaum's δ, as ``bouncemap cascade
    --format json``. Flags as ``bouncemap cascade``."""
    return _json("cascade", flags)


def manifolds(**flags):
    """The unstable and stable manifolds of a saddle cycle, as ``bouncemap
    manifolds --format json``: the saddle, its multipliers, and ``manifolds``, each
    with its kind (``manifold``: ``unstable`` or ``stable``), the map it is grown
    under (its growth factor ``multiplier`` and ``direction``) and both
    ``branches``, each with its ``points`` [[t, phase, v], ...] from the saddle
    out, its ``length`` and its ``end``.

    Flags as ``bouncemap manifolds`` (``table``, ``alpha``, ``r``, ``k``, or ``n``,
    ``k``, ``t0``, ``v0`` for an (n, k) saddle; ``length``; ``which`` =
    ``"unstable"``, ``"stable"`` or ``"both"``).
    """
    return _json("manifolds", flags)


def certify(**flags):
    """A proof of an (n, k) cycle by interval arithmetic, as ``bouncemap certify
    --format json``: ``verdict`` (``"proved"`` or ``"not_proved"``), ``reason`` and
    ``message`` when not proved, the parameters' enclosures ``alpha_enclosure`` and
    ``r_enclosure``, Newton's ``cycle``, the ``box`` ([lo, hi] of every phase and
    velocity, the landings' ``impact_speeds``, its ``width``) and ``stability``
    (``verdict`` ``"stable"``, ``"unstable"`` or ``"undecided"``, the enclosures of
    ``trace``, ``det``, ``pd_test``, ``fold_test`` and the ``multipliers``).

    Flags as ``bouncemap certify`` (``table``, ``alpha``, ``r``, ``n``, ``k``, and
    optionally ``t0`` with ``v0``).
    """
    return _json("certify", flags)


def curves(**flags):
    """Two-parameter curves of special points (period doubling, fold, border
    collision, grazing) and their codimension-two points, as ``bouncemap curves
    --format json``. Flags as ``bouncemap curves`` (``table``, ``x``, ``y``,
    ``max_period``, ``seeds``, ...)."""
    return _json("curves", flags)


def plane(**flags):
    """A two-parameter map: ``bouncemap plane``'s pixels as (ny, nx) arrays.

    Flags as ``bouncemap plane`` (``table``, ``x="alpha:LO..HI"``,
    ``y="d:LO..HI"`` or ``"r:LO..HI"``, ``size="NXxNY"``, ``transient``, ...).
    Returns the settings of ``bouncemap plane --format json`` (``table``, ``x``,
    ``y``, ``r``, ``transient``, ...), its analytic ``curves``, and arrays indexed
    [j, i] (row j up the y axis, column i along x): ``x_values``, ``y_values`` (the
    axes' values), ``class`` and ``status`` (str), ``period`` and ``table_periods``
    (0 where empty), ``lyapunov`` (NaN where empty, -inf for a cycle that sticks),
    ``resolved`` (1, 0, -1 where empty) and ``growth_decades`` (NaN where empty).
    Runs on every core; Ctrl-C cancels it.
    """
    d = _bouncemap.plane(_argv("plane", flags))
    doc = json.loads(d["header"])
    doc["curves"] = json.loads(d["curves"])
    nx, ny = doc["x"]["n"], doc["y"]["n"]

    def grid(a, dtype=None):
        return np.asarray(a, dtype=dtype).reshape(ny, nx)

    doc["x_values"] = grid(d["x"])[0]
    doc["y_values"] = grid(d["y"])[:, 0]
    doc["class"] = grid(d["class"], str)
    doc["status"] = grid(d["status"], str)
    for key in ("period", "table_periods", "lyapunov", "resolved", "growth_decades"):
        doc[key] = grid(d[key])
    return doc


class System:
    """One system: a table, alpha and r, checked as the command line checks them.

    ``table`` is a built-in name (``sine``, ``quad``, ``cubic``, ``fd:D``) or a table
    file (``PATH.toml``, its parameters as ``PATH.toml:w=0.3``); ``alpha`` and ``r``
    left as None take the commands' defaults. A bad value raises ``ValueError`` with
    the command's message. The methods are the module's functions for this system::

        >>> s = bouncemap.System("fd:0.1", alpha=0.45, r=0.8)
        >>> s.kappa_c, s.fixed()["alpha_pd"]
        >>> o = s.orbit(t0=0.19, v0=0.51, bounces=1000)
    """

    def __init__(self, table="fd:0.1", alpha=None, r=None):
        self.table, self.alpha, self.r = table, alpha, r
        doc = fixed(**self._flags({}))
        #: The table as the outputs name it, alpha and r as read, and kappa_c.
        self.table_name = doc["table"]
        self.alpha, self.r = doc["alpha"], doc["r"]
        self.kappa_c = doc["kappa_c"]

    def _flags(self, flags):
        own = {"table": self.table, "alpha": self.alpha, "r": self.r}
        clash = sorted(set(own) & set(flags))
        if clash:
            raise ValueError(f"{clash[0]}: the system's own; valid without {clash[0]}")
        return {**own, **flags}

    def __repr__(self):
        return f"System({self.table!r}, alpha={self.alpha!r}, r={self.r!r})"

    def fixed(self, **flags):
        """``fixed`` of this system."""
        return fixed(**self._flags(flags))

    def two_cycle(self, **flags):
        """``two_cycle`` of this system."""
        return two_cycle(**self._flags(flags))

    def orbit(self, **flags):
        """``orbit`` of this system."""
        return orbit(**self._flags(flags))

    def lyapunov(self, **flags):
        """``lyapunov`` of this system."""
        return lyapunov(**self._flags(flags))

    def basins(self, **flags):
        """``basins`` of this system."""
        return basins(**self._flags(flags))
