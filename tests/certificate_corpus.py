"""Genuine certificates on a spread of problems, shared by the kernel tests.

Each entry is made by the engine; the kernel tests check them, forge them
and mutate them.  Small on purpose: every certificate here is checked many
times over.
"""

from functools import lru_cache

import exactinv as ei
from exactinv.certificates import certificate

BOX = ei.Polyhedron.box([-1, -1], [1, 1])
ROT = ei.LinearSystem([[-1, 1], [-1, -1]])


def _full(S, P, m, box=True):
    """What `exactinv certify` puts in one certificate: gamma*, forward Euler,
    the paper's threshold, the largest threshold and the valid set (on a box:
    by the box route, unless ``box`` is False -- then with the vertex lists)."""
    results = [ei.optimal_gamma(S, P), ei.forward_euler_threshold(S, P), ei.steplength_threshold(S, P, m),
               ei.largest_threshold(S, P, m, box=box), ei.valid_steplengths(S, P, m, box=box)]
    return certificate(S, P, m, results)


@lru_cache(maxsize=None)
def corpus():
    """name -> certificate (a fresh copy is the caller's job)."""
    M = ei.methods
    out = {
        "box-taylor4": _full(ROT, BOX, M.taylor(4)),
        "box-taylor4-listed": _full(ROT, BOX, M.taylor(4), box=False),
        "box-taylor2": _full(ROT, BOX, M.taylor(2)),
        "box-backward-euler": _full(ROT, BOX, M.backward_euler()),
        "box-trapezoid": _full(ROT, BOX, M.trapezoid()),
        "triangle-rk4": _full(ei.LinearSystem([[-2, 1], [1, -2]]),
                              ei.Polyhedron.from_vertices([[0, 0], [1, 0], [0, 1]]), M.rk4())
        if ei.optimal_gamma(ei.LinearSystem([[-2, 1], [1, -2]]),
                            ei.Polyhedron.from_vertices([[0, 0], [1, 0], [0, 1]])).value != ei.INF else None,
        "orthant-e2": certificate(ei.LinearSystem([[-1, 2], [0, 1]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0]),
                                  M.backward_euler(),
                                  [ei.steplength_threshold(ei.LinearSystem([[-1, 2], [0, 1]]),
                                                           ei.Polyhedron([[-1, 0], [0, -1]], [0, 0]), M.backward_euler()),
                                   ei.largest_threshold(ei.LinearSystem([[-1, 2], [0, 1]]),
                                                        ei.Polyhedron([[-1, 0], [0, -1]], [0, 0]), M.backward_euler()),
                                   ei.valid_steplengths(ei.LinearSystem([[-1, 2], [0, 1]]),
                                                        ei.Polyhedron([[-1, 0], [0, -1]], [0, 0]), M.backward_euler())]),
        "halfplane-e2prime": _full(ei.LinearSystem([[-1, 0], [0, 1]]), ei.Polyhedron([[1, 0]], [1]), M.backward_euler()),
        "gap-set": ei.valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]),
                                        M.polynomial([1, "1/2", "3/4", "1/4"])).certificate,
        "not-invariant": ei.optimal_gamma(ei.LinearSystem([[1, 0], [1, 1]]), BOX).certificate,
        "minus-infinity": ei.optimal_gamma(ei.LinearSystem([[-1, 0], [0, -2]]),
                                           ei.Polyhedron([[1, 0], [-1, 0]], [0, 0])).certificate,
        "radius-sdirk": ei.absolute_monotonicity_radius(M.rational([1, "1/2"], [1, "-1/2", "1/16"])).certificate,
        "radius-rk4": ei.absolute_monotonicity_radius(M.rk4()).certificate,
        "discrete": certificate(ei.LinearSystem([[0, 0], [0, 0]]), BOX, None,
                                [ei.discrete_invariance([[0, 1], [-1, 0]], BOX),
                                 ei.discrete_invariance([[1, 1], [0, 1]], BOX)]),
        "invariance": certificate(ROT, BOX, None, [ei.continuous_invariance(ROT, BOX)]),
    }
    return {k: v for k, v in out.items() if v is not None}
