"""What accuracy costs: mesh convergence, Richardson extrapolation and solve time.

Extends the paper's Fig. 3 (section 2.6: contact resistance on several meshes, 51 x 51
chosen) into a measured error budget. For one scene at speeds in the boundary, mixed and
full-film regimes, ``run_study`` solves a ladder of square meshes (nodes a side n, spacing
h = 1/(n - 1) of the domain, refined by about sqrt(2) per level), a few domain lengths at a
fixed spacing and a few solver tolerances (by the default solver, and by the one Newton
against it), timing every solve. ``accuracy_table`` then
estimates the mesh-converged value of each quantity by Richardson extrapolation with the
observed order of accuracy, and the error of every mesh against it, so that a user reads
off "1 % in resistance at 1 m/s needs mesh n and t seconds" (``markdown``,
``plot_accuracy_cost``).

Method: Roache (1998), *Verification and Validation in Computational Science and
Engineering*, and the ASME procedure of Celik et al. (2008), J. Fluids Eng. 130:078001.
For meshes h1 < h2 < h3 with values f1, f2, f3, e21 = f2 - f1, e32 = f3 - f2,
r21 = h2/h1, r32 = h3/h2 and s = sign(e32/e21), the observed order p solves

    p = |ln|e32/e21| + ln((r21^p - s)/(r32^p - s))| / ln r21           (fixed point)

and the extrapolated value is f_ext = (r21^p f1 - f2)/(r21^p - 1), with the fine-grid
convergence index GCI = 1.25 |e21/f1|/(r21^p - 1) as its uncertainty. s < 0 (oscillatory
convergence) is flagged. The contact resistance spans orders of magnitude across speeds,
so it is extrapolated in ln R and its error is |R/R_ext - 1|.

Library code: knows nothing of Snakemake (workflow/rules/accuracy.smk calls it); the
figure uses matplotlib's object API.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from lubecontact.io.version import package_version
from lubecontact.model.solve import solve
from lubecontact.numerics.mesh import build_mesh
from lubecontact.scene import load_scene
from lubecontact.studies.accuracy_plan import DOMAIN_RADIUS_FRACTION, QUANTITIES, study_points
from lubecontact.studies.figure_grids import key_value

# Safety factor of the grid convergence index for three or more meshes (Roache; Celik 2008).
GCI_SAFETY = 1.25
# An observed order outside this range means the meshes are not in the asymptotic range
# (or the differences are at the solver's noise): the extrapolation then uses the nearest
# end of the range and the result is flagged ``asymptotic = False``.
ORDER_RANGE = (0.5, 4.0)
# Fixed-point iterations of the observed order (non-uniform refinement ratios).
ORDER_ITERATIONS = 100

REGIME_BOUNDARY = 0.05  # fluid carries less than this fraction of the load: boundary
REGIME_FULL_FILM = 0.95  # more than this: full film; in between: mixed


@dataclass(frozen=True)
class Extrapolation:
    """Richardson extrapolation from the three finest meshes of a ladder."""

    value: float  # extrapolated (mesh-converged) value
    order: float  # observed order p (NaN when two meshes agree exactly)
    gci: float  # fine-grid convergence index (relative: see extrapolate)
    oscillatory: bool  # e32 and e21 of opposite sign
    asymptotic: bool  # p within ORDER_RANGE and not oscillatory


def observed_order(f1: float, f2: float, f3: float, r21: float, r32: float) -> tuple[float, bool]:
    """Observed order p of three solutions on meshes h1 < h2 < h3 (fine to coarse) with
    refinement ratios r21 = h2/h1 > 1, r32 = h3/h2 > 1 (Celik et al. 2008, Eqs. 3-5);
    returns (p, oscillatory). p is NaN when e21 or e32 is exactly zero (no convergence
    information: the values agree to round-off)."""
    if not (r21 > 1.0 and r32 > 1.0):
        raise ValueError(f"refinement ratios must be > 1, got r21 = {r21}, r32 = {r32}")
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0.0 or e32 == 0.0:
        return math.nan, False
    s = 1.0 if e32 / e21 > 0.0 else -1.0
    ratio = abs(e32 / e21)
    p = abs(math.log(ratio)) / math.log(r21)  # start: the uniform-ratio answer (q = 0)
    for _ in range(ORDER_ITERATIONS):
        a, b = r21**p - s, r32**p - s
        q = math.log(a / b) if a > 0.0 and b > 0.0 else 0.0
        new = abs(math.log(ratio) + q) / math.log(r21)
        if abs(new - p) <= 1e-12 * max(1.0, p):
            p = new
            break
        p = min(new, 50.0)  # r^p stays finite however the iteration wanders
    return p, s < 0.0


def richardson(f1: float, f2: float, ratio: float, order: float) -> float:
    """Richardson extrapolation f1 + (f1 - f2)/(r^p - 1) of the fine value f1 and the
    coarser f2 (ratio r = h2/h1 > 1, order p > 0)."""
    return f1 + (f1 - f2) / (ratio**order - 1.0)


def extrapolate(spacing: Sequence[float], values: Sequence[float], scale: float | None = None) -> Extrapolation:
    """Richardson extrapolation of ``values`` on meshes of ``spacing`` (any order) from the
    three finest meshes; the order is the observed one, clipped to ORDER_RANGE. The GCI is
    relative to ``scale`` (default: |finest value|; 1 for values that are logarithms)."""
    h = np.asarray(spacing, dtype=float)
    f = np.asarray(values, dtype=float)
    if h.size != f.size or h.size < 3:
        raise ValueError(f"need at least three meshes with one value each, got {h.size} and {f.size}")
    if not np.all(np.isfinite(f)):
        raise ValueError(f"cannot extrapolate non-finite values {f.tolist()}")
    order = np.argsort(h)[:3]
    (h1, h2, h3), (f1, f2, f3) = h[order], f[order]
    p, oscillatory = observed_order(f1, f2, f3, h2 / h1, h3 / h2)
    if math.isnan(p):
        return Extrapolation(float(f1), p, 0.0, False, False)
    used = min(max(p, ORDER_RANGE[0]), ORDER_RANGE[1])
    value = richardson(f1, f2, h2 / h1, used)
    scale = abs(f1) if scale is None else scale
    gci = GCI_SAFETY * abs(f1 - f2) / scale / ((h2 / h1) ** used - 1.0) if scale > 0.0 else math.inf
    asymptotic = (not oscillatory) and ORDER_RANGE[0] <= p <= ORDER_RANGE[1]
    return Extrapolation(float(value), float(p), float(gci), oscillatory, asymptotic)


def relative_error(values, reference: float, quantity: str, floor: float = 0.0) -> np.ndarray:
    """Error of ``values`` against ``reference`` as the table reports it: |R/R_ref - 1| for
    a log quantity (reference is then ln R_ref), else |f - f_ref| / max(|f_ref|, floor)."""
    values = np.asarray(values, dtype=float)
    if QUANTITIES[quantity].log:
        return np.abs(np.expm1(np.log(values) - reference))
    return np.abs(values - reference) / max(abs(reference), floor)


def regime(fluid_load_fraction: float) -> str:
    """'boundary', 'mixed' or 'full film' by the fraction of the load the fluid carries."""
    if fluid_load_fraction < REGIME_BOUNDARY:
        return "boundary"
    if fluid_load_fraction > REGIME_FULL_FILM:
        return "full film"
    return "mixed"


# --- running the study ---------------------------------------------------------------------


# Case outputs recorded for every solve of the study.
RECORDED = ("converged", "iterations", "fluid_load_fraction")


def timed_solve(scene, repeats: int = 1, budget: float = math.inf):
    """Solve ``scene`` up to ``repeats`` times while the time spent stays below ``budget``
    seconds (at least once); returns (first Dataset, median solve_time s, all times)."""
    times = []
    first = None
    while len(times) < max(1, repeats) and (not times or sum(times) < budget):
        ds = solve(scene)
        first = ds if first is None else first
        times.append(float(ds["solve_time"]))
    return first, statistics.median(times), times


def run_study(spec: Mapping, log: Callable[[str], None] = print) -> xr.Dataset:
    """Solve every point of ``spec`` (``study_spec``; see ``study_points``), each from a cold start after a
    warm-up solve, timing each (median of up to spec["timing"]["repeats"] solves within
    spec["timing"]["budget"] seconds). Returns the raw study Dataset: per part ("mesh",
    "domain", "tolerance", "newton") the quantities, solve_time and RECORDED over (speed, <part>)."""
    base = load_scene(spec["scene"], spec.get("set") or {})
    quantities = list(spec["quantities"])
    timing = spec.get("timing") or {}
    repeats, budget = int(timing.get("repeats", 1)), float(timing.get("budget", math.inf))
    warm = time.perf_counter()
    solve(base.replace({"mesh.nx": 15, "mesh.ny": 11}))
    log(f"warm-up solve (imports): {time.perf_counter() - warm:.2f} s")

    speeds = [float(s) for s in spec["speeds"]]
    results: dict[str, dict] = {}
    attrs = {}
    for point in study_points(spec):
        scene = base.replace({"operating.speed": point["speed"], **point["overrides"]})
        ds, median, times = timed_solve(scene, repeats, budget)
        row = {q: float(ds[q]) for q in quantities} | {r: float(ds[r]) for r in RECORDED}
        row["solve_time"] = median
        mesh = build_mesh(scene)
        row["x_min"], row["nodes"] = float(mesh.x[0]), mesh.nx * mesh.ny
        part = results.setdefault(point["part"], {})
        part[(point["speed"], point["key"])] = row
        for name in quantities + ["solve_time", *RECORDED]:
            attrs[name] = dict(ds[name].attrs)
        attrs["x_min"] = {"units": "m", "long_name": "inlet end of the domain x_min (automatic: follows the film)"}
        attrs["nodes"] = {"units": "1", "long_name": "nodes of the mesh (the automatic inlet adds columns)"}
        log(f"{point['part']:9s} U = {point['speed']:g} m/s, {point['key']:g}: "
            + ", ".join(f"{q} = {row[q]:.6g}" for q in quantities)
            + f", converged = {int(row['converged'])}, {median:.3f} s (median of {len(times)})")

    data_vars, coords = {}, {"speed": ("speed", speeds, {"units": "m s-1", "long_name": "sliding speed U of the block"})}
    part_coords = {
        "mesh": ("nodes a side (nx = ny)", "1", [int(n) for n in spec["meshes"]]),
        "domain": ("domain length / automatic domain length", "1", [float(s) for s in (spec.get("domain") or {}).get("scales", [])]),
        "tolerance": ("solver.tolerance", "1", [float(v) for v in (spec.get("tolerance") or {}).get("values", [])]),
        "newton": ("solver.tolerance of the one Newton (solver.method newton)", "1",
                   [float(v) for v in (spec.get("newton") or {}).get("values", [])]),
    }
    for part, rows in results.items():
        long_name, units, keys = part_coords[part]
        dim = part
        coords[dim] = (dim, keys, {"units": units, "long_name": long_name})
        prefix = "" if part == "mesh" else f"{part}_"
        for name in quantities + ["solve_time", "x_min", "nodes", *RECORDED]:
            values = np.array([[rows[(s, k)][name] for k in keys] for s in speeds])
            data_vars[prefix + name] = (("speed", dim), values, attrs[name])
    out = xr.Dataset(data_vars, coords=coords)
    out["solve_time"].attrs["long_name"] = "wall time of one solve (median of repeats), model assembly included"
    for q in quantities:
        floor = QUANTITIES[q].floor
        out[q].attrs["error_floor"] = float(key_value(base, floor)) if floor else 0.0
    out.attrs.update({
        "title": "lubecontact accuracy study: mesh ladder, domain lengths and solver tolerances (nested and one Newton)",
        "Conventions": "CF-1.10",
        "scene": base.canonical_yaml(),
        "scene_file": str(spec["scene"]),
        "scene_overrides": repr(dict(spec.get("set") or {})),
        "lubecontact_version": package_version(),
        "quantities": ",".join(quantities),
        "domain_mesh": int((spec.get("domain") or {}).get("mesh", 0)),
        "tolerance_mesh": int((spec.get("tolerance") or {}).get("mesh", 0)),
        "newton_mesh": int((spec.get("newton") or {}).get("mesh", 0)),
        "timing": f"median of up to {repeats} solves within {budget:g} s, after a warm-up solve",
    })
    return out


# --- the table -----------------------------------------------------------------------------


def _transformed(values, quantity):
    values = np.asarray(values, dtype=float)
    return np.log(values) if QUANTITIES[quantity].log else values


def _extrapolated_display(value: float, quantity: str) -> float:
    return math.exp(value) if QUANTITIES[quantity].log else value


def accuracy_table(study: xr.Dataset) -> xr.Dataset:
    """The study with its error budget added (per speed and quantity q):

    - ``q_extrapolated``, ``q_order``, ``q_gci``, ``q_asymptotic``: Richardson from the three
      finest meshes (observed order; GCI relative to the finest value);
    - ``q_order_by_mesh`` (speed, mesh): the observed order of the three meshes ending at
      each mesh (the asymptotic range shows as a plateau);
    - ``q_error`` (speed, mesh): error of each mesh against the extrapolated value;
    - ``domain_q_change`` / ``tolerance_q_change`` / ``newton_q_change``: change against the
      largest domain, the tightest tolerance and, for the one Newton, the nested solver's
      tightest tolerance (check_reference), in the same error measure;
    - ``regime`` (speed): boundary / mixed / full film on the finest mesh.

    A quantity that is not finite (an open circuit) or not positive where extrapolated in
    logs on some mesh of a speed gets NaN there and a note in ``notes``.
    """
    out = study.copy()
    quantities = study.attrs["quantities"].split(",")
    spacing = 1.0 / (study["mesh"].values - 1.0)
    n_speed, n_mesh = study.sizes["speed"], study.sizes["mesh"]
    notes = []
    finest = int(np.argmin(spacing))
    out["regime"] = ("speed", [regime(float(v)) for v in study["fluid_load_fraction"].values[:, finest]],
                     {"long_name": "lubrication regime on the finest mesh (fluid load fraction < 5 %: boundary, > 95 %: full film)"})
    for q in quantities:
        attrs = study[q].attrs
        floor = attrs.get("error_floor", 0.0)
        log_note = " (extrapolated in ln)" if QUANTITIES[q].log else ""
        names = ("extrapolated", "order", "gci", "asymptotic")
        table = {name: np.full(n_speed, np.nan) for name in names}
        by_mesh = np.full((n_speed, n_mesh), np.nan)
        error = np.full((n_speed, n_mesh), np.nan)
        for i, speed in enumerate(study["speed"].values):
            values = study[q].values[i]
            ok = np.all(np.isfinite(values)) and (not QUANTITIES[q].log or np.all(values > 0.0))
            if not ok or n_mesh < 3:
                notes.append(f"{q} at U = {speed:g} m/s: not extrapolated (values {values.tolist()})")
                continue
            f = _transformed(values, q)
            scale = 1.0 if QUANTITIES[q].log else max(abs(float(values[finest])), floor)
            result = extrapolate(spacing, f, scale)
            table["extrapolated"][i] = _extrapolated_display(result.value, q)
            table["order"][i] = result.order
            table["gci"][i] = result.gci
            table["asymptotic"][i] = float(result.asymptotic)
            error[i] = relative_error(values, result.value, q, floor)
            sort = np.argsort(-spacing)  # coarse to fine
            for k in range(2, n_mesh):
                three = sort[k - 2: k + 1]
                p, _ = observed_order(f[three[2]], f[three[1]], f[three[0]],
                                      spacing[three[1]] / spacing[three[2]], spacing[three[0]] / spacing[three[1]])
                by_mesh[i, three[2]] = p
            if not result.asymptotic:
                notes.append(f"{q} at U = {speed:g} m/s: observed order {result.order:.3g}"
                             + (" (oscillatory)" if result.oscillatory else "") + ": not in the asymptotic range")
        unit = attrs.get("units", "1")
        out[f"{q}_extrapolated"] = ("speed", table["extrapolated"], {"units": unit, "long_name": f"mesh-converged {QUANTITIES[q].label} (Richardson{log_note})"})
        out[f"{q}_order"] = ("speed", table["order"], {"units": "1", "long_name": f"observed order of accuracy of the {QUANTITIES[q].label}, three finest meshes{log_note}"})
        out[f"{q}_gci"] = ("speed", table["gci"], {"units": "1", "long_name": f"grid convergence index of the {QUANTITIES[q].label} on the finest mesh, in the error measure of q_error"})
        out[f"{q}_asymptotic"] = ("speed", table["asymptotic"], {"units": "1", "long_name": "1 if the observed order is in [0.5, 4] and convergence is monotone"})
        out[f"{q}_order_by_mesh"] = (("speed", "mesh"), by_mesh, {"units": "1", "long_name": f"observed order of the three meshes ending at this one{log_note}"})
        denominator = "|R/R_ext - 1|" if QUANTITIES[q].log else ("|f - f_ext| / max(|f_ext|, sigma)" if floor else "|f/f_ext - 1|")
        out[f"{q}_error"] = (("speed", "mesh"), error, {"units": "1", "long_name": f"relative error of the {QUANTITIES[q].label} against the extrapolated value, {denominator}"})
        for part in ("domain", "tolerance", "newton"):
            name = f"{part}_{q}"
            if name not in study:
                continue
            values = study[name].values
            against, member, what = check_reference(study, part)
            references = study[f"{against}_{q}"].values[:, member]
            change = np.full(values.shape, np.nan)
            for i in range(n_speed):
                if np.all(np.isfinite(values[i])) and (not QUANTITIES[q].log or np.all(values[i] > 0.0)):
                    change[i] = relative_error(values[i], float(_transformed(references[i], q)), q, floor)
            out[f"{name}_change"] = (("speed", part), change, {"units": "1", "long_name": f"relative change of the {QUANTITIES[q].label} against {what}"})
    out.attrs["notes"] = "; ".join(notes)
    out.attrs["method"] = ("Richardson extrapolation with the observed order of the three finest meshes "
                           "(Celik et al. 2008, J. Fluids Eng. 130:078001); spacing h = 1/(n - 1)")
    return out


def check_reference(study: xr.Dataset, part: str) -> tuple[str, int, str]:
    """(the part, the member and its description) a check's ``part`` is measured against:
    the largest domain; the tightest tolerance; for the one Newton the nested solver's
    tightest tolerance where the study has it on the same mesh (the same discrete problem:
    what is left is the Newton's tolerance and, where the contact has two states, the state
    it found), else its own tightest."""
    if part == "domain":
        return "domain", int(np.argmax(study["domain"].values)), "the largest domain"
    if part == "newton" and "tolerance" in study.dims and study.attrs.get("tolerance_mesh") == study.attrs.get("newton_mesh"):
        return "tolerance", int(np.argmin(study["tolerance"].values)), "the nested solver's tightest tolerance"
    return part, int(np.argmin(study[part].values)), "the tightest tolerance"


def least_work_index(errors: np.ndarray, work: np.ndarray, target: float) -> int | None:
    """Index of the member doing the least ``work`` (nodes, or steps' worth of tolerance)
    whose error is finite and <= target, or None. By work, not by measured time: members of
    similar cost swap places with timing noise (36² and 51² at 0.001 m/s did, from one run of
    the study to the next), while the work a member does is fixed by its definition."""
    good = np.flatnonzero(np.isfinite(errors) & (errors <= target))
    return None if good.size == 0 else int(good[np.argmin(work[good])])


def coarsest_mesh(table: xr.Dataset, quantity: str, speed_index: int, target: float) -> tuple[int, float] | None:
    """(nodes a side, solve time s) of the coarsest mesh whose error is <= target, or None."""
    nodes = table["mesh"].values
    best = least_work_index(table[f"{quantity}_error"].values[speed_index], nodes, target)
    return None if best is None else (int(nodes[best]), float(table["solve_time"].values[speed_index, best]))


def percent(x: float) -> str:
    """A relative error as a percentage in two significant digits ('n/a' when not finite)."""
    if not np.isfinite(x):
        return "n/a"
    return f"{100 * x:.2g} %" if x >= 1e-4 else f"{100 * x:.1e} %"


def cost_table(table: xr.Dataset, quantities: Sequence[str], targets: Sequence[float]) -> list[str]:
    """Markdown rows of what each target error costs: per quantity and target, at each speed
    the coarsest square mesh that reaches it and its solve time (README.md quotes these
    rows, written by scripts/doc_numbers.py)."""
    speeds = table["speed"].values
    header = "| quantity | target | " + " | ".join(f"U = {s:g} m/s ({table['regime'].values[i]})" for i, s in enumerate(speeds)) + " |"
    lines = [header, "|" + "---|" * (2 + len(speeds))]
    for q in quantities:
        for target in targets:
            cells = []
            for i in range(len(speeds)):
                found = coarsest_mesh(table, q, i, target)
                cells.append(f"{found[0]}², {found[1]:.3g} s" if found else "finer than the ladder")
            lines.append(f"| {QUANTITIES[q].label} | {percent(target)} | " + " | ".join(cells) + " |")
    return lines


def markdown(table: xr.Dataset, targets: Sequence[float] = (0.1, 0.01, 0.001)) -> str:
    """The error budget as Markdown: what each target error costs, then per speed the mesh
    ladder (mesh -> error -> time), the extrapolated values, domain and tolerance checks."""
    quantities = table.attrs["quantities"].split(",")
    speeds = table["speed"].values
    finest = int(np.argmax(table["mesh"].values))
    lines = ["# What accuracy costs: mesh, error and solve time", "",
             f"Scene: `{table.attrs['scene_file']}` with overrides {table.attrs['scene_overrides']} (canonical YAML: "
             f"attribute `scene` of accuracy_cost.nc). Times: wall time of one solve, {table.attrs['timing']}.",
             f"Method: {table.attrs['method']}.",
             "Errors: contact resistance |R/R_ext - 1| (extrapolated in ln R); friction |f/f_ext - 1|; "
             "minimum film |h - h_ext| / max(|h_ext|, sigma).",
             "The ladder uses the automatic domain and the scene's tolerance: its errors are those of the mesh "
             "alone. The domain and tolerance tables of each speed add their own (domain table: the long inlet, "
             "mesh.far_inlet false, row 1 its automatic length: its truncation error at that speed; where the ladder's "
             "automatic domain is open to the far inlet, at speeds whose long inlet adds columns, the film upstream is "
             "the flooded one by construction).", ""]
    lines += ["## Coarsest square mesh for a target error (nodes a side, its solve time)", ""]
    lines += cost_table(table, quantities, targets)
    for i, speed in enumerate(speeds):
        lines += ["", f"## U = {speed:g} m/s ({table['regime'].values[i]}, fluid carries "
                  f"{100 * table['fluid_load_fraction'].values[i, finest]:.3g} % of the load on the finest mesh)", ""]
        lines.append("| mesh | nodes | x_min (mm) | solve time (s) | " + " | ".join(f"error {QUANTITIES[q].label}" for q in quantities) + " | converged |")
        lines.append("|" + "---|" * (5 + len(quantities)))
        for k, n in enumerate(table["mesh"].values):
            errors = " | ".join(percent(table[f"{q}_error"].values[i, k]) for q in quantities)
            lines.append(f"| {n} × {n} | {int(table['nodes'].values[i, k])} | {1e3 * table['x_min'].values[i, k]:.3g} | "
                         f"{table['solve_time'].values[i, k]:.3g} | {errors} | {int(table['converged'].values[i, k])} |")
        lines += ["", "| quantity | extrapolated | unit | observed order | GCI (finest mesh) | asymptotic |", "|---|---|---|---|---|---|"]
        for q in quantities:
            lines.append(f"| {QUANTITIES[q].label} | {table[f'{q}_extrapolated'].values[i]:.6g} | {table[q].attrs.get('units', '1')} | "
                         f"{table[f'{q}_order'].values[i]:.3g} | {percent(table[f'{q}_gci'].values[i])} | "
                         f"{'yes' if table[f'{q}_asymptotic'].values[i] == 1 else 'no'} |")
        for part, what in (("domain", f"domain length (x), at the spacing of the {table.attrs.get('domain_mesh')}² mesh; "
                                      "change against the largest domain (domains stop at "
                                      f"{DOMAIN_RADIUS_FRACTION:g} R, Eq. 4 needs |x| < R: rows with the "
                                      "same x_min were capped there)"),
                           ("tolerance", f"solver tolerance on the {table.attrs.get('tolerance_mesh')}² mesh; "
                                         "change against the tightest"),
                           ("newton", f"the one Newton (solver.method newton) at each solver tolerance on the "
                                      f"{table.attrs.get('newton_mesh')}² mesh; change against")):
            if part not in table.dims:
                continue
            if part == "newton":
                what = f"{what} {check_reference(table, part)[2]}"
            lines += ["", f"{what}:", "", f"| {part} | x_min (mm) | solve time (s) | " + " | ".join(QUANTITIES[q].label for q in quantities) + " |",
                      "|" + "---|" * (3 + len(quantities))]
            for k, key in enumerate(table[part].values):
                changes = " | ".join(percent(table[f"{part}_{q}_change"].values[i, k]) for q in quantities)
                lines.append(f"| {key:g} | {1e3 * table[f'{part}_x_min'].values[i, k]:.3g} | "
                             f"{table[f'{part}_solve_time'].values[i, k]:.3g} | {changes} |")
    if table.attrs.get("notes"):
        lines += ["", "Notes: " + table.attrs["notes"]]
    return "\n".join(lines) + "\n"


# --- the figure ----------------------------------------------------------------------------
