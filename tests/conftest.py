"""Test-wide guards: a NaN or an overflow produced silently by numpy is a failure.

Underflow stays allowed (far Gaussian tails underflow to 0 by design); intentional
divisions by zero are wrapped in ``np.errstate`` where they happen.
"""

import numpy as np
import pytest


@pytest.fixture(autouse=True)
def numpy_raises_on_invalid_and_overflow():
    with np.errstate(invalid="raise", over="raise", divide="raise", under="ignore"):
        yield
