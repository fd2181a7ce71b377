"""The polynomial conditions of A_d(h) S subset of S (layer ``conditions``; beyond the paper,
docs/design.md): the exact valid set {h >= 0 : A_d(h) S subset of S} is their common nonnegative set.

``polyhedron.py`` the generator-facet conditions of P (vertices, rays, lines; ConditionSet), ``box.py``
a box's row sign patterns instead of its 2n 2^n pairs, ``ellipsoid.py`` the PSD conditions q_k(h) of an
ellipsoid, ``pruning.py`` and ``pruning_rational.py`` the certified pruning of vertex-facet pairs
(in h, or in u = h/(s + h) for rational methods).  Never imports ``invariance`` or ``monotonicity``.
"""
