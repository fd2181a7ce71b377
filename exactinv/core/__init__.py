"""Exact arithmetic that knows no model (layer ``core``): scalars (the input
boundary), polys (Q[x] primitives), algebraic (RealAlgebraic and the one exact
ordering), roots, intervals, encode (exact value -> JSON), latex, results."""
