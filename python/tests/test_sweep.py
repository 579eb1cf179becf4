"""Sweeps over the default process pool and a Dask cluster."""

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import mbexpr

A1 = """A1
DIFF/1, IC = 0, FUNCTION = DIF(2)
DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, {k}, 1.5, {cmax}, {d})
END
"""


def ball(values):
    """A1 with its clearance as a parameter (a template function)."""
    return A1.replace("-1, 1,", f"-{values['gap']}, {values['gap']},").format(k=1e5, cmax=50, d=0.01)


def test_a_grid_gives_one_row_per_set_with_the_single_runs_numbers():
    grid = {"k": [1e4, 1e5], "cmax": [0.0, 50.0], "d": [0.01]}
    table = mbexpr.sweep(A1, grid, ThreadPoolExecutor(2), end=0.5, steps=50)
    assert len(table) == 4 and table.errors == [None] * 4
    assert table["k"].tolist() == [1e4, 1e4, 1e5, 1e5]
    assert table["cmax"].tolist() == [0.0, 50.0, 0.0, 50.0]
    for row in range(4):
        one = mbexpr.simulate(
            A1.format(k=table["k"][row], cmax=table["cmax"][row], d=0.01), end=0.5, steps=50
        )
        assert table["final DIF(1)"][row] == one["DIF(1)"][-1]
        assert table["max DIF(1)"][row] == one["DIF(1)"].max()
        assert table["events"][row] == len(one.events)
        assert table["first event"][row] == one.events[0].time
    # Undamped, the ball leaves the wall as fast as it came; damped, slower.
    assert table["max DIF(2)"][0] == pytest.approx(5.0)


def test_the_default_process_pool_and_template_functions():
    sets = [{"gap": 0.5}, {"gap": 1.0}, {"gap": 3.0}]
    table = mbexpr.sweep(ball, sets, end=0.5, steps=10, task_seconds=0.0)
    assert table.errors == [None] * 3
    assert table["first event"][0] == pytest.approx(0.1)
    assert math.isnan(table["first event"][2])  # never reaches a wall at 3 m
    assert table.runs_per_second > 0


def test_a_failed_run_is_a_row_with_its_message():
    table = mbexpr.sweep(A1, {"k": [1e5, -1.0], "cmax": [50], "d": [0.01]}, ThreadPoolExecutor(1), end=0.1, steps=2)
    assert table.errors[0] is None and "must not be negative" in table.errors[1]
    assert np.isnan(table["final DIF(1)"][1])
    # A template that names a model file that is not there fails its row.
    def named(values):
        return A1.format(k=1e5, cmax=50, d=0.01) if values["n"] == 0 else "runs/k=1e4/none.adm"

    table = mbexpr.sweep(named, [{"n": 0}, {"n": 1}], ThreadPoolExecutor(1), end=0.1, steps=2)
    assert table.errors[0] is None and table.errors[1].startswith("FileNotFoundError")


def test_settings_no_run_can_take_are_refused_before_any_run():
    # Each run failed with the same message, the first in this process and
    # the rest on the executor.
    made = []

    def counted(values):
        made.append(values)
        return A1.format(**values)

    grid = {"k": [1e4, 1e5], "cmax": [50], "d": [0.01]}
    refusals = [
        (dict(end=1.0, steps=10, rtol=-1.0), "relative tolerance"),
        (dict(end=math.nan, steps=10), "end time must be a positive number, not NaN"),
        (dict(end=1.0, steps=10, h_max=-1.0), "largest step must be positive"),
        (dict(steps=10, atol=0.0), "absolute tolerance"),
        (dict(end=1.0, steps=10, method="euler"), "unknown integration method"),
        (dict(end=1.0, steps=10, format="csv"), "neither"),
    ]
    for settings, message in refusals:
        with pytest.raises(mbexpr.Error, match=message):
            mbexpr.sweep(counted, grid, ThreadPoolExecutor(2), **settings)
    assert made == []
    # The settings checked are those the runs take.
    table = mbexpr.sweep(counted, grid, ThreadPoolExecutor(2), end=0.1, steps=2, h_max=0.01, max_steps=1000)
    assert table.errors == [None, None] and len(made) == 2


def test_a_study_on_a_dask_cluster_of_two_workers():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        grid = {"k": [1e4, 3e4, 1e5], "cmax": [10.0, 50.0], "d": [0.005, 0.01]}
        table = mbexpr.sweep(A1, grid, client.get_executor(), end=0.5, steps=20, task_seconds=0.0)
    local = mbexpr.sweep(A1, grid, ThreadPoolExecutor(1), end=0.5, steps=20)
    assert table.errors == [None] * 12
    for name in local.columns:
        assert np.array_equal(table[name], local[name], equal_nan=True), name
