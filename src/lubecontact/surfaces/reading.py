"""Read a measured surface into heights in metres on a uniform grid.

Two routes:

- an instrument file (some 40 formats: Gwyddion/Wyko/SPIP plain text with a header, X3P,
  SDF, Zygo, Keyence, ...) read by SurfaceTopography, which takes the size and the unit
  from the file;
- a raw height matrix, plain text (one row of the map per line, rows along y, values
  along x, the sliding direction) or ``.npy``, with its size and unit given (``size`` and
  ``unit``: both lengths and heights in that unit). One row, or a 1-D array, is a profile.

Refused, with the reason (``SurfaceError``): an unreadable file, an unknown format, a file
without a size when none is given, a size given for a file whose header gives its own, a
file holding no heights, heights with NaN gaps (undefined points), a non-uniform grid (x-z
pairs at irregular spacing), fewer than ``MIN_POINTS`` points along a direction.
"""

from __future__ import annotations

import hashlib
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "nm": 1e-9}
RAW_SUFFIXES = (".npy", ".txt", ".dat", ".csv")
# Fewer points than this along a direction leave no spectrum to take moments from.
MIN_POINTS = 8


class SurfaceError(ValueError):
    """A surface that cannot be used; the message says why and what is allowed."""


class SizeNotGiven(SurfaceError):
    """A file that gives no size or no unit of its own: a raw height matrix, which only the
    command line can size (--size, --unit); a scene names such a surface through the
    roughness section `lubecontact roughness` writes for it. ``what`` is the fact without
    the command line's advice (``advice``, appended to the message)."""

    def __init__(self, what: str, advice: str = ""):
        self.what = what
        super().__init__(f"{what}; {advice}" if advice else what)


@dataclass(frozen=True)
class Surface:
    """Heights ``z[iy, ix]`` in m (a profile has one row), sampled every ``dx`` (and ``dy``)
    metres; ``periodic`` if the map wraps around (synthetic maps), ``sha256`` of the file."""

    heights: np.ndarray
    dx: float
    dy: float | None
    periodic: bool
    source: str
    sha256: str

    @property
    def is_profile(self) -> bool:
        return self.heights.shape[0] == 1

    @property
    def size(self) -> tuple[float, ...]:
        ny, nx = self.heights.shape
        return (nx * self.dx,) if self.is_profile else (nx * self.dx, ny * self.dy)


