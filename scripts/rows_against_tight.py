#!/usr/bin/env python3
"""Every row of every example model against a tight Radau5 run.

For each dataset in examples/simulate/, runs `mbexpr simulate` with Radau5
at rtol 1e-12 (the reference) and with DOP853 and Auto at rtol 1e-6 and
1e-9, 400 output steps each, and prints, per run, the largest difference
of a row from the reference divided by the largest magnitude of its column
(columns that stay below 1e-6 are left out), in units of rtol, with the
column and the run's steps, rejected steps and right-hand sides.

    python3 scripts/rows_against_tight.py [path/to/mbexpr]

Only the Python standard library is used.
"""
import csv
import os
import re
import subprocess
import sys

BINARY = sys.argv[1] if len(sys.argv) > 1 else "target/release/mbexpr"
FOLDER = "examples/simulate"


def rows(text):
    table = list(csv.reader(text.splitlines()))
    return table[0], [[float(value) for value in row] for row in table[1:]]


def simulate(path, method, rtol):
    return subprocess.run(
        [BINARY, "simulate", path, "--method", method, "--rtol", rtol,
         "--steps", "400", "--format", "csv"],
        capture_output=True, text=True)


for name in sorted(f for f in os.listdir(FOLDER) if f.endswith(".adm")):
    path = os.path.join(FOLDER, name)
    reference = simulate(path, "radau", "1e-12")
    if reference.returncode:
        print(name, "reference failed")
        continue
    header, exact = rows(reference.stdout)
    for method in ["dop853", "auto"]:
        for rtol in ["1e-6", "1e-9"]:
            run = simulate(path, method, rtol)
            if run.returncode:
                print(name, method, rtol, "failed")
                continue
            _, found = rows(run.stdout)
            worst, where = 0.0, ""
            for column in range(1, len(header)):
                scale = max(abs(row[column]) for row in exact)
                if scale < 1e-6:
                    continue
                difference = max(abs(a[column] - b[column]) for a, b in zip(exact, found)) / scale
                if difference > worst:
                    worst, where = difference, header[column]
            cost = re.search(r"(\d+) steps \((\d+) rejected\), (\d+) right-hand sides", run.stderr)
            steps = "%s steps (%s rejected), %s rhs" % cost.groups() if cost else "?"
            print(f"{name} {method} {rtol}: {worst / float(rtol):.3g} x rtol ({where}); {steps}")
