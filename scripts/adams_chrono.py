#!/usr/bin/env python3
"""Runs the Adams View datasets of Project Chrono's joint tests with mbexpr
and compares every request with the results Adams computed for them.

Project Chrono (BSD-3) keeps, under `data/testing/joints/`, nineteen
datasets Adams View wrote (`adams_models/test_*.adm`: revolute, prismatic,
spherical, universal, cylindrical joints, a rack and pinion, a distance
GCON, translational and rotational springs) and, for each case, the columns
Adams Solver wrote for its requests every 0.01 s over 5 s
(`*/Name_CaseNN_ADAMS_Pos.txt`, `_Vel`, `_Acc`, `_Quat`, `_Avel`, `_Aacc`,
`_Rforce`, `_Rtorque`). Neither is part of mbexpr: point this script at a
copy of that folder.

    python3 scripts/adams_chrono.py path/to/chrono/data/testing/joints

For each quantity it prints the largest difference over the run divided by
the largest magnitude Adams wrote (Adams writes six significant digits, so
about 1e-6 is agreement), and exits 1 when a case does not run or a
quantity differs by more than --limit.
"""

import argparse
import csv
import os
import subprocess
import sys

# The files Adams wrote, the request columns they hold (the datasets'
# REQUEST/1 to /5), and mbexpr's names for them (F2 ... when the request
# lists expressions, its standard columns when it is of a standard kind).
QUANTITIES = [
    ("Pos", [("REQUEST/1.DX",), ("REQUEST/1.DY",), ("REQUEST/1.DZ",)]),
    ("Vel", [("REQUEST/2.VX",), ("REQUEST/2.VY",), ("REQUEST/2.VZ",)]),
    ("Acc", [("REQUEST/3.ACCX",), ("REQUEST/3.ACCY",), ("REQUEST/3.ACCZ",)]),
    ("Quat", [("REQUEST/4.F2",), ("REQUEST/4.F3",), ("REQUEST/4.F4",), ("REQUEST/4.F6",)]),
    ("Avel", [("REQUEST/2.WX",), ("REQUEST/2.WY",), ("REQUEST/2.WZ",)]),
    ("Aacc", [("REQUEST/3.WDTX",), ("REQUEST/3.WDTY",), ("REQUEST/3.WDTZ",)]),
    ("Rforce", [("REQUEST/5.F2", "REQUEST/5.FX"), ("REQUEST/5.F3", "REQUEST/5.FY"),
                ("REQUEST/5.F4", "REQUEST/5.FZ")]),
    ("Rtorque", [("REQUEST/5.F6", "REQUEST/5.TX"), ("REQUEST/5.F7", "REQUEST/5.TY"),
                 ("REQUEST/5.F8", "REQUEST/5.TZ")]),
]


def read_adams(path):
    rows = []
    with open(path) as text:
        for line in text:
            if line.startswith("#") or not line.strip() or line.startswith("Time"):
                continue
            rows.append([float(field) for field in line.split()])
    return rows


def run(mbexpr, dataset, rtol, method):
    command = [mbexpr, "simulate", dataset, "--end", "5", "--steps", "500",
               "--format", "csv", "--rtol", str(rtol), "--method", method]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return None, done.stderr.strip().splitlines()
    rows = list(csv.reader(done.stdout.splitlines()))
    header, values = rows[0], [[float(v) for v in row] for row in rows[1:]]
    columns = {name: [row[k] for row in values] for k, name in enumerate(header)}
    summary = [line for line in done.stderr.splitlines() if ": t = 0 .." in line]
    return columns, summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("joints", help="chrono's data/testing/joints folder")
    parser.add_argument("--mbexpr", default="target/release/mbexpr")
    parser.add_argument("--rtol", type=float, default=1e-8)
    parser.add_argument("--method", default="auto")
    parser.add_argument("--limit", type=float, default=1e-3,
                        help="the largest relative difference accepted")
    parser.add_argument("--cases", nargs="*", help="only these (Revolute_Case01 ...)")
    args = parser.parse_args()

    models = os.path.join(args.joints, "adams_models")
    folders = [f for f in sorted(os.listdir(args.joints)) if f != "adams_models"]
    failed = 0
    print(f"{'case':<22} {'quantity':<8} {'difference':>10}  {'of':>10}  worst at")
    for folder in folders:
        names = sorted({f.split("_ADAMS_")[0] for f in os.listdir(os.path.join(args.joints, folder))
                        if "_ADAMS_" in f})
        for case in names:
            if args.cases and case not in args.cases:
                continue
            dataset = os.path.join(models, f"test_{case}.adm")
            if not os.path.exists(dataset):
                print(f"{case:<22} no dataset (Adams' results only)")
                continue
            columns, messages = run(args.mbexpr, dataset, args.rtol, args.method)
            if columns is None:
                failed += 1
                print(f"{case:<22} does not run: {messages[0] if messages else '?'}")
                continue
            results = []
            for quantity, wanted in QUANTITIES:
                path = os.path.join(args.joints, folder, f"{case}_ADAMS_{quantity}.txt")
                if not os.path.exists(path):
                    continue
                adams = read_adams(path)
                names = [next((n for n in options if n in columns), None) for options in wanted]
                if None in names:
                    failed += 1
                    print(f"{case:<22} {quantity:<8} not written (no {wanted[names.index(None)][0]})")
                    continue
                scale, worst, at = 0.0, 0.0, 0.0
                for row in adams:
                    step = round(row[0] / 0.01)
                    if step >= len(columns["time"]):
                        continue
                    for k, name in enumerate(names):
                        scale = max(scale, abs(row[k + 1]))
                        difference = abs(columns[name][step] - row[k + 1])
                        if difference > worst:
                            worst, at = difference, row[0]
                results.append((quantity, scale, worst, at))
            # A quantity Adams writes as rounding noise (a torque of 1e-15)
            # is compared against a thousandth of the case's largest one.
            floor = 1e-3 * max((scale for _, scale, _, _ in results), default=0.0)
            for quantity, scale, worst, at in results:
                relative = worst / max(scale, floor) if max(scale, floor) > 0 else worst
                flag = "" if relative <= args.limit else "  <-- differs"
                failed += bool(flag)
                print(f"{case:<22} {quantity:<8} {relative:10.2e}  {scale:10.3e}  t = {at:g}{flag}")
            for line in messages:
                print(f"{'':<22} {line.split(': ', 1)[-1]}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
