#!/usr/bin/env python3
"""Gantry's `gantry check` beside FabMo-Engine's OpenSBP parser on the same generated files
(sbp_bench_files.py), whole processes alternated, best of REPS by CPU time (user + sys, which
other work on a shared machine hardly moves) and by wall clock. Issue 27's target: >= 15x.

usage: fabmo_side_by_side.py FABMO_DIR [BUILD_DIR] [REPS]
FABMO_DIR holds FabMo-Engine's runtime/opensbp (any checkout of github.com/FabMo/FabMo-Engine);
its log.js is replaced by a stub in a copy when the real one cannot load (it needs npm
packages the parser does not). Nothing of FabMo's is in this repository."""
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
fabmo = os.path.abspath(sys.argv[1])
build = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "..", "build"))
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
work = tempfile.mkdtemp(prefix="gantry_fabmo_")
subprocess.run([sys.executable, os.path.join(here, "sbp_bench_files.py"), work], check=True)

# A copy of the parser with a stub logger beside it (../../log from runtime/opensbp).
copy = os.path.join(work, "fabmo")
shutil.copytree(os.path.join(fabmo, "runtime", "opensbp"), os.path.join(copy, "runtime", "opensbp"))
with open(os.path.join(copy, "log.js"), "w") as f:
    f.write("const nop = () => {};\nexports.logger = () => ({debug: nop, info: nop, warn: nop,"
            " error: console.error, tick: nop, tock: nop});\n")

def run(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed: {done.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall

gantry = os.path.join(build, "gantry")
print(f"{'file':<12}{'gantry cpu':>12}{'fabmo cpu':>12}{'ratio':>8}{'gantry wall':>13}"
      f"{'fabmo wall':>12}{'ratio':>8}   target >= 15x")
for name in ("simple.sbp", "mixed.sbp"):
    path = os.path.join(work, name)
    g, n = [], []
    for _ in range(reps):
        g.append(run([gantry, "check", path]))
        n.append(run(["node", os.path.join(here, "fabmo_parse.js"), copy, path]))
    gc, gw = min(c for c, _ in g), min(w for _, w in g)
    nc, nw = min(c for c, _ in n), min(w for _, w in n)
    verdict = "PASS" if nc / gc >= 15 else "MISS"
    print(f"{name:<12}{gc:>11.3f}s{nc:>11.3f}s{nc / gc:>7.1f}x{gw:>12.3f}s{nw:>11.3f}s"
          f"{nw / gw:>7.1f}x   {verdict}")
shutil.rmtree(work)
