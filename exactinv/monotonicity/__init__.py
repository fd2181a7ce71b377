"""The radius of absolute monotonicity rho(r) of a stability function r = g/h (layer ``monotonicity``;
paper, Section 3.2, Definition 3.11, with erratum E1).

``radius.py`` the definition and the polynomial case, ``result.py`` the result and its certificate claim,
``tail.py`` a rational r with poles (Pringsheim, the tail), ``poles.py`` the poles seen from -kappa,
``line_poles.py`` poles on p*'s vertical line, ``balanced_tie.py`` balanced ties of several poles,
``bernstein.py`` rho = oo by Bernstein's theorem.  Never imports ``invariance`` or ``conditions``.
"""
