"""Where a result may be written (the CLI's ``--out``), checked before anything is solved.

Allowed: a new path, or an existing regular file (replaced atomically by output.write_case:
temp file in the same directory + rename). Refused: anything else at the path (directory,
device, FIFO, socket), a path that is also an input (the scene file), and a directory in
which a file cannot be created (permissions, read-only mount, /proc), tried with a real
temporary file. Missing parent directories are created at write time.

Symbolic links are followed: ``--out link.nc`` writes the file the link points to (the
same checks apply to that target) and the link stays a link. That is what a link to a
results disk is for; replacing the link by a regular file would silently detach it.
"""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path


class OutputPathError(ValueError):
    """An unusable output path; the message names it and says why."""


_KINDS = {
    stat.S_ISDIR: "a directory",
    stat.S_ISCHR: "a character device",
    stat.S_ISBLK: "a block device",
    stat.S_ISFIFO: "a FIFO (named pipe)",
    stat.S_ISSOCK: "a socket",
}


def _kind(mode: int) -> str:
    return next((name for test, name in _KINDS.items() if test(mode)), "not a regular file")


def _same(a: Path, b: Path) -> bool:
    try:
        return a.exists() and b.exists() and os.path.samefile(a, b)
    except OSError:
        return False


def check_output_path(path, inputs=(), option: str = "--out") -> Path:
    """The path to write (symlinks resolved), or OutputPathError naming ``path``."""
    given = Path(path)
    target = given.resolve()  # follows links, dangling ones included
    shown = f"{option} {str(given)!r}" + (f" (a link to {str(target)!r})" if given.is_symlink() else "")
    if target.exists():
        mode = target.stat().st_mode
        if not stat.S_ISREG(mode):
            raise OutputPathError(f"{shown}: is {_kind(mode)}; allowed: a new path or a regular file")
    for source in inputs:
        if target == Path(source).resolve() or _same(target, Path(source)):
            raise OutputPathError(f"{shown}: is also an input ({source}); write the result elsewhere")
    directory = target.parent
    while not directory.exists():
        directory = directory.parent
    if not directory.is_dir():
        raise OutputPathError(f"{shown}: {directory} is not a directory")
    try:
        fd, probe = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".probe", dir=directory)
    except OSError as err:
        raise OutputPathError(f"{shown}: cannot create a file in {directory}: {err.strerror or err}") from None
    os.close(fd)
    os.unlink(probe)
    return target
