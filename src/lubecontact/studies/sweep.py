"""A speed sweep of one scene: the Stribeck-like curves of Figs. 3-11 for one parameter set,
speeding up, slowing down or both (where the contact has two steady states: lift-off and
touch-down, docs/physics.md section 23)."""

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

# the ways through a sweep's speeds, each point started from the one solved before it
DIRECTIONS = {
    "up": "speeding up: each point started from the slower one before it",
    "down": "slowing down: each point started from the faster one before it",
}
BOTH = "both"
# the variable that marks a point solved cold in a warm sweep (one_way)
COLD_RESTART = {"units": "1", "long_name": (
    "1: the state continued from the previous speed did not converge here, and this point was solved from a "
    "cold start (the branch followed may end near this speed: a lift-off or a touch-down); 0: continued")}


def sweep(scene, speeds: Sequence[float], fields: bool = False, warm_start: bool = True, progress: bool | None = None,
          direction: str = "up") -> xr.Dataset:
    """Solve ``scene`` at each speed (m/s); returns a Dataset along ``speed`` (ascending).

    With ``warm_start`` each point starts from the previous point's position and deformation
    (continuation), in the order ``direction`` gives: "up" from the slowest speed, "down" from
    the fastest. Where the contact has one steady state either order and a cold start give
    the same answer within tolerance. Where it has two (a fluid-carried and a contact-carried
    state at the same speed: lift-off and touch-down, docs/physics.md section 23), "up" stays
    on the contact-carried branch to its end and "down" on the fluid-carried one; "both"
    solves the two and returns them along a ``direction`` dimension ("up", "down"), with the
    largest difference between them in the attribute ``hysteresis``.
    ``progress`` shows a bar (default: when stderr is a terminal).
    """
    speeds = np.asarray(sorted(float(s) for s in speeds))
    if speeds.size == 0 or np.any(~np.isfinite(speeds)) or np.any(speeds < 0):
        raise ValueError(f"speeds must be finite and >= 0 m/s, got {speeds.tolist()}")
    twice = repeated_speeds(speeds)
    if twice:  # the speed coordinate must be strictly monotonic (CF)
        raise ValueError(f"each speed once: {twice} listed twice")
    if direction not in (*DIRECTIONS, BOTH):
        raise ValueError(f"direction must be one of {', '.join(repr(d) for d in (*DIRECTIONS, BOTH))}, got {direction!r}")
    if progress is None:
        progress = sys.stderr.isatty()
    if direction != BOTH:
        return one_way(scene, speeds, fields, warm_start, progress, direction)
    ways = [one_way(scene, speeds, fields, warm_start, progress, way) for way in DIRECTIONS]
    out = xr.concat(ways, dim="direction", combine_attrs="drop_conflicts")
    out = out.assign_coords(direction=xr.Variable(("direction",), list(DIRECTIONS), {
        "long_name": "order of the continuation: " + "; ".join(DIRECTIONS.values())}))
    out.attrs["validity_notes"] = "\n".join(f"{way}, {line}" for way, ds in zip(DIRECTIONS, ways)
                                            for line in ds.attrs["validity_notes"].splitlines())
    out.attrs["effects_run"] = effects_run_by_any([ds.attrs["effects_run"] for ds in ways], scene)
    out.attrs["hysteresis"] = largest_difference(*ways)
    return out


