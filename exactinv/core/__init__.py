"""Exact arithmetic that knows no model (layer ``core``): scalars (the input
boundary), polys (Q[x] primitives), real_algebraic (RealAlgebraic), digits
(certified decimal digits), algebraic (the one exact ordering), roots,
intervals, encode (exact value -> JSON), latex, results."""
