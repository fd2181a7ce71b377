import os
import sys

# the kernel's test files share a few helpers by module name (test_kernel_attacks, test_speed_paths), as the files
# directly under tests/ do (tests/conftest.py)
sys.path.insert(0, os.path.dirname(__file__))
