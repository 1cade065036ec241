"""Test-suite settings.

In CI (CI=true) hypothesis runs derandomized: the same examples every run, so a
submission lands or fails on its own merits. Locally it explores new examples on every
run and keeps failures in its database, which is how new edge cases get found.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
settings.register_profile("dev", deadline=None)
settings.load_profile("ci" if os.environ.get("CI") else "dev")
