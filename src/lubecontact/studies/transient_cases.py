"""The transient figures' cases (config/transient.yaml): which scenes to run, by content hash.

A study names a base scene and overrides shared by every case, and its figures: curve
figures such as ``stop`` and ``shock`` (any figure with ``curves``: a list of {label, set:
overrides}, after the figure's optional set: overrides of every curve), design charts such
as ``reconnect`` and ``temperature`` (any figure with an ``x``: optional set: overrides of
every case; x: a dotted key and its values, one line per value of ``series``), convergence
ladders such as ``accuracy`` (any figure with ``meshes``: ``ladder_cases``), and one case
(any other figure, ``vibration``: its set).
Each case is a scene; its hash is
the case identity (results/transient/<hash>.nc), so a case shared by two figures (the
baseline stop) runs once. Library code: reads only the base scene.
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Mapping
from dataclasses import fields

import yaml

from lubecontact.scene.scene import SECTIONS, SceneError, load_scene


def _merge(base: dict, extra: Mapping | None) -> dict:
    out = copy.deepcopy(base)
    for key, value in (extra or {}).items():
        out[key] = _merge(out.get(key, {}), value) if isinstance(value, Mapping) and isinstance(out.get(key), Mapping) else value
    return out


# the keys a transient figure of each kind takes (figure_kind), and the study's own
FIGURE_KEYS = {
    "curves": {"title", "set", "curves"},
    "design chart": {"title", "set", "x", "x_scale", "values", "series"},
    "ladder": {"title", "set", "meshes", "mesh_ny", "line", "tolerances", "rest_refinements"},
    "single case": {"title", "set"},
}
STUDY_KEYS = {"base", "set", "figures"}
CURVE_KEYS = {"label", "set"}


def study_spec(path, overrides: Mapping | None = None) -> dict:
    """config/transient.yaml deep-merged with ``overrides`` (config["transient"]); ValueError
    listing every key it does not know (spec_problems), naming the file."""
    with open(path) as stream:
        spec = _merge(yaml.safe_load(stream), overrides)
    problems = spec_problems(spec)
    if problems:
        raise ValueError(f"{path} (with config transient:):\n  " + "\n  ".join(problems))
    return spec


def figure_kind(figure: Mapping) -> str:
    """What a transient figure draws, from the keys it has: curves, a design chart (x), a
    convergence ladder (meshes), or one case (set alone)."""
    if "curves" in figure:
        return "curves"
    if "x" in figure:
        return "design chart"
    return "ladder" if is_ladder(figure) else "single case"


def given_twice(items, key=None) -> list:
    """The items of ``items`` given more than once, each once, sorted (by ``key``)."""
    return sorted((item for item, count in Counter(items).items() if count > 1), key=key)


def spec_problems(spec: Mapping) -> list[str]:
    """Why the study ``spec`` is not what its figures can draw: unknown keys (a misspelt key
    was silently ignored), a curves figure with no curve (it drew empty axes) or with a label
    twice, a design chart with a value twice, a figure that names no case."""
    problems = [f"unknown key {key!r}; allowed: {', '.join(sorted(STUDY_KEYS))}" for key in spec if key not in STUDY_KEYS]
    for name, figure in (spec.get("figures") or {}).items():
        where = f"transient figure {name!r}"
        if not isinstance(figure, Mapping):
            problems.append(f"{where}: not a mapping")
            continue
        kind = figure_kind(figure)
        allowed = FIGURE_KEYS[kind]
        problems += [f"{where} ({kind}): unknown key {key!r}; allowed: {', '.join(sorted(allowed))}"
                     for key in figure if key not in allowed]
        if kind == "single case" and "set" not in figure:
            problems.append(f"{where}: names no case; give curves, a design chart (x, values, series), a ladder "
                            "(meshes) or a set")
        if kind == "curves":
            curves = figure["curves"] or []
            labels = [curve.get("label") for curve in curves if isinstance(curve, Mapping)]
            if not curves:
                problems.append(f"{where}: 'curves' is empty; a figure of curves needs one at least")
            problems += [f"{where}: curve label {label!r} given twice" for label in given_twice(labels, key=str)]
            problems += [f"{where}: curve {i + 1}: unknown key {key!r}; allowed: {', '.join(sorted(CURVE_KEYS))}"
                         for i, curve in enumerate(curves) if isinstance(curve, Mapping) for key in curve
                         if key not in CURVE_KEYS]
        if kind == "design chart":
            values = list(figure.get("values") or [])
            problems += [f"{where}: value {v!r} of 'values' given twice" for v in given_twice(values)]
    return problems


def _scene(spec: Mapping, overrides: Mapping):
    return load_scene(spec["base"], {**spec.get("set", {}), **overrides})


def figure_cases(spec: Mapping) -> dict[str, list[dict]]:
    """figure -> its cases, each {"id": hash, "overrides": {...}, "label": str, and for the
    design chart "x" and "series"}. Raises SceneError naming a bad value."""
    out = {}
    for name, figure in spec["figures"].items():
        kind = figure_kind(figure)
        if kind == "curves":
            shared = figure.get("set") or {}
            out[name] = [{"label": curve["label"], "overrides": {**shared, **(curve.get("set") or {})}}
                         for curve in figure["curves"]]
        elif kind == "design chart":
            out[name] = _design_chart(name, figure)
        elif kind == "ladder":
            out[name] = ladder_cases(name, figure)
        else:
            out[name] = [{"label": name, "overrides": dict(figure["set"])}]
    for name, cases in out.items():
        for case in cases:
            try:
                case["id"] = _scene(spec, case["overrides"]).hash
            except SceneError as err:  # which figure and curve, not only the base scene file
                raise SceneError(f"{err.origin}, transient figure {name!r}, {case['label']!r}", err.problems) from None
    return out


def _design_chart(name: str, chart: Mapping) -> list[dict]:
    """The cases of a design chart: every x value for every series value. ValueError where
    either list is empty (a chart of no case drew empty axes without a word)."""
    (series_key, series_values), = chart["series"].items()
    for what, values in (("values", chart["values"]), (f"series {series_key}", series_values)):
        if not values:
            raise ValueError(f"transient figure {name!r}: '{what}' is empty; a design chart needs at least one "
                             "value on each")
    return [
        {"label": f"{key_words(series_key)} = {s:g} {key_units(series_key)}", "x": x, "series": s,
         "overrides": {**(chart.get("set") or {}), chart["x"]: x, series_key: s}}
        for s in series_values for x in chart["values"]
    ]


def is_ladder(figure: Mapping) -> bool:
    """Whether a transient figure is a convergence ladder (it names ``meshes``)."""
    return "meshes" in figure


def ladder_cases(name: str, ladder: Mapping) -> list[dict]:
    """The cases of a convergence ladder (studies/transient_accuracy.py): the figure's scene
    (its optional set:) on every mesh of ``meshes``, nodes along the sliding direction, each
    with ``mesh_ny`` nodes along the cylinder axis (n x mesh_ny; n x n without it, n x 1 with
    ``line: true``), part "mesh", then on the square mesh ``tolerances.mesh`` at every
    motion.tolerance of ``tolerances.values``, part "tolerance", and on the mesh
    ``rest_refinements.mesh`` (x ``rest_refinements.mesh_ny``) at every motion.rest_refinement
    of ``rest_refinements.values``, part "rest_refinement"; each case names its nodes
    along x and y (``nx``, ``ny``) beside its overrides, which the workflow does not pass on. Each ladder needs three
    different values at least (Richardson extrapolation with an observed order); ValueError
    names the figure."""
    shared = dict(ladder.get("set") or {})
    line = bool(ladder.get("line", False))

    def whole(n, what: str) -> int:
        if int(n) != n or n < 3:
            raise ValueError(f"transient figure {name!r}: {what} must be whole numbers >= 3, got {n!r}")
        return int(n)

    def nodes(n, across=None) -> dict:
        return {"mesh.nx": whole(n, "mesh nodes"), "mesh.ny": 1 if line else whole(across or n, "mesh_ny")}

    def shape(overrides: dict) -> str:
        return f"{overrides['mesh.nx']} \u00d7 {overrides['mesh.ny']} nodes"

    meshes = list(ladder["meshes"])
    if len(set(meshes)) < 3:
        raise ValueError(f"transient figure {name!r}: 'meshes' needs three different meshes at least, got {meshes}")
    ladder_meshes = [(int(n), nodes(n, ladder.get("mesh_ny"))) for n in sorted(meshes)]
    cases = [{"label": shape(mesh), "part": "mesh", "value": n, "nx": n, "ny": mesh["mesh.ny"],
              "overrides": {**shared, **mesh}} for n, mesh in ladder_meshes]
    tolerances = ladder.get("tolerances")
    if tolerances is not None:
        values = sorted((float(t) for t in tolerances["values"]), reverse=True)
        if len(set(values)) < 3 or min(values) <= 0.0:
            raise ValueError(f"transient figure {name!r}: 'tolerances.values' needs three different positive "
                             f"tolerances at least, got {tolerances['values']}")
        mesh = nodes(tolerances["mesh"])
        cases += [{"label": f"tolerance {t:g}, {shape(mesh)}", "part": "tolerance", "value": t, "nx": mesh["mesh.nx"],
                   "ny": mesh["mesh.ny"], "overrides": {**shared, **mesh, "motion.tolerance": t}} for t in values]
    refinements = ladder.get("rest_refinements")
    if refinements is not None:
        values = sorted(refinements["values"])
        if len(set(values)) < 3 or any(int(r) != r or r < 1 for r in values):
            raise ValueError(f"transient figure {name!r}: 'rest_refinements.values' needs three different whole "
                             f"numbers >= 1 at least, got {refinements['values']}")
        mesh = nodes(refinements["mesh"], refinements.get("mesh_ny"))
        cases += [{"label": f"mesh at rest {int(r)} times finer, {shape(mesh)}", "part": "rest_refinement",
                   "value": int(r), "nx": mesh["mesh.nx"], "ny": mesh["mesh.ny"],
                   "overrides": {**shared, **mesh, "motion.rest_refinement": int(r)}} for r in values]
    return cases


def key_words(dotted: str) -> str:
    """What a scene key is, in words (its schema doc without the parenthesis), e.g.
    'dynamic viscosity mu' for lubricant.viscosity: figure labels name no config key."""
    section, name = dotted.split(".")
    doc = next(f for f in fields(SECTIONS[section]) if f.name == name).metadata["doc"]
    return doc.split(" (")[0]


def key_units(dotted: str) -> str:
    """The unit of a scene key (its schema rule), e.g. 'Pa s' for lubricant.viscosity."""
    section, name = dotted.split(".")
    rule = next(f for f in fields(SECTIONS[section]) if f.name == name).metadata["rule"]
    return getattr(rule, "unit", "1")


def case_overrides(spec: Mapping, cases: Mapping) -> dict[str, dict]:
    """case id -> the full dotted overrides of its scene (plain values, for Snakemake params)."""
    return {c["id"]: {**spec.get("set", {}), **c["overrides"]} for group in cases.values() for c in group}
