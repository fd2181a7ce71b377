"""Invariance (layer ``invariance``; paper, Section 2): is a set S invariant for x' = Ax or x+ = A_d x?

``polyhedra.py`` continuous and discrete invariance of P = {x : Gx <= b} (the certificates H and H~,
Farkas' lemma), ``gamma_star.py`` gamma* = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0} with its H
(Lemma 3.14) -- its rows by ``gamma_batch.py`` (sparse G) or ``gamma_dense.py`` (dense G) --,
``witness.py`` the exact point of P leaving through a facet, ``ellipsoids.py`` the same questions for
E = {x : x^T Q x <= 1} (beyond the paper: exact LDL^T).  Never imports ``monotonicity`` or ``conditions``.
"""
