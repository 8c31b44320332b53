"""Atomic files: a file is there whole or not at all, so a killed process never leaves a
truncated one that a later run would take for complete."""

from __future__ import annotations

import errno
import os
from contextlib import contextmanager
from pathlib import Path

# A write that fails while its file system has less than this free is taken for a full disk:
# the netCDF library reports one as "NetCDF: HDF error" (a RuntimeError), not as ENOSPC.
FULL_DISK_BYTES = 16 * 2**20


@contextmanager
def atomic_path(path, make_parents: bool = False):
    """Yield a temporary path in ``path``'s directory to write to; on success it is renamed
    to ``path`` in one step, on failure removed. A missing directory is an error (OSError)
    unless ``make_parents``; a failure on a full file system is OSError(ENOSPC), whatever the
    writing library raised."""
    path = Path(path)
    if make_parents:
        path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        yield tmp
        os.replace(tmp, path)
    except OSError:
        raise
    except Exception as err:
        if _free_bytes(path.parent) < FULL_DISK_BYTES:
            raise OSError(errno.ENOSPC, f"No space left on device ({type(err).__name__}: {err})") from err
        raise
    finally:
        if tmp.exists():
            tmp.unlink()


def _free_bytes(directory: Path) -> float:
    """Bytes an unprivileged write may still use in ``directory``'s file system (inf if unknown)."""
    try:
        fs = os.statvfs(directory)
    except OSError:
        return float("inf")
    return fs.f_bavail * fs.f_frsize


def write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (``atomic_path``)."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
