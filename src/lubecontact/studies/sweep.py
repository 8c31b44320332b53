"""A speed sweep of one scene: the Stribeck-like curves of Figs. 3-11 for one parameter set."""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import fields

import numpy as np
import xarray as xr

from lubecontact.model.coupling import WarmStart
from lubecontact.model.solve import solve
from lubecontact.numerics.mesh import build_mesh
from lubecontact.numerics.transfer import interpolate_field


def sweep(scene, speeds: Sequence[float], fields: bool = False, warm_start: bool = True, progress: bool | None = None) -> xr.Dataset:
    """Solve ``scene`` at each speed (m/s); returns a Dataset along ``speed``.

    Points are solved in ascending speed; with ``warm_start`` each starts from the previous
    point's position and deformation (continuation: a speed-up only, a cold start gives the
    same answer within tolerance). ``progress`` shows a bar (default: when stderr is a terminal).
    """
    from tqdm.auto import tqdm

    speeds = np.asarray(sorted(float(s) for s in speeds))
    if speeds.size == 0 or np.any(~np.isfinite(speeds)) or np.any(speeds < 0):
        raise ValueError(f"speeds must be finite and >= 0 m/s, got {speeds.tolist()}")
    twice = repeated_speeds(speeds)
    if twice:  # the speed coordinate must be strictly monotonic (CF)
        raise ValueError(f"each speed once: {twice} listed twice")
    if progress is None:
        progress = sys.stderr.isatty()
    cases, flagged = [], []
    initial = previous_mesh = None
    for speed in tqdm(speeds, desc="speeds", unit="pt", disable=not progress):
        point = scene.replace({"operating.speed": float(speed)})
        mesh = build_mesh(point)
        if initial is not None and previous_mesh.shape != mesh.shape:  # the inlet grew with the film
            pressure = None if initial.pressure is None else interpolate_field(initial.pressure, previous_mesh, mesh)
            initial = WarmStart(z=initial.z, delta=interpolate_field(initial.delta, previous_mesh, mesh), pressure=pressure)
        ds, state = solve(point, fields=fields, initial=initial, return_state=True)
        if warm_start and ds["converged"].item() == 1:
            initial, previous_mesh = WarmStart(z=state.z, delta=state.delta), mesh
            if state.reynolds is not None:  # the set follows from the pressure (projected_smoothing)
                initial.cavitated = state.reynolds.cavitated
                initial.pressure = state.reynolds.pressure
        cases.append(ds.drop_vars("speed"))
        flagged += [f"{speed:g} m/s: {line}" for line in ds.attrs["validity_notes"].splitlines()]
    out = xr.concat(cases, dim="speed", combine_attrs="drop_conflicts")
    out = out.assign_coords(speed=xr.Variable(("speed",), speeds, {"units": "m s-1", "long_name": "sliding speed U of the block"}))
    out.attrs["scene"] = scene.canonical_yaml()
    out.attrs["scene_hash"] = scene.hash
    out.attrs["note"] = "operating.speed of the scene is replaced by the speed coordinate"
    out.attrs["validity_notes"] = "\n".join(flagged)  # each point's flags (they differ: concat drops them)
    out.attrs["effects_run"] = effects_run_by_any([ds.attrs["effects_run"] for ds in cases], scene)
    return out


def repeated_speeds(speeds: Sequence[float]) -> list[float]:
    """The speeds given more than once, ascending: a sweep's speed coordinate must be
    strictly monotonic (CF), so the CLI (--speeds) and ``sweep`` refuse them."""
    return sorted(float(v) for v, n in Counter(float(v) for v in speeds).items() if n > 1)


def effects_run_by_any(runs: Sequence[str], scene) -> str:
    """The effects some point of a sweep ran (each point's ``effects_run``, a comma list), in
    the order of the scene's effects: they differ where a speed of 0 runs no hydrodynamics,
    and concat drops what differs (a sweep from 0 m/s ended in a KeyError)."""
    ran = {name for run in runs for name in run.split(",") if name}
    return ",".join(name for name in (f.name for f in fields(scene.effects)) if name in ran)
