"""Atomic files: a file is there whole or not at all, so a killed process never leaves a
truncated one that a later run would take for complete."""

from __future__ import annotations

import os
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def atomic_path(path, make_parents: bool = False):
    """Yield a temporary path in ``path``'s directory to write to; on success it is renamed
    to ``path`` in one step, on failure removed. A missing directory is an error (OSError)
    unless ``make_parents``."""
    path = Path(path)
    if make_parents:
        path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (``atomic_path``)."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
