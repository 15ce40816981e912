#!/usr/bin/env python3
"""Writes the two OpenSBP files the side-by-side figures use (docs/performance.md):
simple.sbp, LINES lines of `M3, x, y, z` with literal numbers, and mixed.sbp, LINES lines of
labels, assignments with functions, IF...GOTO and GOSUB to subroutines at the file's end
(more than 1 MiB from most callers), every block's numbers different.
usage: sbp_bench_files.py OUTDIR [LINES]"""
import os
import random
import sys

out = sys.argv[1]
lines = int(sys.argv[2]) if len(sys.argv) > 2 else 200000
os.makedirs(out, exist_ok=True)
rng = random.Random(42)

with open(os.path.join(out, "simple.sbp"), "w") as f:
    f.write("SA\nMS, 4, 2\n")
    for _ in range(lines - 2):
        f.write(f"M3, {rng.uniform(1, 23):.4f}, {rng.uniform(1, 17):.4f}, {rng.uniform(-0.5, 0.5):.4f}\n")

with open(os.path.join(out, "mixed.sbp"), "w") as f:
    f.write("SA\n&b = 1\n&c = 0\n")
    for k in range((lines - 35) // 8):
        f.write(f"B{k}:\n"
                f"&a = {rng.uniform(0, 10):.3f} + ABS(&b - {rng.uniform(0, 5):.3f})\n"
                f"&b = SQR(&a * {rng.uniform(1, 3):.3f}) MOD 7\n"
                f"IF &a > {rng.uniform(5, 15):.3f} THEN GOTO C{k}\n"
                f"GOSUB S{k % 10}\n"
                f"C{k}:\n"
                f"&c = &c + &a * {rng.uniform(0, 1):.4f}\n"
                f"IF &a < -1000 THEN GOTO B0\n")
    f.write("END\n")
    for j in range(10):
        f.write(f"S{j}:\n&d = SIN(&a + {j})\nRETURN\n")
