import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    max_examples=int(os.environ.get("EXACTINV_EXAMPLES", "25")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.load_profile("ci")

import sys

sys.path.insert(0, os.path.dirname(__file__))  # tests/strategies.py, under --import-mode=importlib
