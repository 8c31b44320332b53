"""What a reconnect time's accuracy costs: the transient's part of the accuracy study.

One motion (config/transient.yaml, figure ``accuracy``: the Table 1 stop from 1 m/s) runs
on a ladder of meshes at one motion.tolerance, on one mesh at a ladder of motion.tolerance,
and on one mesh at a ladder of motion.rest_refinement (its mesh at rest, where the film
drains, refined; studies/transient_cases.ladder_cases plans the cases). Each ladder's
reconnect time is extrapolated by Richardson with its observed order from its three finest
members (studies/accuracy.extrapolate, Celik et al. 2008): the mesh ladder in the spacing
h = 1/(n - 1), the refinement ladder in 1/r, the tolerance ladder in the tolerance itself (variable-step BDF2's global
error goes as the tolerance to the power 2/3, docs/physics.md section 14; the order is
observed, not assumed). The error of every member is |t/t_ext - 1| against its own ladder's
extrapolation, and each member's cost is the wall time of its run (the case file's
``solve_time``), so the table reads "5 % needs n nodes and t seconds" (``markdown``,
plotting/accuracy.plot_transient_accuracy). A ladder with a member that did not converge,
or did not reconnect within its duration, has no extrapolation: the table says which.

Library code: knows nothing of Snakemake (workflow/rules/transient.smk calls it).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from lubecontact.studies.accuracy import extrapolate, least_work_index, percent

# what each ladder varies: its coordinate's long name and units, and the spacing its
# Richardson extrapolation uses
PARTS = {
    "mesh": ("nodes along the sliding direction", "1"),
    "tolerance": ("time integrator's relative tolerance, motion.tolerance", "1"),
    "rest_refinement": ("nodes per metre of the mesh at rest along the sliding direction, as a multiple of the "
                        "motion's mesh, motion.rest_refinement", "1"),
}
# what the Markdown table's first column calls each ladder's members
MEMBERS = {"mesh": "mesh (nodes along the sliding direction)", "tolerance": "motion.tolerance",
           "rest_refinement": "motion.rest_refinement"}


def spacing(part: str, values) -> np.ndarray:
    """The extrapolation's spacing of each ladder member: 1/(n - 1) of the domain for a mesh
    of n nodes, the tolerance itself for a tolerance, 1/r of the motion's node spacing for a
    mesh at rest r times finer."""
    values = np.asarray(values, dtype=float)
    if part == "mesh":
        return 1.0 / (values - 1.0)
    return 1.0 / values if part == "rest_refinement" else values


def ladder_table(cases: Sequence[Mapping], data: Sequence[xr.Dataset]) -> xr.Dataset:
    """The ladders' table from the planned cases (transient_cases.ladder_cases: part, value)
    and their transient Datasets, in the same order. Per part (``mesh``, ``tolerance``):
    along its coordinate the reconnect time, its relative error against the extrapolation,
    the nodes along the cylinder axis of the member's mesh, the run's wall time, steps,
    rejected steps and convergence; scalars the extrapolated
    reconnect time, observed order, GCI and whether the ladder is in its asymptotic range.
    ``notes`` says why a ladder has no extrapolation."""
    out, notes = xr.Dataset(), []
    for part, (long_name, units) in PARTS.items():
        planned = sorted(((c["value"], ds, c) for c, ds in zip(cases, data) if c["part"] == part), key=lambda m: m[0])
        if not planned:
            continue
        members = [(v, ds) for v, ds, _ in planned]
        values = np.array([v for v, _ in members], dtype=float)
        times = np.array([float(ds["reconnect_time"]) for _, ds in members])
        out.coords[part] = xr.DataArray(values, dims=part, attrs={"long_name": long_name, "units": units})
        out[f"{part}_nx"] = (part, np.array([c["nx"] for _, _, c in planned]),
                             {"long_name": "nodes along the sliding direction of the motion's mesh", "units": "1"})
        out[f"{part}_ny"] = (part, np.array([c["ny"] for _, _, c in planned]),
                             {"long_name": "nodes along the cylinder axis (1: line contact)", "units": "1"})
        _member_variables(out, part, members, times)
        reached = np.isfinite(times) & (times > 0.0) & (out[f"{part}_converged"].values == 1)
        if reached.all():
            ext = extrapolate(spacing(part, values), times)
            error = np.abs(times / ext.value - 1.0)
        else:
            ext, error = None, np.full(times.size, math.nan)
            missing = ", ".join(f"{v:g}" for v, ok in zip(values, reached) if not ok)
            notes.append(f"{part} ladder: no extrapolation, the run(s) at {part} {missing} did not converge or "
                         f"did not reconnect within their duration")
        _ladder_scalars(out, part, ext, error)
    out.attrs["notes"] = "; ".join(notes)
    return out


def _member_variables(out: xr.Dataset, part: str, members, times: np.ndarray) -> None:
    def column(name):
        return [ds[name].item() for _, ds in members]

    out[f"{part}_reconnect_time"] = (part, times, {"long_name": "reconnect time", "units": "s"})
    out[f"{part}_run_time"] = (part, np.array(column("solve_time"), dtype=float),
                               {"long_name": "wall time of the run", "units": "s"})
    out[f"{part}_steps"] = (part, np.array(column("steps")), {"long_name": "accepted time steps", "units": "1"})
    out[f"{part}_rejected_steps"] = (part, np.array(column("rejected_steps")),
                                     {"long_name": "rejected time steps", "units": "1"})
    out[f"{part}_converged"] = (part, np.array(column("converged"), dtype=int),
                                {"long_name": "1 if every step of the run converged", "units": "1"})


def _ladder_scalars(out: xr.Dataset, part: str, ext, error: np.ndarray) -> None:
    out[f"{part}_error"] = (part, error, {"long_name": "relative error of the reconnect time against the "
                                                      f"{part} ladder's extrapolation", "units": "1"})
    nan = math.nan
    out[f"{part}_extrapolated"] = ((), ext.value if ext else nan,
                                   {"long_name": f"reconnect time extrapolated along the {part} ladder", "units": "s"})
    out[f"{part}_order"] = ((), ext.order if ext else nan, {"long_name": f"observed order along the {part} ladder",
                                                            "units": "1"})
    out[f"{part}_gci"] = ((), ext.gci if ext else nan,
                          {"long_name": f"grid convergence index of the {part} ladder's finest member", "units": "1"})
    out[f"{part}_asymptotic"] = ((), int(bool(ext and ext.asymptotic)),
                                 {"long_name": "1 if the observed order is in the asymptotic range", "units": "1"})


def least_work_within(table: xr.Dataset, part: str, target: float) -> tuple[float, float] | None:
    """(member, wall time) of the ladder member doing the least work within ``target``
    relative error (the fewest nodes, at rest too; the loosest motion.tolerance), or None
    when no member is (accuracy.least_work_index: not the least measured time, which swaps
    members of similar cost with timing noise)."""
    members = table[part].values
    work = 1.0 / members if part == "tolerance" else members * table[f"{part}_ny"].values
    best = least_work_index(table[f"{part}_error"].values, work, target)
    return None if best is None else (float(members[best]), float(table[f"{part}_run_time"].values[best]))


def markdown(table: xr.Dataset, targets: Sequence[float] = (0.05, 0.01)) -> str:
    """The ladders as Markdown tables, each with its extrapolation and what each target costs."""
    lines = ["# What a reconnect time's accuracy costs", ""]
    for part in PARTS:
        if part not in table.coords:
            continue
        lines += [f"## {part.replace('_', ' ')} ladder", "", f"| {MEMBERS[part]} | nodes along the cylinder axis | reconnect time (ms) | error | "
                  "steps (rejected) | run (s) |", "|---|---|---|---|---|---|"]
        for i, value in enumerate(table[part].values):
            lines.append(f"| {value:g} | {table[f'{part}_ny'].values[i]} | "
                         f"{table[f'{part}_reconnect_time'].values[i] * 1e3:.4g} | "
                         f"{percent(table[f'{part}_error'].values[i])} | {table[f'{part}_steps'].values[i]} "
                         f"({table[f'{part}_rejected_steps'].values[i]}) | {table[f'{part}_run_time'].values[i]:.3g} |")
        ext = float(table[f"{part}_extrapolated"])
        lines.append("")
        if math.isfinite(ext):
            asymptotic = "" if int(table[f"{part}_asymptotic"]) else " (not in the asymptotic range: treat as rough)"
            lines.append(f"Extrapolated: {ext * 1e3:.4g} ms, observed order {float(table[f'{part}_order']):.2f}, "
                         f"GCI {percent(float(table[f'{part}_gci']))}{asymptotic}.")
            for target in targets:
                best = least_work_within(table, part, target)
                lines.append(f"- within {percent(target)}: " + (f"{part} {best[0]:g}, {best[1]:.3g} s" if best
                                                                  else "no member of the ladder"))
        lines.append("")
    if table.attrs.get("notes"):
        lines += [f"Notes: {table.attrs['notes']}", ""]
    return "\n".join(lines)
