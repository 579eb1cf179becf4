"""mbexpr: multibody-solver function expressions (the Adams dialect) with
exact derivatives over numpy arrays, model files checked and simulated, and
parameter sweeps over any ``concurrent.futures.Executor``.

>>> import mbexpr, numpy as np
>>> force = mbexpr.compile("BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01)", ["x", "v"])
>>> force.value(x=1.005, v=0.7)
array(-52.8453...)
>>> force.gradient(x=np.linspace(-1.1, 1.1, 5), v=0.0).shape
(5, 2)

Every refusal is an :class:`Error` (a ``ValueError``) with the ``line`` and
``column`` it speaks of, and in ``errors`` every problem found (a
compilation or a model's load may find several). Bulk work runs on every core with the GIL
released, on a thread pool of the process (a process forked after it builds
its own, so it does not hang).
"""

from __future__ import annotations

import errno
import os
import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import Error

__all__ = [
    "Error",
    "Program",
    "compile",
    "check_model",
    "Diagnostic",
    "simulate",
    "Simulation",
    "Event",
    "bistop",
    "impact",
    "step",
    "sweep",
    "Sweep",
]

ArrayLike = Union[float, Sequence[float], np.ndarray]


def _columns(values: Sequence[ArrayLike]) -> Tuple[Tuple[int, ...], List[np.ndarray]]:
    """The broadcast shape of ``values`` and each as a 1-D float64 array of
    that many points (a view where numpy can give one; strided views are
    read as they are)."""
    arrays = np.broadcast_arrays(*[np.asarray(v, dtype=np.float64) for v in values])
    shape = arrays[0].shape if arrays else ()
    return shape, [np.ascontiguousarray(a).reshape(-1) if a.ndim != 1 else a for a in arrays]


class Program:
    """An expression compiled for named inputs: immutable, picklable (it
    pickles as its text and inputs and compiles again), shared freely
    between threads.

    Inputs are given by position in the order of :attr:`inputs` or by name,
    as numbers or arrays that broadcast together (numpy rules); the result
    has the broadcast shape. ``threads`` is the number of threads (0, the
    default: every core; 1: the calling thread). The GIL is released while
    the points are evaluated.

    Where a point cannot be evaluated (a domain error such as ``LOG(0)``, an
    overflow, an input that is not finite) the call raises :class:`Error`
    with the index of the first such point and the place of the operation,
    unless ``errors="status"``: then it returns ``(result, status)``, status
    1 where a point failed (its entries 0) and 0 elsewhere. No result is
    ever NaN or infinite.
    """

    __slots__ = ("_program",)

    def __init__(self, text: str, inputs: Sequence[str]):
        self._program = _core.Program(text, list(inputs))

    @property
    def text(self) -> str:
        """The expression's text."""
        return self._program.text

    @property
    def inputs(self) -> List[str]:
        """The input names, in the order positional values are taken."""
        return self._program.inputs

    def __reduce__(self):
        return (Program, (self.text, self.inputs))

    def __repr__(self) -> str:
        return f"mbexpr.compile({self.text!r}, {self.inputs!r})"

    def _points(self, args: Sequence[ArrayLike], kwargs: Dict[str, ArrayLike]):
        names = self.inputs
        if len(args) > len(names):
            raise TypeError(f"{len(args)} values given for {len(names)} inputs {names}")
        given: Dict[str, ArrayLike] = dict(zip(names, args))
        folded = {name.upper(): name for name in names}
        for key, value in kwargs.items():
            name = folded.get(key.upper())
            if name is None:
                raise TypeError(f"{key!r} is not an input; the inputs are {names}")
            if name in given:
                raise TypeError(f"input {name!r} is given twice")
            given[name] = value
        missing = [name for name in names if name not in given]
        if missing:
            raise TypeError(f"no value for input(s) {missing}")
        return _columns([given[name] for name in names])

    def _directions(self, wrt: Optional[Sequence[Union[str, int]]]) -> List[int]:
        if wrt is None:
            return list(range(len(self.inputs)))
        folded = [name.upper() for name in self.inputs]
        indices = []
        for direction in wrt:
            if isinstance(direction, str):
                if direction.upper() not in folded:
                    raise TypeError(f"{direction!r} is not an input; the inputs are {self.inputs}")
                indices.append(folded.index(direction.upper()))
            else:
                indices.append(int(direction))
        return indices

    def _evaluate(self, args, kwargs, wrt, order, threads, errors):
        if errors not in ("raise", "status"):
            raise ValueError(f'errors must be "raise" or "status", not {errors!r}')
        shape, columns = self._points(args, kwargs)
        directions = self._directions(wrt) if order > 0 else []
        values, gradients, hessians, status = self._program.evaluate(
            columns, directions, order, threads, int(np.prod(shape, dtype=np.int64))
        )
        if errors == "raise" and status.any():
            point = int(np.argmax(status != 0))
            at = [float(column[point]) for column in columns]
            try:
                self._program.explain(at, directions, order)
            except Error as error:
                error.point = point
                error.args = (f"at point {point}: {error.args[0]}",)
                raise
        k = len(directions)
        result = [values.reshape(shape)]
        if order >= 1:
            result.append(gradients.reshape(shape + (k,)))
        if order >= 2:
            result.append(hessians.reshape(shape + (k, k)))
        found = result[0] if order == 0 else tuple(result)
        return (found, status.reshape(shape)) if errors == "status" else found

    def value(self, *args: ArrayLike, threads: int = 0, errors: str = "raise", **kwargs: ArrayLike):
        """The value at each point: an array of the broadcast shape."""
        return self._evaluate(args, kwargs, None, 0, threads, errors)

    def gradient(
        self,
        *args: ArrayLike,
        wrt: Optional[Sequence[Union[str, int]]] = None,
        threads: int = 0,
        errors: str = "raise",
        **kwargs: ArrayLike,
    ):
        """``(value, gradient)``: the exact first derivatives in the inputs
        ``wrt`` (names or indices; default all), the gradient of shape
        ``shape + (len(wrt),)``."""
        return self._evaluate(args, kwargs, wrt, 1, threads, errors)

    def hessian(
        self,
        *args: ArrayLike,
        wrt: Optional[Sequence[Union[str, int]]] = None,
        threads: int = 0,
        errors: str = "raise",
        **kwargs: ArrayLike,
    ):
        """``(value, gradient, hessian)``: the exact second derivatives too,
        the Hessian of shape ``shape + (k, k)``, symmetric."""
        return self._evaluate(args, kwargs, wrt, 2, threads, errors)