def file_digest(path) -> str:
    """sha256 of the file's bytes (a scene's case hash sees the content, not the name)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as err:
        raise SurfaceError(f"{path}: cannot read ({err.strerror or err})") from err


def read_surface(path, size=None, unit: str | None = None, periodic: bool = False) -> Surface:
    """The surface in ``path``: an instrument file (``size`` None) or a raw matrix."""
    path = Path(path)
    digest = file_digest(path)
    if size is None:
        if path.suffix.lower() == ".npy":
            raise SizeNotGiven(f"{path}: a raw height matrix needs its size (--size LX [LY]) and unit (--unit)")
        heights, dx, dy, periodic = _instrument(path, unit)
    else:
        _refuse_size_for_a_header_with_size(path)
        heights, dx, dy = _raw(path, size, unit)
    return _checked(heights, dx, dy, periodic, str(path), digest)


def from_array(heights, size, unit: str = "m", periodic: bool = False, source: str = "array") -> Surface:
    """A Surface from an in-memory array (rows along y), ``size`` = (LX,) or (LX, LY)."""
    z, dx, dy = _scaled(np.asarray(heights, dtype=float), size, unit, source)
    return _checked(z, dx, dy, periodic, source, hashlib.sha256(z.tobytes()).hexdigest())


def _instrument(path: Path, unit):
    if unit is not None:
        raise SurfaceError(f"{path}: --unit is for a raw matrix with --size; an instrument file gives its own unit")
    try:
        from SurfaceTopography import read_topography
    except ImportError as err:  # a declared dependency; say what is missing if it is not there
        raise SurfaceError(f"{path}: reading instrument files needs SurfaceTopography (pip install SurfaceTopography): {err}") from err
    try:
        topography = read_topography(str(path))
    except Exception as err:  # noqa: BLE001 - the reader's many errors all mean "cannot use this file"
        reason = str(err) or type(err).__name__
        if "physical_sizes" in reason:
            raise SizeNotGiven(f"{path}: the file gives no physical size",
                               "for a raw matrix pass --size LX [LY] and --unit") from err
        raise SurfaceError(f"{path}: cannot read as an instrument file ({type(err).__name__}: {reason})") from err
    if not topography.is_uniform:
        raise SurfaceError(f"{path}: non-uniform grid (irregular x spacing); resample it onto a uniform grid first")
    if topography.unit is None:
        raise SizeNotGiven(f"{path}: the file gives no length unit", "for a raw matrix pass --size and --unit")
    if topography.has_undefined_data:
        missing = int(np.ma.count_masked(topography.heights()))
        raise SurfaceError(f"{path}: {missing} undefined (NaN) points; fill or crop the gaps first")
    topography = topography.to_unit("m")
    z = np.asarray(topography.heights(), dtype=float).T  # SurfaceTopography indexes [x, y]
    pixel = np.atleast_1d(topography.pixel_size)
    if topography.dim == 1:
        return z[np.newaxis, :], float(pixel[0]), None, bool(topography.is_periodic)
    return z, float(pixel[0]), float(pixel[1]), bool(topography.is_periodic)


def _refuse_size_for_a_header_with_size(path: Path) -> None:
    """Refuse --size (and --unit) for a file whose header gives its size: read as a raw
    matrix, its header would be skipped as comments and its own size and unit ignored."""
    if _header_gives_size(path):
        raise SurfaceError(
            f"{path}: the file's header already gives its size and units; drop --size/--unit "
            "(they are for a raw height matrix without a header)"
        )


def _header_gives_size(path: Path) -> bool:
    """Whether the instrument reader finds a physical size in the file's '#' header (a
    headerless matrix or a .npy has none, and is not handed to the reader at all)."""
    if path.suffix.lower() == ".npy" or not _has_comment_header(path):
        return False
    try:
        from SurfaceTopography import open_topography

        return open_topography(str(path)).default_channel.physical_sizes is not None
    except Exception:  # noqa: BLE001 - no reader takes the file: it gives no size of its own
        return False


def _has_comment_header(path: Path) -> bool:
    """Whether '#' lines (which np.loadtxt skips) come before the first line of data."""
    try:
        with path.open(encoding="utf-8", errors="replace") as text:
            for line in text:
                if line.strip():
                    return line.lstrip().startswith("#")
    except OSError:
        return False  # reading the matrix says why
    return False


def _raw(path: Path, size, unit):
    if unit is None:
        raise SurfaceError(f"{path}: a raw height matrix needs its unit (--unit {'|'.join(u for u in UNITS if u.isascii())})")
    try:
        if path.suffix.lower() == ".npy":
            z = np.load(path, allow_pickle=False)
        else:
            z = _text_matrix(path)
    except (OSError, ValueError) as err:
        raise SurfaceError(f"{path}: cannot read as a height matrix ({err})") from err
    return _scaled(np.asarray(z, dtype=float), size, unit, str(path))


def _text_matrix(path: Path) -> np.ndarray:
    """The numbers of a plain text matrix ('#' comments skipped; empty if it holds none,
    without numpy's warning: the caller refuses an empty matrix with its own message)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="loadtxt: input contained no data")
        return np.loadtxt(path, delimiter="," if path.suffix.lower() == ".csv" else None)


def _scaled(z: np.ndarray, size, unit: str, source: str):
    """Heights and sampling intervals in m from a matrix in ``unit`` of the given size."""
    if unit not in UNITS:
        raise SurfaceError(f"{source}: unit {unit!r} unknown; allowed: {', '.join(UNITS)}")
    if z.size == 0:
        raise SurfaceError(f"{source}: empty (holds no heights); give a matrix of heights, one row of the map per line")
    if z.ndim == 1 or (z.ndim == 2 and z.shape[0] == 1):
        z = z.reshape(1, -1)
    elif z.ndim != 2:
        raise SurfaceError(f"{source}: {z.ndim}-dimensional array; allowed: a profile (1-D) or a map (2-D)")
    size = [float(s) for s in np.atleast_1d(size)]
    wanted = 1 if z.shape[0] == 1 else 2
    if len(size) != wanted or not all(np.isfinite(s) and s > 0 for s in size):
        kind = "a profile needs one length LX" if wanted == 1 else "a map needs two lengths LX LY"
        raise SurfaceError(f"{source}: size {size}: {kind}, positive, in --unit")
    scale = UNITS[unit]
    dx = size[0] * scale / z.shape[1]
    dy = size[1] * scale / z.shape[0] if wanted == 2 else None
    return z * scale, dx, dy


def _checked(z, dx, dy, periodic, source, digest) -> Surface:
    bad = int(np.count_nonzero(~np.isfinite(z)))
    if bad:
        raise SurfaceError(f"{source}: {bad} undefined (NaN or infinite) heights; fill or crop the gaps first")
    ny, nx = z.shape
    if nx < MIN_POINTS or 1 < ny < MIN_POINTS:
        raise SurfaceError(f"{source}: {nx} x {ny} points; allowed: at least {MIN_POINTS} along each direction")
    z.setflags(write=False)
    return Surface(z, float(dx), None if dy is None else float(dy), bool(periodic), source, digest)
