"""Erratum E2 on polygons: the rational threshold's alpha(H) decision, before and after issue 22.

Backward Euler (rho = oo, pole z_p = 1), A = -2I, P a polygon with N rational vertices on
the ellipse x^2/4 + y^2 = 1 (N facets, b > 0).  gamma* and its certificate H (N x N) are
computed first and not timed; then `rational_threshold` (Theorem 3.12 with errata E2, E2'):

* before -- today's path until issue 22: alpha(H) = the largest real root of the dense
            characteristic polynomial of H, always (FLINT; no alarm interrupts it, so each
            run is a subprocess killed after --cap seconds);
* after  -- thresholds/spectral.py: alpha(H) only where E2 may bind (Collatz-Wielandt with
            v = b: Hb <= 0 gives alpha(H) <= 0 here, so the bound never binds).

Each cell is a fresh subprocess: seconds of the threshold computation and its peak memory
(growth of the peak resident set over the resident set before it, MB; FLINT's allocations
included).  `kernel s`: exactinv_check re-proving the certificate of the after run.

Run:  python benchmarks/e2_polygon.py [--sizes 50 100 ...] [--cap 120] [--after-only]
"""

from __future__ import annotations

import argparse
import math
import multiprocessing as mp
import resource
import time
from fractions import Fraction


def ellipse_polygon(N: int):
    import exactinv as ei
    pts, k = set(), 0
    while len(pts) < N:
        theta = -math.pi + 2 * math.pi * (k + 0.5) / N
        s = Fraction(math.tan(theta / 2)).limit_denominator(10**6)
        pts.add((2 * (1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)))
        k += 1
    return ei.Polyhedron.from_vertices(sorted(pts))


def _rss_mb() -> float:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize() / 2**20


def _run(N: int, route: str, out, started) -> None:
    import exactinv as ei
    from exactinv.core.roots import real_roots
    from exactinv.thresholds import rational
    from exactinv_check import check
    P, S, m = ellipse_polygon(N), ei.LinearSystem([[-2, 0], [0, -2]]), ei.methods.backward_euler()
    g = ei.optimal_gamma(S, P)
    _ = g.H_flint  # H built now (cached), outside the timed E2 decision
    rational.absolute_monotonicity_radius(m)  # cached: not part of the E2 decision
    if route == "before":  # the code path before issue 22: alpha(H) always, from the dense charpoly
        rational._e2_may_bind = lambda H, gamma, z_p, value, nonpositive: z_p is not None and H.nrows() > 0
        rational.spectral_abscissa = lambda H: real_roots(H.charpoly())[-1][0]
    base = _rss_mb()
    started.set()
    t0 = time.perf_counter()
    t = rational.rational_threshold(m, g)
    seconds = time.perf_counter() - t0
    peak = max(0.0, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 - base)
    kernel = None
    if route == "after":
        t0 = time.perf_counter()
        ok = check(t.certificate).ok
        kernel = time.perf_counter() - t0 if ok else "REJECTED"
    out.put({"seconds": seconds, "peak_mb": peak, "value": str(t.value), "kernel": kernel})


def measure(N: int, route: str, cap: float) -> dict | None:
    """One run in a fresh process; None when the timed part exceeds ``cap`` seconds (killed:
    FLINT's charpoly cannot be interrupted otherwise)."""
    ctx = mp.get_context("fork")
    out, started = ctx.Queue(), ctx.Event()
    p = ctx.Process(target=_run, args=(N, route, out, started))
    p.start()
    while not started.wait(timeout=1):
        if not p.is_alive():
            return None
    try:
        result = out.get(timeout=cap)
    except Exception:
        result = None
    if result is None:
        p.kill()
    p.join()
    return result


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sizes", type=int, nargs="*", default=[50, 100, 150, 233, 500, 1000])
    parser.add_argument("--cap", type=float, default=120.0, help="seconds before a 'before' run is given up")
    parser.add_argument("--after-only", action="store_true", help="skip the before route")
    args = parser.parse_args()
    print(f"{'facets':>7} {'before s':>10} {'before MB':>10} {'after s':>9} {'after MB':>9} {'kernel s':>9}  tau")
    skip_before = args.after_only
    for N in args.sizes:
        before = None if skip_before else measure(N, "before", args.cap)
        skip_before = before is None  # larger sizes take longer still
        after = measure(N, "after", args.cap)
        b_s = f"> {args.cap:.0f}" if before is None else f"{before['seconds']:.3f}"
        b_m = "-" if before is None else f"{before['peak_mb']:.1f}"
        k = after["kernel"]
        print(f"{N:>7} {b_s:>10} {b_m:>10} {after['seconds']:>9.3f} {after['peak_mb']:>9.1f} "
              f"{k if isinstance(k, str) else f'{k:.2f}':>9}  {after['value']}", flush=True)


if __name__ == "__main__":
    main()
