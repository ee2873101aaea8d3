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

__all__ = ["fixed", "orbit", "sweep", "basins", "KINDS", "__version__"]

__version__ = _bouncemap.VERSION

#: The event kinds of an orbit, by their code in ``orbit(...)["kind_code"]``.
KINDS = ("impact", "stick", "release")


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
        flag = "--" + key.replace("_", "-")
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
