from typing import Any, Dict, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

Window = Tuple[float, float]
Value = Union[str, int, float, bool, Window, None]

__version__: str
KINDS: Tuple[str, str, str]

def tables() -> str: ...

def fixed(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    k: int = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def orbit(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    t0: float = ...,
    v0: float = ...,
    bounces: int = ...,
    skip: int = ...,
    solver: str = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def sweep(
    *,
    table: str = ...,
    alpha: Union[float, Window] = ...,
    r: Union[float, Window] = ...,
    steps: int = ...,
    transient: int = ...,
    keep: int = ...,
    preset: str = ...,
    starts: int = ...,
    lyapunov: bool = ...,
    threads: int = ...,
    **flags: Value,
) -> Dict[str, npt.NDArray[Any]]: ...
def basins(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    grid: str = ...,
    w_max: float = ...,
    transient: int = ...,
    threads: int = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def two_cycle(
    *, table: str = ..., alpha: float = ..., r: float = ..., k: int = ..., **flags: Value
) -> Dict[str, Any]: ...
def lyapunov(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    t0: float = ...,
    v0: float = ...,
    near_fixed_point: bool = ...,
    transient: int = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def continue_branches(
    *,
    table: str = ...,
    r: float = ...,
    alpha: Window = ...,
    from_: str = ...,
    n: int = ...,
    k: int = ...,
    t0: float = ...,
    v0: float = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def manifolds(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    k: int = ...,
    n: int = ...,
    t0: float = ...,
    v0: float = ...,
    length: float = ...,
    which: str = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def certify(
    *,
    table: str = ...,
    alpha: float = ...,
    r: float = ...,
    n: int = ...,
    k: int = ...,
    t0: float = ...,
    v0: float = ...,
    **flags: Value,
) -> Dict[str, Any]: ...
def cascade(*, table: str = ..., r: float = ..., **flags: Value) -> Dict[str, Any]: ...
def curves(
    *, table: str = ..., x: str = ..., y: str = ..., max_period: int = ..., **flags: Value
) -> Dict[str, Any]: ...
def plane(
    *,
    table: str = ...,
    x: str = ...,
    y: str = ...,
    size: str = ...,
    transient: int = ...,
    **flags: Value,
) -> Dict[str, Any]: ...

class System:
    table: str
    table_name: str
    alpha: float
    r: float
    kappa_c: float
    def __init__(
        self, table: str = ..., alpha: Optional[float] = ..., r: Optional[float] = ...
    ) -> None: ...
    def fixed(self, **flags: Value) -> Dict[str, Any]: ...
    def two_cycle(self, **flags: Value) -> Dict[str, Any]: ...
    def orbit(self, **flags: Value) -> Dict[str, Any]: ...
    def lyapunov(self, **flags: Value) -> Dict[str, Any]: ...
    def basins(self, **flags: Value) -> Dict[str, Any]: ...
