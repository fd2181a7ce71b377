"""What users touch (layer ``interfaces``): the problem file format, the
pipeline (``certify`` -> ``Report``), the oracle, the explainer, display and
plots, the comparison table and the command line."""
