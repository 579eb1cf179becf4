#!/usr/bin/env python3
"""Hostile-input probes of the mbexpr binary (issue 17): random bytes, token
soup and corpus mutations through `check -` and `parse`; deep nesting of
parentheses, signs and powers; long argument lists; a 50 MB line; mangled
scene files; mangled simulation models through `simulate`; garbage in REPL
batch mode.

Each run counts as a panic (exit 101 or "panicked" on standard error), a
hang (killed after --timeout seconds), or a NaN output ("NaN", "nan" or "inf"
as a value on standard output); peak memory is the child's maximum resident
set, as `/usr/bin/time -f %M` reads it (the rusage of a child forked from
this script would count the script's own pages). Prints one Markdown table
row per probe, for docs/reliability.md.

    python3 scripts/probes.py target/release/mbexpr [--seed 1] [--quick]
"""

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "..", "shared", "corpus")
TOKENS = [
    "x", "v", "TIME", "MODE", "PI", "RTOD", ".m.p.mar", "STEP", "BISTOP", "IMPACT",
    "IF", "SIN", "LOG", "SQRT", "MAX", "POLY", "DX", "VARVAL", "AKISPL", "0", "1",
    "2.5", "1e5", ".5", "90D", "1.0D3", "1E400", "-1e308", "5e-324", "+", "-", "*",
    "/", "**", "^", "<", "!", "=", "(", ")", ",", ":", " ", "\t", "{", "\n", "0201",
    "é", "\u00a0", "\x1b",
]
NAN = re.compile(r"(?<![A-Za-z_])(nan|NaN|inf|-inf)(?![A-Za-z_])")


class Tally:
    def __init__(self, name):
        self.name = name
        self.runs = self.panics = self.hangs = self.nans = 0
        self.peak_kb = 0
        self.input_bytes = 0
        self.seconds = 0.0
        self.examples = []

    def row(self):
        ratio = ""
        if self.input_bytes >= 1 << 20:
            ratio = f" ({self.peak_kb * 1024 / self.input_bytes:.1f}x input)"
        return (f"| {self.name} | {self.runs} | {self.panics} | {self.hangs} | {self.nans} "
                f"| {self.peak_kb / 1024:.0f} MB{ratio} | {self.seconds:.1f} s |")


