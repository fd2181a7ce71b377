"""Shared by the pruning tests (polynomial and rational routes): a problem's data as Fraction
lists for the kernel's functions, a polygon's facet rows, and the kernel pruning test's packed
slot tests counted (the ``forced`` fixture is in conftest.py)."""

from fractions import Fraction

from kernel_deadline import TooSlow

from exactinv_check.failure import CheckFailure
from exactinv_check.routes import pruning


def fractions_of(S, P):
    """(A, G, b, vertices) of a system and a polyhedron, as Fraction lists."""
    A = [[Fraction(x) for x in r] for r in S.A]
    return A, [[Fraction(x) for x in r] for r in P.G], [Fraction(x) for x in P.b], [list(map(Fraction, v)) for v in P.vertices]


def polygon_rows(pts):
    """(G, b): the facet rows of the convex polygon with these vertices, counter-clockwise."""
    G, b = [], []
    for (x1, y1), (x2, y2) in zip(pts, pts[1:] + pts[:1]):
        g = [y2 - y1, x1 - x2]
        G.append(g)
        b.append(g[0] * x1 + g[1] * y1)
    return G, b


def count_slot_tests(monkeypatch, G, b, V, N, T, limit):
    """The packed slot tests of pruning.survivors (counted, not timed); TooSlow once they pass
    ``limit``; a CheckFailure (a price) ends the count as well."""
    counted = [0]
    original = pruning._Packed.outside

    def counting(self, box):
        counted[0] += len(self.J)
        if counted[0] > limit:
            raise TooSlow(f"{counted[0]} slot tests")
        return original(self, box)

    monkeypatch.setattr(pruning._Packed, "outside", counting)
    try:
        pruning.survivors(G, b, V, N, T)
    except CheckFailure:
        pass
    finally:
        monkeypatch.setattr(pruning._Packed, "outside", original)
    return counted[0]


def circle_polygon(m):
    """m rational points on the unit circle, counter-clockwise from (-1, 0), and their rows."""
    pts = []
    for a in range(m):
        s = Fraction(int((2 * a + 1 - m) * 10**6 // m), 10**6) if a else None  # tan(theta/2) in (-1, 1), increasing
        pts.append((Fraction(-1), Fraction(0)) if s is None else ((1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)))
    pts = [pts[0]] + sorted(set(pts[1:]), key=lambda p: (p[1] >= 0, p[0] if p[1] < 0 else -p[0]))
    return pts, *polygon_rows(pts)
