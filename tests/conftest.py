"""Test-wide guards: a NaN or an overflow produced silently by numpy is a failure; the
surface cache is the session's own.

Underflow stays allowed (far Gaussian tails underflow to 0 by design); intentional
divisions by zero are wrapped in ``np.errstate`` where they happen.
"""

import numpy as np
import pytest


@pytest.fixture(autouse=True, scope="session")
def private_surface_cache(tmp_path_factory):
    """Analysed surfaces (lubecontact.surfaces.measured) go to a cache of this test session,
    not the user's, so no test depends on what an earlier run left there."""
    import os

    os.environ["LUBECONTACT_CACHE"] = str(tmp_path_factory.mktemp("surface_cache"))
    yield


@pytest.fixture(autouse=True)
def numpy_raises_on_invalid_and_overflow():
    with np.errstate(invalid="raise", over="raise", divide="raise", under="ignore"):
        yield
