"""Is a case file complete? A case file (results/cases/<id>.nc) counts only if it opens,
every variable reads back, and it carries its scene hash and the solver-sources
fingerprint (the solve job writes both, atomically). Anything else (a truncated or
overwritten file, a foreign file under the name) is moved aside so that the workflow solves
the case again: nothing stale is kept, nothing is deleted. The workflow's other netCDF
products (a figure's dataset, a transient run, the accuracy study) are moved aside the same
way where they do not read back, so a rerun rebuilds them.
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import netCDF4
import numpy as np

from lubecontact.io.atomic_write import write_text

FINGERPRINT = "solver_sources_sha256"
QUARANTINE = ".corrupt"  # hidden folder next to the case files


def read_back(path) -> dict | str:
    """The global attributes of the netCDF file ``path`` after every variable read back, or
    why it does not read ("missing", "unreadable (...)")."""
    path = Path(path)
    if not path.exists():
        return "missing"
    try:
        with netCDF4.Dataset(path) as nc:
            attrs = {name: nc.getncattr(name) for name in nc.ncattrs()}
            for var in nc.variables.values():
                var[...]
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as err:  # netCDF/HDF5 errors
        return f"unreadable ({type(err).__name__}: {err})"
    return attrs


def dataset_problem(path) -> str | None:
    """Why ``path`` is not a netCDF dataset that reads back, or None."""
    attrs = read_back(path)
    return attrs if isinstance(attrs, str) else None


def case_problem(path, case_id: str, fingerprint: str | None = None) -> str | None:
    """Why ``path`` is not the complete case ``case_id`` (solved by ``fingerprint``, if
    given), or None. A missing file is a problem too ("missing")."""
    attrs = read_back(path)
    if isinstance(attrs, str):
        return attrs
    if attrs.get("scene_hash") != case_id:
        return f"scene_hash is {attrs.get('scene_hash')!r}, not {case_id!r}"
    if not attrs.get(FINGERPRINT):
        return f"no {FINGERPRINT} attribute (not written by a solve job)"
    if fingerprint is not None and attrs[FINGERPRINT] != fingerprint:
        return "solved by other solver sources"
    return None


@dataclass(frozen=True)
class CaseRecord:
    """What collect takes from a case: its global attributes and its 0-d variables
    (name -> (0-d numpy value, variable attributes)), without xarray."""

    attrs: dict
    scalars: dict

    @classmethod
    def from_dataset(cls, dataset) -> "CaseRecord":
        """The record of an in-memory case Dataset (solve's output)."""
        scalars = {name: (var.values, dict(var.attrs)) for name, var in dataset.data_vars.items() if var.ndim == 0}
        return cls(dict(dataset.attrs), scalars)


def read_case(path) -> CaseRecord:
    """The case file's record, read with netCDF4 as stored (the values xarray decodes: a case
    holds no packed or time variables; NaN is its fill value), or RuntimeError naming the
    file and the remedy (collect's loader). xarray took 10 ms a file; this takes about 3
    (a scalar's getValue skips the slicing that var[...] costs: 1.6 instead of 2.8 ms for a
    case's 23 variables)."""
    try:
        with netCDF4.Dataset(path) as nc:
            nc.set_auto_maskandscale(False)
            attrs = {name: nc.getncattr(name) for name in nc.ncattrs()}
            scalars = {
                name: (np.asarray(var.getValue()), {a: var.getncattr(a) for a in var.ncattrs() if a != "_FillValue"})
                for name, var in nc.variables.items()
                if var.ndim == 0
            }
    except Exception as err:  # netCDF/HDF5 raise OSError, RuntimeError, ValueError, ...
        raise RuntimeError(
            f"case file {path} does not read ({type(err).__name__}: {err}); run snakemake again: "
            f"it moves the file aside and solves the case again"
        ) from err
    return CaseRecord(attrs, scalars)


def _signature(path: Path) -> list[int]:
    st = path.stat()
    return [st.st_size, st.st_mtime_ns, st.st_ino]


def quarantine(cases: dict[str, str], memo) -> list[str]:
    """Move every existing but incomplete case file aside (``cases``: id -> path); one
    message per file moved, naming it, why, and where it went (move_aside)."""
    return move_aside({path: partial(case_problem, path, case_id) for case_id, path in cases.items()}, memo,
                      "the case will be solved again")


def quarantine_datasets(paths, memo) -> list[str]:
    """Move every existing netCDF product in ``paths`` that does not read back aside, so the
    workflow builds it again (a truncated figure dataset had failed every rerun)."""
    return move_aside({path: partial(dataset_problem, path) for path in paths}, memo, "it will be built again")


def move_aside(checks: dict, memo, then: str) -> list[str]:
    """Move each existing file of ``checks`` (path -> a call giving why it is not complete,
    or None) that is not complete into QUARANTINE beside it; one message per file moved,
    naming it, why, where it went and ``then`` (what the workflow does about it).

    Reading ~500 files costs seconds, so a file found complete is remembered in ``memo``
    (JSON: name -> size, mtime, inode) and read again only when one of those changes (any
    rewrite, truncation or replacement does)."""
    memo = Path(memo)
    try:
        known = json.loads(memo.read_text())
    except (OSError, ValueError):
        known = {}
    good, moved = {}, []
    stamp = time.strftime("%Y%m%dT%H%M%S")
    for path, problem in checks.items():
        path = Path(path)
        if not path.exists():
            continue
        signature = _signature(path)
        why = None if known.get(path.name) == signature else problem()
        if why is None:
            good[path.name] = signature
            continue
        aside = path.parent / QUARANTINE / f"{path.stem}.{stamp}{path.suffix}"
        aside.parent.mkdir(exist_ok=True)
        os.replace(path, aside)
        moved.append(f"{path}: {why}; moved to {aside}, {then}")
    if good != known and (good or memo.exists()):
        memo.parent.mkdir(parents=True, exist_ok=True)
        write_text(memo, json.dumps(good, sort_keys=True))
    return moved
