#!/usr/bin/env python3
"""Writes the sparse-core benchmark's models (issue 24) as solver datasets.

  stack N: N balls (mass 1, IP 0.1) in a column along ground z under
      gravity, each resting on the one below through
      IMPACT(DM(b,a), VR(b,a), 1.0, 1e6, 1.5, 1e5, 1e-3) and the bottom one on
      the ground through IMPACT(DZ(b,g), VZ(b,g), 0.5, 1e6, 1.5, 1e5, 1e-3);
      dropped from 5 cm gaps: stiff (modes near -1e5 per second).
  chain N: N free balls along ground x, no gravity, every other one moving,
      meeting their neighbours through IMPACT(DM, VR, 1.0, 1e4, 1.5, 10, 1e-3):
      not stiff.
  links N: N unit links (mass 1, IP 1) hanging along ground x from ground
      on REVOLUTE joints, under gravity along -y: the jointed chain of
      BENCHMARKS.md.
  diff-stack N: the stack as 2N DIFFs (heights and vertical speeds), for
      scipy beside mbexpr (scripts/sparse_core.py writes the same equations in
      Python).

Usage: stack_models.py KIND N > model.adm
"""

import sys

GAP = 0.05


def stack(n):
    lines = [f"A stack of {n} balls dropped onto a damped stop (scripts/stack_models.py)", "!"]
    lines += ["PART/1, GROUND", "MARKER/1, PART = 1", "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = -9.81"]
    for k in range(n):
        part, marker = 2 + k, 2 + k
        z = round(0.5 + GAP + k * (1.0 + GAP), 10)
        lines.append(f"PART/{part}, MASS = 1, CM = {marker}, IP = 0.1, 0.1, 0.1")
        lines.append(f"MARKER/{marker}, PART = {part}, QP = 0, 0, {z!r}")
    lines.append(
        "SFORCE/1, TRANSLATIONAL, I = 2, J = 1"
        ", FUNCTION = IMPACT(DZ(2, 1), VZ(2, 1), 0.5, 1e6, 1.5, 1e5, 1e-3)"
    )
    for k in range(1, n):
        i, j = 2 + k, 1 + k
        lines.append(
            f"SFORCE/{k + 1}, TRANSLATIONAL, I = {i}, J = {j}"
            f", FUNCTION = IMPACT(DM({i}, {j}), VR({i}, {j}), 1.0, 1e6, 1.5, 1e5, 1e-3)"
        )
    lines.append("END")
    return "\n".join(lines) + "\n"


def chain(n):
    lines = [f"A chain of {n} free balls meeting through IMPACT (scripts/stack_models.py)", "!"]
    lines += ["PART/1, GROUND", "MARKER/1, PART = 1"]
    for k in range(n):
        part, marker = 2 + k, 2 + k
        speed = 1.0 if k % 2 == 0 else -1.0
        lines.append(f"PART/{part}, MASS = 1, CM = {marker}, IP = 0.1, 0.1, 0.1, VX = {speed}")
        lines.append(f"MARKER/{marker}, PART = {part}, QP = {round(k * 1.2, 10)!r}, 0, 0")
    for k in range(1, n):
        i, j = 2 + k, 1 + k
        lines.append(
            f"SFORCE/{k}, TRANSLATIONAL, I = {i}, J = {j}"
            f", FUNCTION = IMPACT(DM({i}, {j}), VR({i}, {j}), 1.0, 1e4, 1.5, 10, 1e-3)"
        )
    lines.append("END")
    return "\n".join(lines) + "\n"


def links(n):
    lines = [f"A chain of {n} links on REVOLUTE joints (scripts/stack_models.py)"]
    lines += ["PART/1, GROUND", "MARKER/1, PART = 1"]
    previous = 1
    for part in range(2, n + 2):
        x = part - 2
        lines.append(f"PART/{part}, MASS = 1, IP = 1, 1, 1, CM = {part * 10}")
        lines.append(f"MARKER/{part * 10}, PART = {part}, QP = {x}.5, 0, 0")
        lines.append(f"MARKER/{part * 10 + 1}, PART = {part}, QP = {x}, 0, 0")
        lines.append(f"MARKER/{part * 10 + 2}, PART = {part}, QP = {x + 1}, 0, 0")
        lines.append(f"JOINT/{part}, REVOLUTE, I = {part * 10 + 1}, J = {previous}")
        previous = part * 10 + 2
    lines += ["ACCGRAV/JGRAV = -9.8", "END"]
    return "\n".join(lines) + "\n"


def diff_stack(n):
    """Heights z_k = DIF(k + 1), speeds v_k = DIF(n + k + 1)."""
    lines = [f"The stack of {n} balls as DIFFs (scripts/stack_models.py)", "!"]
    z = lambda k: f"DIF({k + 1})"
    v = lambda k: f"DIF({n + k + 1})"
    for k in range(n):
        lines.append(f"DIFF/{k + 1}, IC = {round(0.5 + GAP + k * (1.0 + GAP), 10)!r}, FUNCTION = {v(k)}")
    for k in range(n):
        below = (
            f"IMPACT({z(0)}, {v(0)}, 0.5, 1e6, 1.5, 1e5, 1e-3)"
            if k == 0
            else f"IMPACT({z(k)} - {z(k - 1)}, {v(k)} - {v(k - 1)}, 1.0, 1e6, 1.5, 1e5, 1e-3)"
        )
        above = (
            f" - IMPACT({z(k + 1)} - {z(k)}, {v(k + 1)} - {v(k)}, 1.0, 1e6, 1.5, 1e5, 1e-3)"
            if k + 1 < n
            else ""
        )
        lines.append(f"DIFF/{n + k + 1}, IC = 0, FUNCTION = {below}{above} - 9.81")
    lines.append("END")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    kind, n = sys.argv[1], int(sys.argv[2])
    write = {"stack": stack, "chain": chain, "links": links, "diff-stack": diff_stack}[kind]
    sys.stdout.write(write(n))
