"""The radius of absolute monotonicity: the engine of issue 14 against the one before it (commit 17e9024).

In one run, per method: the old engine (pure-Python VCA bisection on the d_j, recomputed as the coefficient
count doubles up to 64) in a subprocess with a time cap, and the new one (FLINT pole structure, tie
polynomial, tail index bounded before the scan, Descartes filter, FLINT isolation) in process; the new
certificate's kernel check is timed too.  "cap" means the old engine was stopped at the cap.

Run:  python benchmarks/radius.py [--cap SECONDS] [--quick]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tarfile
import tempfile
import time
from io import BytesIO
from pathlib import Path

import exactinv as ei
from exactinv import methods as M

ROOT = Path(__file__).resolve().parents[1]
OLD_COMMIT = "17e9024"
OLD_RUN = """
import json, sys, time
from exactinv.model import methods as M
from exactinv.monotonicity.radius import absolute_monotonicity_radius
num, den = json.loads(sys.argv[1])
m = M.rational(num, den) if len(den) > 1 else M.polynomial(num)
t = time.perf_counter()
try:
    r = absolute_monotonicity_radius(m)
    out = [time.perf_counter() - t, r.reason, float(r.value)]
except Exception as e:
    out = [time.perf_counter() - t, type(e).__name__, None]
print(json.dumps(out))
"""


def cases(quick: bool = False) -> dict:
    out = {f"pade({k},{l})": M.pade(k, l) for k in range(7) for l in range(7)}
    for name in ["lobatto_iiic2", "lobatto_iiic3", "lobatto_iiic4", "radau_iia1", "radau_iia2", "radau_iia3",
                 "sdirk4"]:
        out[name] = M.preset(name)
    out.update({f"sdirk2({g})": M.sdirk2(g) for g in ["1/4", "1/3", "1/2"]})
    out.update({f"ssp_sdirk({s})": M.ssp_sdirk(s) for s in (2, 4, 6)})
    out["1/(1-z+z^2/4-z^3/40)"] = M.rational([1], [1, -1, "1/4", "-1/40"])
    out["1/(1-2z/3-z^2/4)"] = M.rational([1], [1, "-2/3", "-1/4"])
    if quick:
        out = {k: v for k, v in out.items() if k in ("pade(1,3)", "pade(2,3)", "pade(6,5)", "lobatto_iiic3")}
    return out


def old_checkout() -> str:
    tmp = tempfile.mkdtemp(prefix="exactinv-old-")
    data = subprocess.run(["git", "-C", str(ROOT), "archive", OLD_COMMIT, "exactinv"], check=True,
                          capture_output=True).stdout
    tarfile.open(fileobj=BytesIO(data)).extractall(tmp)
    return tmp


def run_old(path: str, m, cap: float):
    arg = json.dumps([[str(c) for c in m.numerator], [str(c) for c in m.denominator]])
    try:
        done = subprocess.run([sys.executable, "-c", OLD_RUN, arg], capture_output=True, text=True, timeout=cap,
                              env={"PYTHONPATH": path, "PATH": "/usr/bin:/bin"}, cwd=path)  # not the new checkout
        return json.loads(done.stdout.strip().splitlines()[-1])
    except subprocess.TimeoutExpired:
        return [cap, "cap", None]


def run_new(m):
    t = time.perf_counter()
    try:
        r = ei.absolute_monotonicity_radius(m)
    except ei.Undecided:
        return time.perf_counter() - t, "Undecided", None, None
    engine = time.perf_counter() - t
    t = time.perf_counter()
    ok = ei.check(r.certificate).ok
    return engine, r.reason, float(r.value), (time.perf_counter() - t) if ok else "REJECTED"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cap", type=float, default=60.0)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    old = old_checkout()
    print("| method | before s | before outcome | after s | after outcome | rho | kernel s | before/after |")
    print("|---|---:|---|---:|---|---:|---:|---:|")
    for name, m in cases(args.quick).items():
        t_old, why_old, _ = run_old(old, m, args.cap)
        t_new, why_new, value, kernel = run_new(m)
        shown = "cap" if why_old == "cap" else why_old
        before = f"≥ {args.cap:.0f}" if why_old == "cap" else f"{t_old:.3f}"
        kernel_s = kernel if isinstance(kernel, str) else ("–" if kernel is None else f"{kernel:.3f}")
        rho = "–" if value is None else f"{value:.6g}"
        print(f"| {name} | {before} | {shown} | {t_new:.3f} | {why_new} | {rho} | {kernel_s} | "
              f"{(t_old / t_new if t_new else float('inf')):.0f}{'+' if why_old == 'cap' else ''} |", flush=True)


if __name__ == "__main__":
    main()
