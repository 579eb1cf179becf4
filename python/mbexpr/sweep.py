"""Parameter sweeps: many simulations of one model template over a grid or
a list of parameter sets, spread over any ``concurrent.futures.Executor``.
"""

from __future__ import annotations

import itertools
import math
import multiprocessing
import os
import time
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _core

Template = Union[str, Callable[[Dict[str, Any]], str]]
Parameters = Union[Mapping[str, Sequence[Any]], Sequence[Mapping[str, Any]]]


@dataclass
class Sweep:
    """The table of a sweep, one row per parameter set in the order given
    (a grid in ``itertools.product`` order, the last name fastest).

    ``columns`` maps each parameter name, and for each result column ``C``
    of the model ``final C``, ``max C`` and ``min C``, then ``events`` (the
    number of located branch switches) and ``first event`` (the time of the
    first, NaN when there is none), to a numpy array. A run that failed has
    NaN results and its message in ``errors`` (None for a run that
    succeeded). ``runs_per_second`` is the study's throughput (wall time of
    the whole sweep)."""

    columns: Dict[str, np.ndarray]
    errors: List[Optional[str]]
    runs_per_second: float

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def __len__(self) -> int:
        return len(self.errors)

    def to_pandas(self):
        """The table as a ``pandas.DataFrame`` (pandas is not a dependency)."""
        import pandas

        frame = pandas.DataFrame(self.columns)
        frame["error"] = self.errors
        return frame


def _parameter_sets(parameters: Parameters) -> List[Dict[str, Any]]:
    if isinstance(parameters, Mapping):
        names = list(parameters)
        return [dict(zip(names, values)) for values in itertools.product(*parameters.values())]
    return [dict(entry) for entry in parameters]


def _text(template: Template, values: Dict[str, Any]) -> str:
    return template(values) if callable(template) else template.format_map(values)


def _summary(template: Template, settings: Dict[str, Any], values: Dict[str, Any]):
    """One run: ``(names, results, None)`` or ``(None, None, message)``."""
    from . import Error, simulate

    try:
        result = simulate(_text(template, values), **settings)
    except (Error, KeyError, IndexError, ValueError, OSError) as error:
        return None, None, f"{type(error).__name__}: {error}"
    names = [name for name in result.columns if name != "time"]
    numbers = []
    for name in names:
        column = result.columns[name]
        numbers += [column[-1], column.max(), column.min()]
    first = result.events[0].time if result.events else math.nan
    return names, numbers + [len(result.events), first], None


def _run_batch(template: Template, settings: Dict[str, Any], batch: List[Dict[str, Any]]):
    """The runs of one task (module level, so that it pickles)."""
    return [_summary(template, settings, values) for values in batch]


def _default_executor() -> Executor:
    # Never fork: a child forked from a process whose threads are running
    # (rayon's, numpy's BLAS) can hang; forkserver starts clean workers.
    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    return ProcessPoolExecutor(max_workers=os.cpu_count() or 1, mp_context=context)


def sweep(
    model_template: Template,
    parameters: Parameters,
    executor: Optional[Executor] = None,
    *,
    end: Optional[float] = None,
    steps: Optional[int] = None,
    method: str = "auto",
    rtol: float = 1e-6,
    atol: Optional[float] = None,
    h_max: Optional[float] = None,
    max_steps: Optional[int] = None,
    format: Optional[str] = None,  # noqa: A002 - as in simulate
    task_seconds: float = 0.1,
) -> Sweep:
    """Runs a study of many simulations and returns its table (:class:`Sweep`).

    ``model_template`` is the text of a model (a dataset or a scene file)
    with ``{name}`` fields filled from each parameter set
    (``str.format_map``; write a literal brace as ``{{``), or a function
    taking the parameter set as a dict and returning the text (a
    module-level function, so that process executors can pickle it).
    ``parameters`` is a grid, ``{"k": [1e4, 1e5], "d": [0.01, 0.02]}``, or
    a list of parameter sets, ``[{"k": 1e4, "d": 0.01}, ...]``. The run
    settings are those of :func:`mbexpr.simulate`, checked once before any
    run: settings no run can take (an unknown method, a tolerance or an end
    time out of range) raise :class:`mbexpr.Error` and start nothing. An
    end time or a number of output steps left to the model, and a largest
    step against the end time (a model's SENSOR may halt it sooner), are
    checked by each run.

    ``executor`` is any ``concurrent.futures.Executor``: by default a
    process pool of one worker per core started with ``forkserver`` (never
    ``fork``); a Dask cluster's ``client.get_executor()`` runs the same
    study on the cluster. The first run is timed in the calling process and
    the others are sent in batches of at least ``task_seconds`` of work
    each, so that the executor's overhead per task (about 0.2 ms for a
    process pool, 1 ms or more for Dask) stays small.
    """
    _core.check_settings(format, (method, end, steps, rtol, atol, h_max, max_steps))
    sets = _parameter_sets(parameters)
    settings = dict(
        end=end,
        steps=steps,
        method=method,
        rtol=rtol,
        atol=atol,
        h_max=h_max,
        max_steps=max_steps,
        format=format,
    )
    started = time.perf_counter()
    outcomes = []
    if sets:
        outcomes.append(_summary(model_template, settings, sets[0]))
    one_run = max(time.perf_counter() - started, 1e-6)
    size = max(1, math.ceil(task_seconds / one_run))
    rest = sets[1:]
    batches = [rest[i : i + size] for i in range(0, len(rest), size)]
    if batches:
        owned = executor is None
        pool = _default_executor() if owned else executor
        try:
            futures = [pool.submit(_run_batch, model_template, settings, batch) for batch in batches]
            for future in futures:
                outcomes.extend(future.result())
        finally:
            if owned:
                pool.shutdown()
    elapsed = time.perf_counter() - started
    return _table(sets, outcomes, len(sets) / elapsed if sets else 0.0)


def _table(sets: List[Dict[str, Any]], outcomes, rate: float) -> Sweep:
    names = next((found for found, _, _ in outcomes if found is not None), [])
    headers = [f"{kind} {name}" for name in names for kind in ("final", "max", "min")]
    headers += ["events", "first event"]
    parameter_names = list(dict.fromkeys(name for values in sets for name in values))
    columns: Dict[str, np.ndarray] = {}
    for name in parameter_names:
        values = [values.get(name) for values in sets]
        columns[name] = np.asarray(values)
    rows = np.full((len(sets), len(headers)), math.nan)
    errors: List[Optional[str]] = []
    for row, (found, numbers, error) in enumerate(outcomes):
        if error is None and found == names:
            rows[row] = numbers
        elif error is None:
            error = f"the columns {found} differ from the first run's {names}"
        errors.append(error)
    for i, header in enumerate(headers):
        columns[header] = rows[:, i]
    return Sweep(columns, errors, rate)
