#!/usr/bin/env python3
"""Runs one pytest file of the Python module's suites (CTest, label python).

Exit 77 (CTest: skipped) with the reason when pytest or numpy is missing for this interpreter.
"""
import sys

try:
    import numpy  # noqa: F401
    import pytest
except ImportError as e:
    print(f"SKIPPED: {e.name} is not installed for {sys.executable} (Debian: python3-numpy, "
          "python3-pytest)")
    sys.exit(77)

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]]))
