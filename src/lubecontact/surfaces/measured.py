"""A scene's ``roughness.surface``: McCool's parameters of a self-describing surface file.

The analysis (reading the instrument file with SurfaceTopography, spectral moments,
McCool's formulas) is a pure function of the file's content, the cut-off, this package's
analysis sources and the reader's version. Its result is kept in memory and on disk
(``cache_dir``), so a process that only needs a scene's hash (planning the workflow, a
cluster job re-reading the Snakefile) neither imports the reader (0.9 s) nor reads the
file (0.4 s for a 512^2 map).
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
from dataclasses import asdict
from importlib import metadata
from pathlib import Path

from lubecontact.io.atomic_write import write_text
from lubecontact.surfaces.mccool import McCool, parameters
from lubecontact.surfaces.moments import Moments, spectral_moments
from lubecontact.surfaces.reading import file_digest, read_surface

# the modules whose code decides the parameters (a change of any of them misses the cache)
_ANALYSIS_SOURCES = ("reading.py", "moments.py", "mccool.py", "measured.py")


def scene_roughness(path, cutoff: float | None = None) -> tuple[McCool, str]:
    """(parameters, sha256 of the file) of an instrument file (size and unit in the file),
    with the short-wavelength cut-off ``cutoff`` (m; None: the default of ``moments``).
    Cached on the file's content, so a grid of many scenes reads and analyses it once."""
    digest = file_digest(path)
    return _cached(str(path), digest, cutoff), digest


def cache_dir() -> Path | None:
    """Where analysed surfaces are kept: $LUBECONTACT_CACHE, else the user's cache
    directory ($XDG_CACHE_HOME or ~/.cache) / lubecontact / surfaces; None without a home."""
    if os.environ.get("LUBECONTACT_CACHE"):
        return Path(os.environ["LUBECONTACT_CACHE"])
    try:
        base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    except RuntimeError:  # no home directory to be found: analyse every time
        return None
    return Path(base) / "lubecontact" / "surfaces"


@functools.cache
def _analysis_fingerprint() -> str:
    digest = hashlib.sha256()
    for name in _ANALYSIS_SOURCES:
        digest.update(name.encode() + b"\0" + (Path(__file__).parent / name).read_bytes())
    try:
        digest.update(metadata.version("SurfaceTopography").encode())
    except metadata.PackageNotFoundError:
        pass  # reading then fails with its own message
    return digest.hexdigest()


@functools.lru_cache(maxsize=32)
def _cached(path: str, digest: str, cutoff: float | None) -> McCool:
    key = hashlib.sha256(f"{digest}|{cutoff!r}|{_analysis_fingerprint()}".encode()).hexdigest()[:32]
    directory = cache_dir()
    stored = None if directory is None else directory / f"{key}.json"
    kept = None if stored is None else _read_kept(stored)
    if kept is not None:
        return kept
    result = parameters(spectral_moments(read_surface(path), cutoff))
    if stored is not None:
        try:  # a cache that cannot be written costs time only
            stored.parent.mkdir(parents=True, exist_ok=True)
            write_text(stored, json.dumps(asdict(result)))
        except OSError:
            pass
    return result


def _read_kept(stored: Path) -> McCool | None:
    """The parameters kept in ``stored``, or None when it is not there or not readable as such."""
    try:
        fields = json.loads(stored.read_text())
        moments = fields.pop("moments")
        return McCool(**fields, moments=Moments(**{k: tuple(v) if isinstance(v, list) else v for k, v in moments.items()}))
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        return None
