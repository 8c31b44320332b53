"""A scene's ``roughness.surface``: McCool's parameters of a self-describing surface file."""

from __future__ import annotations

import functools

from .mccool import McCool, parameters
from .moments import spectral_moments
from .reading import file_digest, read_surface


def scene_roughness(path, cutoff: float | None = None) -> tuple[McCool, str]:
    """(parameters, sha256 of the file) of an instrument file (size and unit in the file),
    with the short-wavelength cut-off ``cutoff`` (m; None: the default of ``moments``).
    Cached on the file's content, so a grid of many scenes reads and analyses it once."""
    digest = file_digest(path)
    return _cached(str(path), digest, cutoff), digest


@functools.lru_cache(maxsize=32)
def _cached(path: str, digest: str, cutoff: float | None) -> McCool:
    return parameters(spectral_moments(read_surface(path), cutoff))
