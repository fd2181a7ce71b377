"""Exact valid sets past the quadratic wall (issue 13): before vs after, in one run.

For each instance the same computation runs twice:

* before -- commit 17e9024 (every vertex-facet polynomial built; rational
            methods interpolated at m x V level), in a subprocess from a
            temporary git worktree, stopped after ``--cap`` seconds;
* after  -- this tree: certified pruning on graded pieces of [0, T]
            (polynomial methods) or of [0, U] in u = h/(s + h) (rational
            methods), N(h) = D(h) r(hA) on the n x n matrices.

and, where asked, the trusted kernel checks the "after" certificate (its
time / the engine's).  Pruning statistics: pairs, survivors (built as
polynomials), seconds per stage.  Instances: regular polygons (Taylor-4 valid
set), hypercubes (Taylor-4), and the R^6 family: 100 random facets
(integer normals in [-9, 9], b = 1; 4,233 vertices), A = -I + a small skew
matrix (P invariant), with the Taylor-6 valid set, the Taylor-12 largest
threshold, the backward-Euler and the Pade(6,6) valid sets.

Hypercubes take the box route (exactinv/conditions/box.py: the sign patterns of
the rows of N(h), no vertex enumeration); ``--general`` measures the general route
(``box=False``) on them instead, for the same-run ratio.

With ``--kernel-before REV`` the kernel of git revision REV (from a temporary
worktree) and this tree's kernel also check the same certificate file, each
in a fresh ``python -S -m exactinv_check`` subprocess (the kernel's
before/after, in the same run; stopped after ``--cap`` seconds).

Run:  python benchmarks/scale.py [--quick] [--cap SECONDS] [--only NAME ...] [--no-before] [--no-kernel] [--general]
                                 [--kernel-before REV]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from largest import cube_system, polygon  # noqa: E402

import exactinv as ei  # noqa: E402

BEFORE = "17e9024"
ROT = [[-1, "1/2"], ["-1/2", -1]]


def r6():
    rng = random.Random(13)
    n, m = 6, 100
    G = [[rng.randint(-9, 9) for _ in range(n)] for _ in range(m)]
    K = [[Fraction(0)] * n for _ in range(n)]
    for i in range(n):
        for j in range(i + 1, n):
            K[i][j] = Fraction(rng.randint(-3, 3), 20)
            K[j][i] = -K[i][j]
    return ei.LinearSystem([[(-1 if i == j else 0) + K[i][j] for j in range(n)] for i in range(n)]), ei.Polyhedron(G, [1] * m)


def cube(n):
    return cube_system(n, random.Random(n)), ei.Polyhedron.box([-1] * n, [1] * n)


M = ei.methods
INSTANCES = {  # name -> (problem, method, what, kernel check)
    "200-gon T4 valid set": (lambda: (ei.LinearSystem(ROT), polygon(200)), lambda: M.taylor(4), "valid", True),
    "1000-gon T4 valid set": (lambda: (ei.LinearSystem(ROT), polygon(1000)), lambda: M.taylor(4), "valid", True),
    "10000-gon T4 valid set": (lambda: (ei.LinearSystem(ROT), polygon(10000)), lambda: M.taylor(4), "valid", True),
    "cube 2^10 T4 valid set": (lambda: cube(10), lambda: M.taylor(4), "valid", True),
    "cube 2^14 T4 valid set": (lambda: cube(14), lambda: M.taylor(4), "valid", True),
    "cube 2^17 T4 valid set": (lambda: cube(17), lambda: M.taylor(4), "valid", True),
    "cube 2^17 T4 largest threshold": (lambda: cube(17), lambda: M.taylor(4), "largest", True),
    "cube 2^17 T8 valid set": (lambda: cube(17), lambda: M.taylor(8), "valid", True),
    "cube 2^17 BE valid set": (lambda: cube(17), lambda: M.backward_euler(), "valid", True),
    "cube 2^17 Pade(2,2) valid set": (lambda: cube(17), lambda: M.pade(2, 2), "valid", True),
    "R6 T6 valid set": (r6, lambda: M.taylor(6), "valid", True),
    "R6 T12 largest threshold": (r6, lambda: M.taylor(12), "largest", True),
    "R6 BE valid set": (r6, lambda: M.backward_euler(), "valid", True),
    "R6 Pade(6,6) valid set": (r6, lambda: M.pade(6, 6), "valid", True),
}
QUICK = ["200-gon T4 valid set", "cube 2^10 T4 valid set"]


def compute(name, route="box"):
    """(seconds, value text, result) of one instance with the exactinv on the path (problem built untimed;
    its vertices too, unless the box route will not need them).  ``route``: "box" (the default route of
    this tree), "general" (``box=False``) or "old" (the "before" commit, which knows no box route)."""
    problem, method, what, _ = INSTANCES[name]
    S, P = problem()
    if not (route == "box" and name.startswith("cube")):
        P.vertices  # noqa: B018 -- vertex enumeration is not what is measured
    m = method()
    fn = ei.valid_steplengths if what == "valid" else ei.largest_threshold
    kwargs = {"box": False} if route == "general" else {}
    t0 = time.perf_counter()
    result = fn(S, P, m, **kwargs)
    seconds = time.perf_counter() - t0
    text = repr(result.intervals) if what == "valid" else str(result.value)
    return seconds, text, result


def before(name, tree, cap):
    """Seconds of the old route in a subprocess, or None past the cap."""
    env = dict(os.environ, PYTHONPATH=tree)
    cmd = [sys.executable, str(HERE / "scale.py"), "--child", name]
    try:
        out = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=cap, cwd=tree)
    except subprocess.TimeoutExpired:
        return None, None
    data = json.loads(out.stdout.strip().splitlines()[-1])
    return data["seconds"], data["value"]


def kernel_seconds(path, tree, cap):
    """Wall seconds of ``python -S -m exactinv_check -q path`` with the kernel of ``tree``,
    and whether it verified; (None, None) past the cap."""
    cmd = [sys.executable, "-S", "-m", "exactinv_check", "-q", path]
    t0 = time.perf_counter()
    try:
        out = subprocess.run(cmd, env=dict(os.environ, PYTHONPATH=tree), capture_output=True, text=True,
                             timeout=cap, cwd=tree)
    except subprocess.TimeoutExpired:
        return None, None
    return time.perf_counter() - t0, out.returncode == 0


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--cap", type=float, default=120.0)
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--no-before", action="store_true")
    parser.add_argument("--no-kernel", action="store_true")
    parser.add_argument("--general", action="store_true", help="also time the general route (box=False) on cubes")
    parser.add_argument("--kernel-before")
    parser.add_argument("--child")
    args = parser.parse_args(argv)
    if args.child:
        seconds, text, _ = compute(args.child, "old")
        print(json.dumps({"seconds": seconds, "value": text}))
        return
    names = args.only or (QUICK if args.quick else list(INSTANCES))
    with tempfile.TemporaryDirectory() as tmp:
        tree, args.kernel_tree, args.tmp = os.path.join(tmp, "before"), os.path.join(tmp, "kernel-before"), tmp
        made = ([(tree, BEFORE)] if not args.no_before else []) + (
            [(args.kernel_tree, args.kernel_before)] if args.kernel_before else [])
        for path, rev in made:
            subprocess.run(["git", "-C", str(HERE.parent), "worktree", "add", "--detach", path, rev],
                           check=True, capture_output=True)
        try:
            for name in names:
                row(name, tree, args)
        finally:
            for path, _ in made:
                subprocess.run(["git", "-C", str(HERE.parent), "worktree", "remove", "--force", path], capture_output=True)


def _statistics(result):
    """The box route's or the pruning's statistics, with seconds per stage."""
    p, b = result.pruning, result.box
    if b is not None:
        return (f"box route: {b.entries:,} entry polynomials, {b.cells:,} sign patterns, {b.conditions:,} conditions; "
                + ", ".join(f"{stage} {s:.2f}" for stage, s in b.seconds))
    if p is None:
        return "no pruning"
    return (f"pairs {p.pairs:,}, built {p.survivors:,}{'' if p.applied else ' (all: too many survived)'}; "
            + ", ".join(f"{stage} {s:.2f}" for stage, s in p.seconds))


def row(name, tree, args):
    tb, vb = (None, None) if args.no_before else before(name, tree, args.cap)
    ta, va, result = compute(name)
    same = "-" if vb is None else ("same" if vb == va else f"DIFFERENT: {vb}")
    if args.general and result.box is not None:
        tg, vg, _ = compute(name, "general")
        same += f"; general route {tg:.2f} s ({tg / ta:.0f}x), {'same' if vg == va else 'DIFFERENT: ' + vg}"
    print(f"{name:<26} engine {ta:.2f} s (the kernel's check follows)", flush=True)
    kernel = ""
    if INSTANCES[name][3] and not args.no_kernel:
        t0 = time.perf_counter()
        ok = ei.check(result.certificate).ok
        tk = time.perf_counter() - t0
        kernel = f"kernel {tk:.2f} s ({tk / ta:.2f}x engine, {'VERIFIED' if ok else 'REJECTED'})"
    if args.kernel_before and INSTANCES[name][3]:
        path = os.path.join(args.tmp, "certificate.json")
        with open(path, "w", encoding="utf-8") as fh:
            json.dump(result.certificate, fh)
        (t_old, ok_old), (t_new, ok_new) = (kernel_seconds(path, t, args.cap) for t in (args.kernel_tree, str(HERE.parent)))
        def text(t, ok):
            return f"> {args.cap:.0f}" if t is None else f"{t:.2f} s ({'VERIFIED' if ok else 'REJECTED'})"

        ratio = f"{t_old / t_new:.1f}x" if t_old and t_new else "-"
        kernel += (f"\n    kernel by file: before ({args.kernel_before}) {text(t_old, ok_old)}, "
                   f"after {text(t_new, ok_new)}, {ratio}")
    stats = _statistics(result)
    tb_text = f"> {args.cap:.0f}" if tb is None and not args.no_before else ("-" if tb is None else f"{tb:.2f}")
    ratio = f"{tb / ta:.1f}x" if tb else "-"
    print(f"{name:<26} before {tb_text:>7} s  after {ta:7.2f} s  {ratio:>7}  {same}  {kernel}\n    {va[:70]}\n    {stats}",
          flush=True)


if __name__ == "__main__":
    main()
