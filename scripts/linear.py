#!/usr/bin/env python3
"""Growth of time and peak memory with the size of the input (issue 19).

Generates each input at two sizes (the second twice the first), runs the
release binary on it under `/usr/bin/time -v`, and prints a Markdown table
row per case: wall time and peak resident memory at both sizes and their
ratios. A path linear in its input shows ratios near 2; a quadratic one
near 4. Run from the repository root after `cargo build --release`:

    python3 scripts/linear.py                 # every case
    python3 scripts/linear.py chain header    # some of them
    python3 scripts/linear.py --binary PATH   # another build

Each run is made once (the machine is shared): read the ratios, not the
digits, and run a case again when a figure looks odd.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile


def errors_file(n):
    """n expression lines, each with a syntax error: one message per line."""
    return {"in.txt": "SIN(x\n" * n}, ["check", "in.txt"]


def chain(n):
    """A dataset of n VARIABLEs, each reading the one before."""
    lines = ["chain", "VARIABLE/1, FUNCTION = TIME"]
    lines += [f"VARIABLE/{i}, FUNCTION = VARVAL({i - 1})*1.0001" for i in range(2, n + 1)]
    return {"chain.adm": "\n".join(lines) + "\n"}


def model_text(n):
    """A dataset of n parts, each with two markers and a spring between them."""
    lines = ["generated model", "PART/1, GROUND", "MARKER/1, PART = 1"]
    for i in range(2, n + 2):
        lines += [
            f"PART/{i}, MASS = 1, CM = {10 * i}, QG = {i}, 0, 0",
            f"MARKER/{10 * i}, PART = {i}",
            f"MARKER/{10 * i + 1}, PART = {i}, QP = 0.5, 0, 0",
            f"SFORCE/{i}, TRANSLATIONAL, I = {10 * i + 1}, J = 1",
            f", FUNCTION = -1E4*(DM({10 * i + 1},1)-{i})-10*VR({10 * i + 1},1)",
            f", + STEP(TIME, 0, 0, 1, {i})",
        ]
    return "\n".join(lines) + "\n"


def max_arguments(n):
    """One call MAX(x, x, ...) of n arguments."""
    return {"in.txt": "MAX(" + ",".join(["x"] * n) + ")\n"}


def min_constants(n):
    """MIN(0, 1, ..., n-1): n distinct constants, folded by the compiler."""
    return "MIN(" + ",".join(str(i) for i in range(n)) + ")"


def header(n):
    """A CSV file of n columns and one row."""
    names = [f"c{i}" for i in range(n)]
    return {"points.csv": ",".join(names) + "\n" + ",".join(["1"] * n) + "\n"}


def cases():
    """name -> (sizes, files and arguments for a size)."""
    return {
        # 19.1: one message per line, rendered with its line and column.
        "errors": ((50_000, 100_000), errors_file),
        # 19.1: a model's jsonl report and eval --model place every expression.
        "model-jsonl": (
            (20_000, 40_000),
            lambda n: ({"m.adm": model_text(n)}, ["check", "--format", "jsonl", "m.adm"]),
        ),
        "model-eval": (
            (20_000, 40_000),
            lambda n: ({"m.adm": model_text(n)}, ["eval", "--model", "m.adm", "--format", "jsonl"]),
        ),
        # 19.2: chained VARIABLEs, checked and evaluated.
        "chain-check": ((4_000, 8_000), lambda n: (chain(n), ["check", "chain.adm"])),
        "chain-eval": (
            (4_000, 8_000),
            lambda n: (chain(n), ["eval", "--model", "chain.adm", "--format", "jsonl"]),
        ),
        # 19.3: memory per argument, distinct constants, wide headers, large models.
        "max-arguments": ((1_000_000, 2_000_000), lambda n: (max_arguments(n), ["check", "in.txt"])),
        "min-constants": ((8_000, 16_000), lambda n: ({}, ["eval", min_constants(n)])),
        "header": (
            (50_000, 100_000),
            lambda n: (header(n), ["eval", "c0", "--points", "points.csv"]),
        ),
        "model-check": (
            (200_000, 400_000),
            lambda n: ({"m.adm": model_text(n)}, ["check", "m.adm"]),
        ),
    }


def measure(binary, folder, files, arguments):
    """(seconds, peak MiB, bytes of input) of one run."""
    size = 0
    for name, text in files.items():
        with open(os.path.join(folder, name), "w") as file:
            file.write(text)
        size += len(text)
    for argument in arguments:
        if len(argument) > 1000:
            size += len(argument)
    result = subprocess.run(
        ["/usr/bin/time", "-v", binary, *arguments],
        cwd=folder,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    report = result.stderr
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", report)
    hours, minutes, seconds = wall.groups()
    seconds = int(hours or 0) * 3600 + int(minutes) * 60 + float(seconds)
    peak = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", report).group(1))
    return seconds, peak / 1024, size


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", help="cases to run (default: all)")
    parser.add_argument("--binary", default=os.path.abspath("target/release/mbexpr"))
    parser.add_argument("--scale", type=float, default=1.0, help="multiply every size by this")
    options = parser.parse_args()
    known = cases()
    chosen = options.cases or list(known)
    for name in chosen:
        if name not in known:
            sys.exit(f"unknown case {name}; known: {', '.join(known)}")
    print("| case | size | input | time | peak memory | size | input | time | peak memory | time ratio | memory ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in chosen:
        sizes, make = known[name]
        row = [name]
        figures = []
        for n in sizes:
            n = max(1, int(n * options.scale))
            files, arguments = make(n)
            with tempfile.TemporaryDirectory() as folder:
                seconds, peak, size = measure(options.binary, folder, files, arguments)
            figures.append((seconds, peak))
            row += [f"{n:,}".replace(",", " "), f"{size / 1e6:.1f} MB", f"{seconds:.2f} s", f"{peak:.0f} MiB"]
        (t1, m1), (t2, m2) = figures
        row += [f"{t2 / max(t1, 0.01):.1f}", f"{m2 / m1:.1f}"]
        print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
