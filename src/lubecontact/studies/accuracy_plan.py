"""The accuracy study's plan (config/accuracy.yaml): which quantities it may study, the
study as read and checked (``study_spec``) and every solve it makes (``study_points``).

Planned at parse time by the workflow (workflow/rules/accuracy.smk): it loads scenes and
sizes meshes, but neither the solver nor xarray. Running the study and extrapolating its
results is studies/accuracy.py.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from lubecontact.numerics.mesh import domain_x, nodes_x
from lubecontact.scene import load_scene
from lubecontact.studies.figure_grids import merge, read_yaml


@dataclass(frozen=True)
class Quantity:
    """How a case quantity is extrapolated and how its error is measured."""

    log: bool  # extrapolate ln(value) (values span decades; must be > 0)
    floor: str | None  # scene key whose value bounds the error's denominator from below
    label: str  # short name in tables and legends


QUANTITIES = {
    "contact_resistance": Quantity(log=True, floor=None, label="contact resistance"),
    "friction_coefficient": Quantity(log=False, floor=None, label="friction coefficient"),
    # h_min crosses zero between regimes: its error is relative to max(|h_ext|, sigma)
    "min_film_thickness": Quantity(log=False, floor="roughness.sigma", label="minimum film thickness"),
}


STUDY_KEYS = {"scene", "set", "speeds", "meshes", "quantities", "domain", "tolerance", "newton", "timing", "targets"}


def study_spec(path, overrides: Mapping | None = None) -> dict:
    """The study of ``path`` (config/accuracy.yaml) deep-merged with ``overrides``, checked:
    unknown keys, fewer than three meshes, unknown quantities or non-positive speeds are
    refused with a message naming the key. Plain Python (lists, dicts, floats) throughout."""
    spec = merge(read_yaml(path) or {}, overrides or {})
    unknown = sorted(set(spec) - STUDY_KEYS)
    if unknown:
        raise ValueError(f"{path}: unknown keys {unknown}; allowed: {', '.join(sorted(STUDY_KEYS))}")
    for key in ("scene", "speeds", "meshes", "quantities"):
        if key not in spec:
            raise ValueError(f"{path}: '{key}' is required")
    meshes = [int(n) for n in spec["meshes"]]
    if len(meshes) < 3 or min(meshes) < 3 or len(set(meshes)) != len(meshes):
        raise ValueError(f"{path}: 'meshes' needs at least three different node counts >= 3, got {spec['meshes']}")
    speeds = [float(u) for u in spec["speeds"]]
    if not speeds or min(speeds) <= 0.0:
        raise ValueError(f"{path}: 'speeds' must be positive (m/s), got {spec['speeds']}")
    bad = sorted(set(spec["quantities"]) - set(QUANTITIES))
    if bad:
        raise ValueError(f"{path}: unknown quantities {bad}; allowed: {', '.join(QUANTITIES)}")
    spec["meshes"], spec["speeds"] = sorted(meshes), speeds
    spec.setdefault("targets", [0.1, 0.01, 0.001])
    return spec


# The domain study's longest domain stays within this fraction of the cylinder radius
# (study_points): Eq. (4)'s gap R - sqrt(R^2 - x^2) exists for |x| < R only, and this far out
# it is ~R/2, a film no fluid pressure reaches.
DOMAIN_RADIUS_FRACTION = 0.9


def study_points(spec: Mapping) -> list[dict]:
    """Every solve of the study: {part, speed, key, overrides} in run order.

    part "mesh": nx = ny = n for n in spec["meshes"]; part "domain": the automatic domain
    scaled by each of spec["domain"]["scales"] about x = 0, in whole cells of the mesh
    spec["domain"]["mesh"] (same spacing and node positions; nx grows with the domain, ny
    stays), but never past DOMAIN_RADIUS_FRACTION of the radius: the film-following inlet
    is already long at high speed (6.3 mm of R = 10 mm at 10 m/s on Table 1), and Eq. (4)
    needs |x| < R (the study records each solve's x_min); part "tolerance": solver.tolerance = each of
    spec["tolerance"]["values"] on mesh spec["tolerance"]["mesh"]; part "newton": the same by
    the one Newton (solver.method newton) for spec["newton"]["values"] on spec["newton"]["mesh"].
    """
    base = load_scene(spec["scene"], spec.get("set") or {})
    points = []
    for speed in spec["speeds"]:
        speed = float(speed)
        for n in spec["meshes"]:
            points.append({"part": "mesh", "speed": speed, "key": int(n), "overrides": {"mesh.nx": int(n), "mesh.ny": int(n)}})
        domain = spec.get("domain")
        if domain:
            n = int(domain["mesh"])
            reference = base.replace({"mesh.nx": n, "mesh.ny": n, "operating.speed": speed})
            x_min, x_max = domain_x(reference, far_inlet=False)  # the automatic inlet of this speed (it follows the film)
            dx = (x_max - x_min) / (nodes_x(reference, far_inlet=False) - 1)
            for scale in domain["scales"]:
                # whole cells added (removed) at each end: the nodes stay where the reference
                # mesh has them, so only the domain's truncation changes, not the grid's offset
                reach = DOMAIN_RADIUS_FRACTION * reference.geometry.radius
                left = min(round(-x_min * (float(scale) - 1.0) / dx), math.floor((reach + x_min) / dx))
                right = min(round(x_max * (float(scale) - 1.0) / dx), math.floor((reach - x_max) / dx))
                points.append({"part": "domain", "speed": speed, "key": float(scale), "overrides": {
                    "mesh.nx": nodes_x(reference, far_inlet=False) + left + right, "mesh.ny": n, "mesh.x_min": x_min - left * dx,
                    "mesh.x_max": x_max + right * dx, "mesh.far_inlet": False}})
        for part, method in (("tolerance", {}), ("newton", {"solver.method": "newton"})):
            ladder = spec.get(part)
            if ladder:
                n = int(ladder["mesh"])
                for value in ladder["values"]:
                    points.append({"part": part, "speed": speed, "key": float(value), "overrides": {
                        "mesh.nx": n, "mesh.ny": n, "solver.tolerance": float(value), **method}})
    return points