def run(tally, binary, args, stdin=b"", timeout=20.0):
    """Runs the binary once and tallies what happened."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        timed = ["/usr/bin/time", "-f", "MAXRSS %M", binary]
        child = subprocess.Popen(timed + args, stdin=subprocess.PIPE, stdout=out, stderr=err,
                                 env=dict(os.environ, HOME=tempfile.gettempdir()))
        try:
            child.stdin.write(stdin)
            child.stdin.close()
        except BrokenPipeError:
            pass
        deadline = start + timeout
        status = None
        while status is None:
            pid, status_code, _ = os.wait4(child.pid, os.WNOHANG)
            if pid:
                status = status_code
            elif time.monotonic() > deadline:
                child.kill()
                os.wait4(child.pid, 0)
                tally.hangs += 1
                tally.examples.append(("hang", args, stdin[:200]))
                status = -1
            else:
                time.sleep(0.002)
        tally.seconds += time.monotonic() - start
        tally.runs += 1
        tally.input_bytes = max(tally.input_bytes, len(stdin) + sum(len(a) for a in args))
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode("utf-8", "replace")
        stderr = err.read().decode("utf-8", "replace")
    peak = re.search(r"MAXRSS (\d+)\s*$", stderr)
    if peak:
        tally.peak_kb = max(tally.peak_kb, int(peak.group(1)))
        stderr = stderr[: peak.start()]
    code = os.waitstatus_to_exitcode(status) if status != -1 else None
    crashed = "panicked" in stderr or "terminated by signal" in stderr
    if code == 101 or crashed or (code is not None and (code < 0 or code >= 128)):
        tally.panics += 1
        tally.examples.append(("panic", args, stdin[:200], stderr[:300]))
    # `check` and `parse` print no values, only messages (which may say
    # that an operation "gives inf").
    if args[0] not in ("check", "parse") and NAN.search(stdout):
        tally.nans += 1
        tally.examples.append(("nan", args, stdin[:200], stdout[:200]))


def soup(rng, count):
    return "".join(rng.choice(TOKENS) for _ in range(count))


def mutate(rng, text):
    chars = list(text)
    for _ in range(rng.randint(1, 4)):
        action = rng.randrange(4)
        at = rng.randrange(len(chars) + 1)
        if action == 0 and chars:
            del chars[min(at, len(chars) - 1)]
        elif action == 1:
            chars.insert(at, rng.choice(TOKENS))
        elif action == 2 and chars:
            chars.insert(at, chars[min(at, len(chars) - 1)] * rng.randint(2, 50))
        else:
            chars.insert(at, chr(rng.randrange(32, 127)))
    return "".join(chars)


def corpus_expressions():
    path = os.path.join(CORPUS, "expressions.tsv")
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as file:
        lines = file.read().splitlines()[1:]
    return [line.split("\t")[-1] for line in lines if "\t" in line]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--quick", action="store_true", help="fewer runs, no 50 MB line")
    options = parser.parse_args()
    rng = random.Random(options.seed)
    binary = options.binary
    scale = 0.2 if options.quick else 1.0
    n = lambda count: max(1, int(count * scale))
    tallies = []

    def probe(name):
        tally = Tally(name)
        tallies.append(tally)
        return tally

    tally = probe("random bytes: `check -`, `parse`, `eval`")
    for _ in range(n(300)):
        data = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
        run(tally, binary, ["check", "-"], data)
        text = data.replace(b"\0", b"").decode("utf-8", "replace")
        run(tally, binary, ["parse", "--", text] if text.startswith("-") else ["parse", text])

    tally = probe("token soup: `check -`, `parse`, `eval --set x=0.3 --wrt x --order 2`")
    for _ in range(n(300)):
        text = soup(rng, rng.randrange(1, 60))
        run(tally, binary, ["check", "-"], text.encode())
        arg = text.replace("\0", "")
        if not arg.startswith("-"):
            run(tally, binary, ["parse", arg])
            run(tally, binary, ["eval", arg, "--set", "x=0.3", "--set", "v=-2", "--wrt", "x", "--order", "2"])

    expressions = corpus_expressions()
    tally = probe(f"corpus mutations ({len(expressions)} expressions): `check -`, `eval`")
    for _ in range(n(3)):
        mutated = [mutate(rng, text) for text in expressions]
        run(tally, binary, ["check", "-"], "\n".join(mutated).encode())
    for text in rng.sample(expressions, min(len(expressions), n(300))):
        arg = mutate(rng, text)
        if arg and not arg.startswith("-"):
            run(tally, binary, ["eval", arg, "--set", "x=0.3", "--set", "TIME=1"])

    tally = probe("nesting 10 to 1 000 000: `(`, `-`, `**`, `SIN(`, `+` chains")
    for depth in [10, 100, 499, 500, 501, 1000, 10_000, 100_000, 1_000_000]:
        for text in [
            "(" * depth + "x" + ")" * depth,
            "-" * depth + "x",
            "x" + "**x" * depth,
            "SIN(" * depth + "x" + ")" * depth,
            "x+" * depth + "x",
            "x*-" * depth + "x",
            "(" * depth,
        ]:
            run(tally, binary, ["check", "-"], text.encode() + b"\n")
            if len(text) < 100_000 and not text.startswith("-"):
                run(tally, binary, ["eval", text, "--set", "x=1"])

    tally = probe("argument lists of 100 000: MAX, POLY, STEP, IF")
    for text in [
        "MAX(" + ",".join(["x"] * 100_000) + ")",
        "MIN(" + ",".join(str(i) for i in range(100_000)) + ")",
        "POLY(x, 0, " + ",".join(["1"] * 100_000) + ")",
        "STEP(" + ",".join(["x"] * 100_000) + ")",
        "IF(x:" + ",".join(["x"] * 100_000) + ")",
        "F(" + "," * 100_000 + ")",
    ]:
        run(tally, binary, ["check", "-"], text.encode() + b"\n", timeout=60)

    if not options.quick:
        tally = probe("a 50 MB line: `x+x+...`, `MAX(x,x,...)`, garbage")
        size = 50 * 1024 * 1024
        for text in [
            b"x+" * (size // 2) + b"x\n",
            b"MAX(" + b"x," * (size // 2) + b"x)\n",
            bytes(rng.randrange(32, 127) for _ in range(1024)) * (size // 1024),
        ]:
            run(tally, binary, ["check", "-"], text, timeout=120)

    scenes = [os.path.join(ROOT, "examples", "scenes", name)
              for name in sorted(os.listdir(os.path.join(ROOT, "examples", "scenes")))
              if name.endswith(".toml")]
    tally = probe("mangled scene files: `eval --scene`")
    with tempfile.TemporaryDirectory() as folder:
        for index in range(n(300)):
            with open(rng.choice(scenes), encoding="utf-8") as file:
                text = file.read()
            lines = text.splitlines()
            for _ in range(rng.randint(1, 3)):
                at = rng.randrange(len(lines))
                choice = rng.randrange(4)
                if choice == 0:
                    lines[at] = mutate(rng, lines[at])
                elif choice == 1:
                    del lines[at]
                elif choice == 2:
                    lines.insert(at, rng.choice(["k = nan", "mode = 99", "time = inf", "[[body]]",
                                                 "position = [1, 2]", "[[marker]]", "id = 0",
                                                 "euler = [1e308, nan, 0]", "[variables]", "x = 1e999"]))
                else:
                    lines[at] = lines[at] * rng.randint(2, 5)
            path = os.path.join(folder, f"scene{index}.toml")
            with open(path, "w", encoding="utf-8") as file:
                file.write("\n".join(lines))
            run(tally, binary, ["eval", "--scene", path])
            run(tally, binary, ["eval", "DX(ball, wall) + TIME", "--scene", path, "--wrt", "ball.x", "--order", "2"])

    # The simulator on mangled models: numbers swapped for extreme ones
    # (a gravity of 1e15, k = -1e308, IC = nan), lines cut and garbage in.
    models = [os.path.join(ROOT, "examples", "simulate", name)
              for name in sorted(os.listdir(os.path.join(ROOT, "examples", "simulate")))]
    models += [os.path.join(ROOT, "examples", "scenes", name)
               for name in ("ball_simulation.toml", "slider_simulation.toml")]
    extremes = ["0", "-0", "1e308", "-1e308", "1e-308", "5e-324", "nan", "inf", "-1", "1e30",
                "-1e-30", "1e15", "1E400", "3"]
    number = re.compile(r"(?<![A-Za-z_/])-?\d+(\.\d*)?([eE][-+]?\d+)?")
    tally = probe("mangled simulation models: `simulate`")
    with tempfile.TemporaryDirectory() as folder:
        for index in range(n(200)):
            source = rng.choice(models)
            with open(source, encoding="utf-8") as file:
                text = file.read()
            for _ in range(rng.randint(1, 3)):
                found = list(number.finditer(text))
                if found and rng.random() < 0.6:
                    match = rng.choice(found)
                    text = text[: match.start()] + rng.choice(extremes) + text[match.end():]
                else:
                    text = mutate(rng, text)
            path = os.path.join(folder, f"model{index}{os.path.splitext(source)[1]}")
            with open(path, "w", encoding="utf-8") as file:
                file.write(text)
            # Within the time limit: a step budget a tenth of the default.
            run(tally, binary, ["simulate", path, "--end", rng.choice(["0.5", "1", "10"]),
                                "--steps", "10", "--method", rng.choice(["radau", "dop853"]),
                                "--max-steps", "1000000", "--format", "csv"])

    tally = probe("REPL batch garbage: `repl` < lines")
    commands = [":set x = ", ":wrt ", ":order ", ":scene ", ":help ", ":plot ", ":vars", ":q", ":"]
    for _ in range(n(200)):
        lines = []
        for _ in range(rng.randrange(1, 30)):
            line = soup(rng, rng.randrange(0, 20)).replace("\n", " ")
            if rng.random() < 0.3:
                line = rng.choice(commands) + line
            lines.append(line)
        run(tally, binary, ["repl"], "\n".join(lines).encode())

    print("| probe | runs | panics | hangs | NaN outputs | peak memory | time |")
    print("|---|---|---|---|---|---|---|")
    for tally in tallies:
        print(tally.row())
    for tally in tallies:
        for example in tally.examples[:5]:
            print(f"{tally.name}: {example!r}"[:600], file=sys.stderr)
    return 1 if any(t.panics or t.hangs or t.nans for t in tallies) else 0


if __name__ == "__main__":
    sys.exit(main())
