"""Beyond the paper (layer ``beyond``): the condition polynomials, the exact
valid sets and the exact largest thresholds.  Never imports :mod:`exactinv.paper`."""