def compile(text: str, inputs: Sequence[str]) -> Program:  # noqa: A001 - the natural name
    """Parses, checks and compiles ``text`` for the inputs named ``inputs``
    (case-insensitive; ``TIME`` and ``MODE`` may be among them).

    Raises :class:`Error` listing every problem found (a syntax error;
    else every unknown name, broken argument rule such as ``x1 >= x2``,
    wrong number of arguments), each a :class:`Diagnostic` in its
    ``errors`` with its line and column; its ``line`` and ``column`` are
    the first's.
    """
    return Program(text, inputs)


@dataclass(frozen=True)
class Diagnostic:
    """A problem of a model file or an expression, at its line and column
    (from 1; None when it speaks of no place)."""

    message: str
    line: Optional[int]
    column: Optional[int]

    def __str__(self) -> str:
        if self.line is None:
            return self.message
        return f"{self.line}:{self.column}: {self.message}"


def check_model(path: Union[str, os.PathLike]) -> List[Diagnostic]:
    """Checks the model file at ``path`` (a solver dataset ``.adm``, a
    command file ``.acf`` or ``.cmd``, a dataset known by its first lines, or
    a scene file ``.toml``): every problem with its line and column, in file
    order; an empty list when it checks. Raises :class:`Error` when the file
    cannot be read or is not a model file."""
    return _core.check_model(os.fspath(path))


@dataclass(frozen=True)
class Event:
    """A located branch switch of a run: the time, the function (``BISTOP``
    or ``IF``), the branches it leaves and takes, and where the call is in
    the model's file."""

    time: float
    function: str
    from_branch: str
    to_branch: str
    line: int
    column: int


@dataclass
class Simulation:
    """The result of :func:`simulate`: ``columns`` maps each column name
    (``time``, ``DIF(1)``, ``BODY.x`` ..., the outputs) to a numpy array of
    its values at the output times; ``result["DIF(1)"]`` reads one.
    ``events`` lists every located branch switch in time order;
    ``statistics`` the integrator's counts (``steps``, ``rejected``,
    ``rhs_evaluations``, ``jacobian_evaluations``, ``lu_decompositions``),
    ``wall_time`` in seconds and ``stiff_from`` (DOP853: when Hairer's test
    found the run stiff, else None) and ``method_changes`` (under "auto":
    ``(time, from, to)`` per change of method, in time order, the methods
    named "radau" and "dop853")."""

    columns: Dict[str, np.ndarray]
    events: List[Event] = field(default_factory=list)
    statistics: Dict[str, object] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    @property
    def time(self) -> np.ndarray:
        """The output times."""
        return self.columns["time"]


#: The suffixes of model files (any case): a one-line string ending in one
#: is a path.
_MODEL_SUFFIXES = (".adm", ".acf", ".cmd", ".dat", ".toml")


