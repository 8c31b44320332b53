"""One operating point's answer as plain arrays (docs/DESIGN.md "Output of one case") and its two
forms: the ``xarray.Dataset`` of the public API (``to_dataset``) and the case file, written
with netCDF4 directly (``write``).

A solve job or ``lubecontact solve`` then never imports xarray (with pandas, 0.3-0.4 s of
every process) and writes a case in 10 instead of 16 ms. The file is the one
``output.write_case(result.to_dataset(), path)`` writes: ``xarray.open_dataset`` reads the
same variables, attributes and encodings from both (tests/test_case_result.py).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import netCDF4
import numpy as np

from lubecontact.io.atomic_write import atomic_path
from lubecontact.io.case_schema import EXTRA_ATTRS, FIELDS, INTEGER_SCALARS, SCALARS, history_line
from lubecontact.io.version import package_version

_COORDS = {
    "x": {"units": "m", "long_name": "position along sliding (inlet at x_min)"},
    "y": {"units": "m", "long_name": "position along the cylinder axis"},
}


def _attrs(table, name):
    units, long_name = table[name]
    extra = {k: np.asarray(v, dtype=np.int32) if k == "flag_masks" else v for k, v in EXTRA_ATTRS.get(name, {}).items()}
    return {"units": units, "long_name": long_name, **extra}


@dataclass(frozen=True)
class CaseResult:
    """Scalars (keys of io/case_schema.SCALARS, as 0-d int32 or float64 arrays), global attributes
    and, on request, fields on the mesh (``y``, ``x``) with their coordinates."""

    scalars: dict
    attrs: dict
    fields: dict | None = None
    x: np.ndarray | None = None
    y: np.ndarray | None = None

    @classmethod
    def build(cls, scene, scalars: dict, fields: dict | None, mesh, effects_run: dict, notes: str, validity: str) -> CaseResult:
        """``scalars`` must hold exactly the keys of SCALARS; ``scene`` is the scene as
        requested (its canonical YAML and hash identify the case)."""
        missing = set(SCALARS) - set(scalars)
        if missing:
            raise KeyError(f"case output lacks {sorted(missing)}")
        typed = {name: np.asarray(value, dtype=np.int32 if name in INTEGER_SCALARS else np.float64) for name, value in scalars.items()}
        attrs = {
            "title": "lubecontact case: one operating point of a lubricated rough electrical contact",
            "Conventions": "CF-1.10",
            "scene": scene.canonical_yaml(),
            "scene_hash": scene.hash,
            "lubecontact_version": package_version(),
            "effects_run": ",".join(k for k, v in effects_run.items() if v) or "none",
            "notes": notes,
            "validity": validity,
        }
        if not fields:
            return cls(typed, attrs)
        grids = {name: np.asarray(value, dtype=np.float64) for name, value in fields.items()}
        return cls(typed, attrs, grids, np.asarray(mesh.x, dtype=np.float64), np.asarray(mesh.y, dtype=np.float64))

    def with_attrs(self, **extra: str) -> CaseResult:
        """The same result with global attributes added (a workflow's source fingerprint)."""
        return replace(self, attrs={**self.attrs, **extra})

    def to_dataset(self):
        """The case as the public API's ``xarray.Dataset``."""
        import xarray as xr

        data_vars = {name: xr.Variable((), value, _attrs(SCALARS, name)) for name, value in self.scalars.items()}
        coords = {}
        if self.fields:
            coords = {"x": xr.Variable(("x",), self.x, _COORDS["x"]), "y": xr.Variable(("y",), self.y, _COORDS["y"])}
            data_vars.update({name: xr.Variable(("y", "x"), value, _attrs(FIELDS, name)) for name, value in self.fields.items()})
        return xr.Dataset(data_vars, coords=coords, attrs=dict(self.attrs))

    def write(self, path) -> None:
        """Write the case file atomically (a killed process never leaves a file that looks
        complete) with a CF ``history`` line; NaN is the fill value of data variables, the
        coordinates have none (CF 2.5.1), as output.write_case writes a Dataset."""
        with atomic_path(path, make_parents=True) as tmp, netCDF4.Dataset(tmp, "w", format="NETCDF4") as nc:
            nc.setncatts({**self.attrs, "history": history_line(self.attrs.get("history"))})
            for name, value in self.scalars.items():
                _variable(nc, name, value, (), _attrs(SCALARS, name))
            if self.fields:
                for name in ("x", "y"):
                    nc.createDimension(name, getattr(self, name).size)
                    _variable(nc, name, getattr(self, name), (name,), _COORDS[name], fill=None)
                for name, value in self.fields.items():
                    _variable(nc, name, value, ("y", "x"), _attrs(FIELDS, name))


def _variable(nc, name, value, dims, attrs, fill=np.nan):
    """One netCDF variable; floats get ``fill`` as _FillValue, integers none (xarray's default)."""
    var = nc.createVariable(name, value.dtype, dims, fill_value=fill if value.dtype.kind == "f" else None)
    var.setncatts(attrs)
    var[...] = value
