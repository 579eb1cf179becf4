#!/usr/bin/env python3
"""A bead on a closed loop: the dataset of a PTCV on a closed cubic spline
through N points of the three-lobed curve r = 1 + 0.2 cos 3a (x stretched
by 2), the bead started at (2.4, 0) at 3 m/s upwards under gravity.

    python3 scripts/ptcv_loop.py N [ORDER] > loop.adm
    mbexpr simulate loop.adm --end 5 --steps 1 --rtol 1e-8 --method dop853

BENCHMARKS.md ("PTCV: the knots as switches") runs it at N = 12 and 100.
"""
import math
import sys

count = int(sys.argv[1])
order = int(sys.argv[2]) if len(sys.argv) > 2 else 4
points = []
for k in range(count):
    angle = 2 * math.pi * k / count
    radius = 1 + 0.2 * math.cos(3 * angle)
    points.append((2 * radius * math.cos(angle), radius * math.sin(angle), 0))
values = ", ".join(f"{x:.9f}, {y:.9f}, {z}" for x, y, z in points)
print(f"""bead on a three-lobed loop
PART/1, GROUND
MARKER/10, PART = 1
MARKER/11, PART = 1, FLOATING
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1, VY = 3
MARKER/20, PART = 2, QP = {points[0][0]:.9f}, 0, 0
MATRIX/1, FULL = RORDER, ROWS = {count}, COLUMNS = 3, VALUES = {values}
CURVE/1, CLOSED, CURVE_POINTS, MATRIX = 1, ORDER = {order}
PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1
ACCGRAV/JGRAV = -9.81
REQUEST/1, F2 = DX(20), F3 = DY(20), F4 = DZ(20)
END""")
