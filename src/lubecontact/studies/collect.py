"""A figure's cases gathered into one ``xarray.Dataset`` with its swept parameters as
dimensions (the workflow's collect rule), from the layout studies/figure_grids.py plans."""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import xarray as xr

from lubecontact.studies.figure_grids import GridError


def collect(layout: Mapping, open_case: Callable[[str], object]):
    """One figure's cases as an ``xarray.Dataset`` with the swept parameters as dimensions.

    ``layout`` is ``FigureGrid.layout()``; ``open_case(id)`` returns that case's
    casefiles.CaseRecord (read_case of its file).
    Every 0-d variable of the cases becomes an array over (swept dims..., speed) with the
    case's units and long_name; ``case_id`` and ``scene`` (canonical YAML) say where each
    point comes from. A case variable named like a coordinate (``speed``) must agree with it.
    """
    ids = np.array(layout["case_ids"], dtype=object)
    dims = [d["name"] for d in layout["dims"]]
    if ids.ndim != len(dims):
        raise GridError(f"{layout['figure']}: case_ids have {ids.ndim} dimensions, layout names {len(dims)}")
    coords = {}
    for d in layout["dims"]:
        for c in d["coords"]:
            coords[c["name"]] = xr.Variable((d["name"],), np.asarray(c["values"]), c["attrs"])
    for name, r in layout["recorded"].items():
        coords[name] = xr.Variable((), r["value"], r["attrs"])

    arrays: dict[str, np.ndarray] = {}
    attrs: dict[str, dict] = {}
    scenes = np.empty(ids.shape, dtype=object)
    versions = set()
    for index in np.ndindex(ids.shape):
        case_id = ids[index]
        case = open_case(case_id)
        where = f"{layout['figure']}: case {case_id}"
        if case.attrs.get("scene_hash") != case_id:
            raise GridError(f"{where}: the file holds scene {case.attrs.get('scene_hash')!r}, not {case_id!r}")
        if not arrays:
            for v, (value, var_attrs) in case.scalars.items():
                if v not in coords:
                    arrays[v] = np.empty(ids.shape, dtype=value.dtype)
                    attrs[v] = {"units": var_attrs["units"], "long_name": var_attrs["long_name"]}
        elif set(case.scalars) - set(coords) != set(arrays):
            raise GridError(f"{where}: variables {sorted(case.scalars)} differ from the figure's first case {sorted(arrays)}")
        for v, (value, _) in case.scalars.items():
            if v in coords:
                expected = coords[v].values[index[dims.index(coords[v].dims[0])]] if coords[v].dims else coords[v].values
                if not np.isclose(value, expected, rtol=1e-12, atol=0.0):
                    raise GridError(f"{where}: {v} = {value} in the file, {expected} in the grid")
            else:
                arrays[v][index] = value
        scenes[index] = case.attrs["scene"]
        versions.add(case.attrs["lubecontact_version"])

    data_vars = {v: xr.Variable(dims, a, attrs[v]) for v, a in arrays.items()}
    data_vars["case_id"] = xr.Variable(dims, ids.astype(str), {"long_name": "case id: content hash of the scene (results/cases/<id>.nc)"})
    data_vars["scene"] = xr.Variable(dims, scenes.astype(str), {"long_name": "canonical scene YAML of the case"})
    return xr.Dataset(
        data_vars,
        coords=coords,
        attrs={
            "title": f"lubecontact cases of {layout['figure']} over {', '.join(dims)}",
            "Conventions": "CF-1.10",
            "figure": layout["figure"],
            "base_scene": layout["base_scene"],
            "grid": layout["grid"],
            "lubecontact_version": ", ".join(sorted(versions)),
        },
    )
