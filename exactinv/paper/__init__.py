"""One module per result of the paper (layer ``paper``): invariance and gamma*
(Section 2), polynomial thresholds (Theorems 3.4, 3.13), absolute monotonicity
(Definition 3.11), rational thresholds (Theorem 3.12 + errata E2, E2'), forward
Euler (Section 3.3, Lemma 3.14), the paper's bisection (Section 3.1.2, E3) and
``threshold`` (the dispatch).  Never imports :mod:`exactinv.beyond`."""
