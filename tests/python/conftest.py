import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))

DATA = os.path.join(os.path.dirname(__file__), "..", "data")


@pytest.fixture
def rng():
    return np.random.default_rng(7)


def random_knots(rng, p, elements):
    """A clamped knot vector on [0, 1] with random interior knots (one double)."""
    interior = np.sort(rng.uniform(0.05, 0.95, elements - 1))
    interior = np.concatenate([interior, interior[:1]]) if elements > 2 else interior
    return np.concatenate([np.zeros(p + 1), np.sort(interior), np.ones(p + 1)])