def one_way(scene, speeds: np.ndarray, fields: bool, warm_start: bool, progress: bool, direction: str) -> xr.Dataset:
    """``sweep`` through the ascending ``speeds`` in one ``direction`` ("up" or "down").

    A point started from the previous one that does not converge is solved again from a cold
    start, and kept where that converges (``cold_restart`` = 1): near the end of a branch the
    continued state has no solution close by (51 x 51, 20 N, slowing down from 0.251 m/s: at
    0.158 m/s, tests/test_hysteresis.py). Where the cold start fails too, the continued
    attempt is kept, with converged = 0."""
    from tqdm.auto import tqdm

    order = speeds if direction == "up" else speeds[::-1]
    cases, flagged = {}, {}
    initial = previous_mesh = None
    for speed in tqdm(order, desc=f"speeds ({direction})", unit="pt", disable=not progress):
        point = scene.replace({"operating.speed": float(speed)})
        mesh = build_mesh(point)
        if initial is not None and previous_mesh.shape != mesh.shape:  # the inlet grew or shrank with the film
            pressure = None if initial.pressure is None else interpolate_field(initial.pressure, previous_mesh, mesh)
            initial = WarmStart(z=initial.z, delta=interpolate_field(initial.delta, previous_mesh, mesh), pressure=pressure)
        ds, state = solve(point, fields=fields, initial=initial, return_state=True)
        restarted = False
        if initial is not None and ds["converged"].item() != 1:  # the branch followed may end here
            cold, cold_state = solve(point, fields=fields, return_state=True)
            if cold["converged"].item() == 1:
                ds, state, restarted = cold, cold_state, True
        ds["cold_restart"] = xr.DataArray(np.int8(restarted), attrs=COLD_RESTART)
        if warm_start and ds["converged"].item() == 1:
            initial, previous_mesh = WarmStart(z=state.z, delta=state.delta), mesh
            if state.reynolds is not None:  # the set follows from the pressure (projected_smoothing)
                initial.cavitated = state.reynolds.cavitated
                initial.pressure = state.reynolds.pressure
        cases[float(speed)] = ds.drop_vars("speed")
        flagged[float(speed)] = [f"{speed:g} m/s: {line}" for line in ds.attrs["validity_notes"].splitlines()]
    out = xr.concat([cases[float(s)] for s in speeds], dim="speed", combine_attrs="drop_conflicts")
    out = out.assign_coords(speed=xr.Variable(("speed",), speeds, {"units": "m s-1", "long_name": "sliding speed U of the block"}))
    out.attrs["scene"] = scene.canonical_yaml()
    out.attrs["scene_hash"] = scene.hash
    out.attrs["note"] = "operating.speed of the scene is replaced by the speed coordinate"
    out.attrs["sweep_direction"] = DIRECTIONS[direction] if warm_start else "each point from a cold start"
    # each point's flags, in the order of the speeds (they differ: concat drops them)
    out.attrs["validity_notes"] = "\n".join(line for s in speeds for line in flagged[float(s)])
    out.attrs["effects_run"] = effects_run_by_any([ds.attrs["effects_run"] for ds in cases.values()], scene)
    return out


def largest_difference(up: xr.Dataset, down: xr.Dataset) -> str:
    """Where the sweeps up and down differ most in ln(contact resistance), among the speeds
    both converged at, in words: the speed, each direction's resistance and fluid load
    fraction. No threshold decides it: the numbers are given as they are."""
    both = (up["converged"].values == 1) & (down["converged"].values == 1)
    if not both.any():
        return "no speed converged in both directions: nothing to compare"
    r_up, r_down = up["contact_resistance"].values, down["contact_resistance"].values
    with np.errstate(divide="ignore", invalid="ignore"):  # no metallic path: R = inf (or 0 in a test scene)
        gap = np.abs(np.log(r_up) - np.log(r_down))
    gap = np.where(r_up == r_down, 0.0, gap)  # the same, infinite ones too
    i = int(np.argmax(np.where(both, gap, -np.inf)))
    speed = float(up["speed"].values[i])
    f_up, f_down = float(up["fluid_load_fraction"][i]), float(down["fluid_load_fraction"][i])
    return (f"speeding up and slowing down differ most at {speed:g} m/s: contact resistance {r_up[i]:.4g} ohm up, "
            f"{r_down[i]:.4g} ohm down (ln R apart by {gap[i]:.3g}); fluid load fraction {f_up:.3g} up, "
            f"{f_down:.3g} down")


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
