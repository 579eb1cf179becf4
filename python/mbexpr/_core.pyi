# Hand-written stubs of the extension module (maturin's generated ones type
# numpy arguments as Incomplete). The public API is mbexpr/__init__.py.
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from . import Diagnostic

class Error(ValueError):
    """A refusal with its place (line and column from 1, or None): the
    first problem's, and every problem in ``errors``."""

    message: str
    line: Optional[int]
    column: Optional[int]
    errors: List[Diagnostic]
    point: int

class Program:
    def __init__(self, text: str, inputs: List[str]) -> None: ...
    @property
    def text(self) -> str: ...
    @property
    def inputs(self) -> List[str]: ...
    def evaluate(
        self,
        columns: Sequence[npt.NDArray[np.float64]],
        wrt: List[int],
        order: int,
        threads: int,
    ) -> Tuple[
        npt.NDArray[np.float64],
        npt.NDArray[np.float64],
        npt.NDArray[np.float64],
        npt.NDArray[np.int32],
    ]: ...
    def explain(self, point: List[float], wrt: List[int], order: int) -> None: ...

def utility_bulk(
    name: str, columns: Sequence[npt.NDArray[np.float64]], iord: int
) -> npt.NDArray[np.float64]: ...
def check_model(path: str) -> List[Diagnostic]: ...
# (method, end, steps, rtol, atol, h_max, max_steps)
RunSettings = Tuple[
    str, Optional[float], Optional[int], float, Optional[float], Optional[float], Optional[int]
]

def check_settings(format: Optional[str], settings: RunSettings) -> None: ...
def simulate(
    source: str,
    is_path: bool,
    format: str,
    settings: RunSettings,
) -> Tuple[
    List[str],
    npt.NDArray[np.float64],
    List[Tuple[float, str, str, str, int, int]],
    Dict[str, object],
]: ...
