#!/usr/bin/env python3
"""Runs an Adams View command file (.cmd) and the solver dataset Adams View
exported for the same model (.adm) with mbexpr, and compares every column
of the two runs: how closely mbexpr's reading of View's commands agrees
with View's own translation of them.

    python3 scripts/view_exports.py MODEL.cmd MODEL.adm [--end 1 --steps 50]

The pairs are users' files from public repositories (none is part of
mbexpr). Columns are matched by name; the VARIABLEs View makes of its
measures are matched by the measure's name (the `adams_view_name` comment
before each VARIABLE in the .adm, mbexpr's note "VARIABLE/n = MODEL.NAME"
for the .cmd), since the two number them differently. A part's Euler
parameters are compared up to their common sign (q and -q are one
orientation). It prints the largest difference of each column that
differs by more than --limit relative to its largest value, and exits 1
when either file does not run or a column differs.
"""

import argparse
import csv
import re
import subprocess
import sys


def run(mbexpr, path, end, steps):
    command = [mbexpr, "simulate", path, "--format", "csv"]
    if end is not None:
        command += ["--end", str(end), "--steps", str(steps)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        errors = [line for line in done.stderr.splitlines() if ": " in line and "note:" not in line]
        return None, errors[:3] or done.stderr.splitlines()[-3:]
    rows = list(csv.reader(done.stdout.splitlines()))
    header = rows[0]
    values = [[float(v) for v in row] for row in rows[1:]]
    return ({name: [row[k] for row in values] for k, name in enumerate(header)},
            done.stderr)


def measures_in_dataset(path):
    """VARIABLE/n of each measure name, from the export's comments."""
    names = {}
    pending = None
    with open(path, errors="replace") as text:
        for line in text:
            found = re.search(r"adams_view_name='([^']+)'", line)
            if found:
                pending = found.group(1).upper()
                continue
            statement = re.match(r"\s*VARIABLE/(\d+)", line, re.IGNORECASE)
            if statement and pending:
                names[pending] = f"VARIABLE/{statement.group(1)}"
            if line.strip() and not line.startswith("!") and not line.startswith(","):
                pending = None if not statement else pending
    return names


def measures_in_notes(stderr):
    """VARIABLE/n of each measure name, from mbexpr's note."""
    names = {}
    for variable, name in re.findall(r"(VARIABLE/\d+) = ([A-Z0-9_.]+)", stderr):
        # Without the model's name: `SPRING_1.DEFORMATION`, a library
        # spring's variable, is named so in the export too.
        names[name.split(".", 1)[-1]] = variable
    return names


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cmd")
    parser.add_argument("adm")
    parser.add_argument("--mbexpr", default="target/release/mbexpr")
    parser.add_argument("--end", type=float)
    parser.add_argument("--steps", type=int, default=50)
    parser.add_argument("--limit", type=float, default=1e-5)
    args = parser.parse_args()

    view, view_log = run(args.mbexpr, args.cmd, args.end, args.steps)
    export, export_log = run(args.mbexpr, args.adm, args.end, args.steps)
    for name, result, log in [(args.cmd, view, view_log), (args.adm, export, export_log)]:
        if result is None:
            print(f"{name}: does not run: {' | '.join(log)}")
    if view is None or export is None:
        return 1

    # The measures' columns, by name; the others by their own names.
    renamed = {}
    in_view, in_export = measures_in_notes(view_log), measures_in_dataset(args.adm)
    for name, variable in in_view.items():
        if name in in_export:
            renamed[variable] = in_export[name]
    measured = set(in_view.values())
    exported = set(in_export.values())
    pairs = []
    for column in view:
        other = renamed.get(column)
        if other is None:
            if column in measured or column in exported:
                continue
            other = column
        if other in export:
            pairs.append((column, other))
    rows = min(len(view["time"]), len(export["time"]))
    worst = []
    quaternions = {}
    for column, other in pairs:
        a, b = view[column][:rows], export[other][:rows]
        if re.search(r"\.q[0-3]$", column):
            quaternions.setdefault(column[:-3], []).append((a, b))
            continue
        scale = max(max(abs(x) for x in b), 1e-6)
        difference = max(abs(x - y) for x, y in zip(a, b))
        worst.append((difference / scale, column, other, difference, scale))
    for part, components in quaternions.items():
        difference = 0.0
        for k in range(rows):
            same = sum(abs(a[k] - b[k]) for a, b in components)
            flipped = sum(abs(a[k] + b[k]) for a, b in components)
            difference = max(difference, min(same, flipped))
        worst.append((difference, f"{part}.q", f"{part}.q", difference, 1.0))
    worst.sort(reverse=True)
    # A column agrees to the limit, or to rounding where it hardly moves.
    failed = [w for w in worst if w[0] > args.limit and w[3] > 1e-7]
    print(f"{args.cmd}: {len(pairs)} columns ({len(renamed)} measures by name), {rows} rows; "
          f"largest relative difference {worst[0][0]:.1e} ({worst[0][1]})")
    for relative, column, other, difference, scale in failed[:12]:
        print(f"  {column} (export {other}): {difference:.3e} of {scale:.3e}")
    if len(view["time"]) != len(export["time"]):
        print(f"  rows: {len(view['time'])} against {len(export['time'])}")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
