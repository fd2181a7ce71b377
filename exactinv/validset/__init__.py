"""The valid-set engine behind one route protocol (docs/design.md, "The route protocol").

``route.py`` the protocol (a route accepts a problem and produces verified
conditions), ``problem.py`` one checked problem, ``families.py`` the set
types (polyhedra, ellipsoids), ``vertex.py``, ``box.py``, ``lp.py``,
``ellipsoid.py`` the routes (``lp_route.py``: the LP route's parametric LP),
``engine.py`` the one engine (valid set,
largest threshold, forward-Euler step) and the public functions,
``results.py`` their results.  Layer: above ``thresholds`` and ``conditions``.
"""
