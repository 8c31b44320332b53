"""The installed package's version (importlib.metadata), looked up once per process.

Case files, series and the accuracy study record it; ``lubecontact.__version__`` reads it
through here lazily, so ``import lubecontact`` does not load importlib.metadata.
"""

from __future__ import annotations

from functools import cache
from importlib.metadata import PackageNotFoundError, version


@cache
def package_version() -> str:
    """The version of the installed distribution, or "0+unknown" in a source tree that is
    not installed."""
    try:
        return version("lubecontact")
    except PackageNotFoundError:
        return "0+unknown"
