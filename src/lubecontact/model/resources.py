"""What a solve will cost before it starts: memory and wall time from the measured laws.

Measured on the project's machine (bench/run.py; peak RSS of ``lubecontact solve`` at
1 m/s, one core): 51^2 nodes 222 MB and ~0.1 s, 201^2 308 MB and ~1.1 s, 301^2 359 MB and
3.7 s, 501^2 638 MB and 10.9 s, and 2000^2 (issue 13) above 10.8 GB. The memory law is an
upper envelope of those points: the interpreter and libraries (~220 MB) plus 2.7 kB per
mesh node (the sparse LU factors of Reynolds grow faster than the node count, so small
meshes are over-estimated, 2000^2 is met). The time law is the solve-time power law of
the benchmark, t ~ N^1.25 (fit 201^2 .. 501^2), with a floor for start-up.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
import time
from dataclasses import dataclass

BASE_MB = 220.0
MB_PER_NODE = 2.7e-3
SECONDS_AT_REFERENCE = 1.1  # one solve on the 201^2 mesh
REFERENCE_NODES = 201 * 201
TIME_EXPONENT = 1.25
MIN_SECONDS = 0.1
ANNOUNCE_SECONDS = 5.0  # solves estimated longer than this print the estimate and a bar


@dataclass(frozen=True)
class Estimate:
    nodes: int
    points: int
    memory_mb: float
    seconds: float

    def describe(self) -> str:
        return (
            f"{self.nodes} mesh nodes x {self.points} point(s): about {self.memory_mb / 1024:.1f} GB of memory "
            f"and {_duration(self.seconds)} of wall time"
        )


def _duration(seconds: float) -> str:
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def estimate(scene, points: int = 1) -> Estimate:
    """Memory (MB, peak of one solve: points of a sweep run one after the other) and time (s)."""
    nodes = int(scene.mesh.nx) * int(scene.mesh.ny)
    seconds = max(MIN_SECONDS, SECONDS_AT_REFERENCE * (nodes / REFERENCE_NODES) ** TIME_EXPONENT)
    return Estimate(nodes, points, BASE_MB + MB_PER_NODE * nodes, seconds * points)


def machine_memory_mb() -> float:
    """Physical memory of this machine (MB); LUBECONTACT_MEMORY_MB replaces it (tests, batch limits)."""
    override = os.environ.get("LUBECONTACT_MEMORY_MB")
    if override:
        return float(override)
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**20


def too_big(est: Estimate) -> str | None:
    """Why the solve is refused (its estimate beyond this machine's memory), or None."""
    available = machine_memory_mb()
    if est.memory_mb <= available:
        return None
    return (
        f"refusing to solve: {est.describe()}, more than this machine's {available / 1024:.1f} GB; "
        f"use a coarser mesh (mesh.nx, mesh.ny) or pass --force-size if you know better"
    )


@contextlib.contextmanager
def elapsed_bar(est: Estimate, stream=None, interval: float = 0.5):
    """A bar of elapsed against estimated seconds while the block runs (a solve has no
    measurable fraction done); shown when the estimate exceeds ANNOUNCE_SECONDS and the
    stream (default stderr) is a terminal."""
    stream = sys.stderr if stream is None else stream
    if est.seconds <= ANNOUNCE_SECONDS or not stream.isatty():
        yield
        return
    from tqdm.auto import tqdm  # here: 25 ms of imports that a solve without a bar never needs

    done = threading.Event()
    start = time.monotonic()

    def tick(bar):
        while not done.wait(interval):
            bar.n = round(time.monotonic() - start, 1)
            bar.refresh()

    bar = tqdm(total=round(est.seconds, 1), desc="solving (s elapsed / estimated)", file=stream,
               bar_format="{desc}: {n:.0f}/{total:.0f} |{bar}|")
    thread = threading.Thread(target=tick, args=(bar,), daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join()
        bar.close()
