"""Atomic text files: a file is there whole or not at all, so a killed process never
leaves a truncated one that a later run would take for complete."""

from __future__ import annotations

import os
from pathlib import Path


def write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file in the same directory and one
    rename; the temporary file is removed if the write fails."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
