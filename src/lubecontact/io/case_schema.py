"""What a case holds (docs/DESIGN.md "Output of one case": names, units, long names of its
variables; case_result.CaseResult assembles and writes one) and the atomic, CF-1.10
netCDF writer of a Dataset (a case as a Dataset, a figure's collected data)."""

from __future__ import annotations

import sys
import typing
from datetime import datetime, timezone
from pathlib import Path

from lubecontact.io.atomic_write import atomic_path
from lubecontact.io.version import package_version

if typing.TYPE_CHECKING:
    import xarray as xr

# name: (units, long_name). Every variable a case writes is listed here, so that no
# quantity leaves the model without its unit.
SCALARS = {
    "contact_resistance": ("ohm", "electrical contact resistance of the whole path (spots, film, cluster)"),
    "spot_resistance": ("ohm", "resistance of the metal spots in parallel (Eqs. 15-17)"),
    "macro_constriction_resistance": ("ohm", "Greenwood cluster constriction resistance (0 when not modelled)"),
    "film_resistance": ("ohm", "resistance of the lubricant film in parallel over the domain (inf when insulating)"),
    "friction_coefficient": ("1", "friction coefficient (boundary friction of solid load + fluid shear) / applied force"),
    "fluid_force": ("N", "load carried by the fluid film (Eq. 5)"),
    "contact_force": ("N", "load carried by asperity contact (Eq. 11 summed over nodes)"),
    "applied_force": ("N", "applied normal force F (Eq. 18)"),
    "fluid_load_fraction": ("1", "fluid force / (fluid force + contact force)"),
    "min_film_thickness": ("m", "minimum mean-plane separation h over the mesh (may be negative)"),
    "central_film_thickness": ("m", "mean-plane separation h at x = 0, y = 0 (may be negative)"),
    "separation": ("m", "vertical position z of the cylinder (Eq. 3)"),
    "real_contact_area": ("m2", "real area of asperity contact (Eq. 15 integrand, A_r/A_n <= 1, summed over nodes)"),
    "converged": ("1", "1 if the coupled solve met its tolerances, else 0"),
    "iterations": ("1", "outer (deformation) iterations of the coupled solve"),
    "force_residual": ("N", "applied force minus fluid and contact forces (Eq. 18)"),
    "deformation_residual": ("m", "last change of the deformation field in the coupling loop (max norm)"),
    "reynolds_residual": ("1", "relative residual of the discrete Reynolds complementarity problem"),
    "solve_time": ("s", "wall time of the solve, model assembly included"),
    "open_circuit": ("1", "1 if contact_resistance exceeds interface.open_resistance"),
    "clamped_nodes": ("1", "nodes where A_r/A_n was clamped for the alleviation factor (Eq. 16)"),
    "speed": ("m s-1", "sliding speed U of the block"),
    "valid": ("1", "1 if the case stays within every sub-model's range, else 0 (see the validity attribute)"),
    "validity_flags": ("1", "the validity flags a case raised, a bit field (CF flag_masks / flag_meanings)"),
}

# The validity flags (model/validity.py) in the order of their bits in ``validity_flags``:
# the file's contract, so that a figure can mark each kind of breach its own way.
VALIDITY_FLAGS = ("gw_area", "area_capped", "bulk_yield", "bandwidth", "flow_factor_range", "inlet")
# attributes a variable carries besides units and long_name
EXTRA_ATTRS = {
    "validity_flags": {"flag_masks": [1 << bit for bit in range(len(VALIDITY_FLAGS))],
                       "flag_meanings": " ".join(VALIDITY_FLAGS)},
}

FIELDS = {
    "fluid_pressure": ("Pa", "fluid film pressure p (Eq. 1)"),
    "contact_pressure": ("Pa", "nominal asperity contact pressure (Eq. 11 per nominal area)"),
    "film_thickness": ("m", "mean-plane separation h = h_o + z + delta (Eq. 3)"),
    "deformation": ("m", "macro elastic deformation delta of both surfaces (influence coefficients)"),
    "film_content": ("1", "film content theta: fraction of the expected gap filled (effects.cavitation: jfo only)"),
}

INTEGER_SCALARS = ("converged", "iterations", "open_circuit", "clamped_nodes", "valid", "validity_flags")


def history_line(previous: str | None = None) -> str:
    """CF ``history``: ``previous`` with a line appended saying when and by what this file
    is written."""
    stamp = datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    line = f"{stamp} written by lubecontact {package_version()} ({Path(sys.argv[0]).name or 'python'})"
    return f"{previous}\n{line}" if previous else line


def cf_ready(dataset: xr.Dataset) -> tuple[xr.Dataset, dict]:
    """(dataset with a CF ``history`` line appended, netCDF encoding) for CF-1.10: coordinate
    variables carry no ``_FillValue`` (CF 2.5.1; xarray adds NaN to every float by default)."""
    out = dataset.copy()
    out.attrs["history"] = history_line(dataset.attrs.get("history"))
    encoding = {name: {"_FillValue": None} for name in out.coords if out[name].dtype.kind in "fc"}
    return out, encoding


def write_case(dataset: xr.Dataset, path) -> None:
    """Write atomically: a killed process never leaves a file that looks complete."""
    dataset, encoding = cf_ready(dataset)
    with atomic_path(path, make_parents=True) as tmp:
        dataset.to_netcdf(tmp, encoding=encoding)
