"""Discretization methods as exact stability functions r = g/h (paper, Section 3).

A one-step method applied to x' = Ax gives x+ = r(dt A) x.  For Taylor and
general polynomial methods r(z) = sum_k sigma_k z^k (sigma_0 = 1, Section
3.1); for rational methods r = g/h with r(0) = 1 (Section 3.2) -- backward
Euler, the theta-methods, Pade approximants and Runge-Kutta stability
functions R(z) = det(I - zA + z e b^T)/det(I - zA) of rational Butcher
tableaux.  Coefficients are Fractions; g and h are stored coprime with
h(0) = 1.

The methods are built in three modules, gathered here (``exactinv.methods``):
:mod:`~exactinv.model.method` (the type), :mod:`~exactinv.model.families`
(Taylor, polynomial, rational, theta, Pade, Butcher tableaux) and
:mod:`~exactinv.model.presets` (named Runge-Kutta methods), and
:mod:`~exactinv.model.nodepy_methods` (NodePy's method objects, ``from_nodepy``).
"""

from .families import (
    backward_euler,
    forward_euler,
    from_butcher,
    implicit_midpoint,
    pade,
    polynomial,
    rational,
    taylor,
    theta,
    trapezoid,
)
from .method import Method, matrix_polynomial
from .nodepy_methods import from_nodepy
from .presets import (
    PRESETS,
    gauss2,
    heun,
    lobatto_iiic2,
    lobatto_iiic3,
    lobatto_iiic4,
    preset,
    radau_iia1,
    radau_iia2,
    radau_iia3,
    rk4,
    sdirk2,
    sdirk4,
    ssp_sdirk,
    ssprk22,
    ssprk33,
    ssprk_s1,
)

__all__ = [
    "Method", "matrix_polynomial", "taylor", "polynomial", "forward_euler", "rational", "theta",
    "backward_euler", "trapezoid", "implicit_midpoint", "pade", "from_butcher", "heun", "ssprk22",
    "ssprk33", "rk4", "ssprk_s1", "radau_iia2", "lobatto_iiic2", "gauss2", "radau_iia1",
    "radau_iia3", "lobatto_iiic3", "lobatto_iiic4", "sdirk2", "sdirk4", "ssp_sdirk", "PRESETS",
    "preset", "from_nodepy",
]