def _source(path_or_text: Union[str, os.PathLike]) -> Tuple[str, bool]:
    """``(source, is_path)``: a path-like object is a path; a string is a
    path when a file of that name exists or when it looks like one: a
    single line (no line break) that ends in one of ``_MODEL_SUFFIXES``
    (``runs/k=1e4/model.adm``), or has no ``=`` and holds a path
    separator. Model text never
    looks like a path: a dataset's first line is its title, so a one-line
    dataset has no statement, and a scene's settings are ``key = value``.
    A path to no file raises ``FileNotFoundError`` naming it."""
    source = os.fspath(path_or_text)
    one_line = "\n" not in source and "\r" not in source
    if isinstance(path_or_text, str):
        separators = {"/", os.sep, os.altsep} - {None}
        looks_like_path = source.lower().endswith(_MODEL_SUFFIXES) or (
            "=" not in source and any(s in source for s in separators)
        )
        is_path = one_line and (os.path.exists(source) or looks_like_path)
    else:
        is_path = True
    if is_path and not os.path.exists(source):
        raise FileNotFoundError(
            errno.ENOENT,
            "no such model file (a one-line string ending in .adm, .acf, .cmd, .dat or .toml, "
            "or holding a path separator, is read as a path, not as model text)",
            source,
        )
    return source, is_path


def _is_scene_text(text: str) -> bool:
    return re.search(r"^\s*\[", text, re.MULTILINE) is not None


def simulate(
    path_or_text: Union[str, os.PathLike],
    *,
    end: Optional[float] = None,
    steps: Optional[int] = None,
    method: str = "auto",
    rtol: float = 1e-6,
    atol: Optional[float] = None,
    h_max: Optional[float] = None,
    max_steps: Optional[int] = None,
    format: Optional[str] = None,  # noqa: A002 - the word users know
) -> Simulation:
    """Simulates a model from time 0 to ``end`` with ``steps + 1`` output
    rows.

    ``path_or_text`` is a file (a solver dataset, with END and STEPS of a
    ``SIMULATE/DYNAMIC`` command in an ``.acf`` beside it; an Adams View
    command file ``.cmd``, read as the dataset View would export, its run
    from its last ``simulation single_run transient``; or a scene file
    ``.toml``) or the model's text (``format`` "dataset" or "scene"; by
    default a text with a line starting ``[`` is a scene). A path-like
    object, a string naming a file that exists, a one-line string that
    ends in ``.adm``, ``.acf``, ``.cmd``, ``.dat`` or ``.toml`` (any case),
    and one with no ``=`` that holds a path separator are paths: a path to no
    file raises ``FileNotFoundError`` naming it (model text is never such a
    string: a dataset's first line is its title). ``end`` and
    ``steps`` default to the model's own; ``method`` is "auto" (the
    default, as on the command line: DOP853 while the model is not stiff,
    Radau5 while it is; ``statistics["method_changes"]`` lists each change),
    "radau5" (stiff models) or "dop853"; ``atol`` defaults to
    ``rtol / 1000``. The GIL is released during the run.

    Raises :class:`Error` when the model does not check or holds what the
    simulator does not run (constraints), with every problem in its
    ``errors`` (the first's line and column its own), or when the run
    cannot go on.
    """
    source, is_path = _source(path_or_text)
    if format is None:
        format = "dataset" if is_path or not _is_scene_text(source) else "scene"
    names, rows, events, statistics = _core.simulate(
        source, is_path, format, (method, end, steps, rtol, atol, h_max, max_steps)
    )
    table = rows.reshape(-1, len(names))
    columns = {name: np.ascontiguousarray(table[:, i]) for i, name in enumerate(names)}
    return Simulation(columns, [Event(*event) for event in events], statistics)


def _utility(name: str, arguments: Sequence[ArrayLike], iord: int, width: int):
    shape, columns = _columns(arguments)
    vectors = _core.utility_bulk(name, columns, int(iord)).reshape(shape + (3,))
    return vectors[..., 0] if width == 1 else vectors


def bistop(x, xd, x1, x2, k, e, cmax, d, iord: int = 0) -> np.ndarray:
    """The solver's BISTOP utility over arrays (broadcast), as
    MotionSolve's ``py_step`` is: VECTOR per point, shape ``shape + (3,)``:
    ``[F, 0, 0]`` for iord 0, ``[dF/dx, dF/dxd, 0]`` for 1,
    ``[d2F/dx2, d2F/dxdxd, 0]`` for 2. Raises :class:`Error` at the first
    point that would set ERRFLG (a broken rule such as ``x1 >= x2``, an
    input that is not finite, an entry beyond the range of a double)."""
    return _utility("bistop", [x, xd, x1, x2, k, e, cmax, d], iord, 3)


def impact(x, xd, x1, k, e, cmax, d, iord: int = 0) -> np.ndarray:
    """The solver's IMPACT utility over arrays: VECTOR per point, as
    :func:`bistop`."""
    return _utility("impact", [x, xd, x1, k, e, cmax, d], iord, 3)


def step(x, x0, h0, x1, h1, iord: int = 0) -> np.ndarray:
    """The solver's STEP utility over arrays: the value (iord 0) or its
    first or second derivative in x (iord 1, 2), of the broadcast shape."""
    return _utility("step", [x, x0, h0, x1, h1], iord, 1)


from .sweep import Sweep, sweep  # noqa: E402 - sweep uses simulate above
