"""The paper's steplength thresholds (layer ``thresholds``; paper, Section 3), corrected where it errs.

``polynomial.py`` polynomial methods (Theorems 3.4, 3.13; the f_i), ``rational.py`` rational methods
(Theorem 3.12 with errata E2, E2'), ``spectral.py`` alpha(H) where E2 may bind, ``steplength.py`` the
threshold of any method (steplength_threshold), ``forward_euler.py`` 1/gamma* (Section 3.3, Lemma 3.14),
``ellipsoid_forward_euler.py`` forward Euler on an ellipsoid as a generalised eigenvalue (beyond the
paper), ``bisection.py`` the paper's Sturm bisection (Section 3.1.2, erratum E3) as a reference.
Built on ``invariance`` (gamma*) and ``monotonicity`` (rho).
"""
