"""A design study of A1 (examples/simulate/a1_ball.adm): 10 000 runs of the
ball between two walls over stiffness k, damping cmax and damping depth d,
on 1 and 2 workers of a process pool, with the throughput of each.

    python examples/python/a1_study.py [--runs 10000] [--workers 1 2] [--dask]

Prints one line per worker count (runs per second) and the five designs
that take most energy out of the ball. With --dask the study runs on a
dask.distributed LocalCluster of the same number of workers instead.
"""

import argparse
import multiprocessing
import pathlib
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

import mbexpr

A1 = pathlib.Path(__file__).resolve().parents[1] / "simulate" / "a1_ball.adm"


def template() -> str:
    """A1's dataset with k, cmax and d as fields."""
    text = A1.read_text()
    return text.replace("1e5, 1.5, 50, 0.01", "{k}, 1.5, {cmax}, {d}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=10_000)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--dask", action="store_true")
    args = parser.parse_args()
    # 25 x 20 x 20 = 10 000 designs (fewer sets of d for fewer runs).
    grid = {
        "k": np.geomspace(1e4, 1e6, 25).tolist(),
        "cmax": np.linspace(0.0, 100.0, 20).tolist(),
        "d": np.linspace(0.002, 0.05, max(1, args.runs // 500)).tolist(),
    }
    model = template()
    for workers in args.workers:
        started = time.perf_counter()
        if args.dask:
            from distributed import Client, LocalCluster

            with LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None) as cluster:
                with Client(cluster) as client:
                    table = mbexpr.sweep(model, grid, client.get_executor(), end=1.0, steps=100)
        else:
            context = multiprocessing.get_context("forkserver")
            with ProcessPoolExecutor(workers, mp_context=context) as pool:
                table = mbexpr.sweep(model, grid, pool, end=1.0, steps=100)
        elapsed = time.perf_counter() - started
        failed = sum(error is not None for error in table.errors)
        print(
            f"{'dask' if args.dask else 'process pool'}, {workers} worker(s): "
            f"{len(table)} runs in {elapsed:.1f} s, {len(table) / elapsed:.0f} runs/s, {failed} failed"
        )
    # The speed left after a second of rebounds (5 m/s at the start).
    speed = np.abs(table["final DIF(2)"])
    print("the five designs that take most energy out of the ball:")
    for row in np.argsort(speed)[:5]:
        print(
            f"  k = {table['k'][row]:.3g}, cmax = {table['cmax'][row]:.3g}, d = {table['d'][row]:.3g}: "
            f"|v(1)| = {speed[row]:.4f} m/s, {int(table['events'][row])} switches"
        )


if __name__ == "__main__":
    main()
