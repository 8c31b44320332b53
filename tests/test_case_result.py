"""A case written with netCDF4 directly (CaseResult.write) against the same case written by
xarray (output.write_case of CaseResult.to_dataset): xarray must read the same variables,
attributes and encodings from both; and a solve job never imports xarray."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from lubecontact.io.case_schema import write_case
from lubecontact.model.solve import solve, solve_case
from lubecontact.scene.scene import load_scene

SRC = Path(__file__).resolve().parents[1] / "src"
ENCODING_KEYS = ("dtype", "_FillValue", "zlib", "shuffle", "contiguous", "chunksizes")


def _both(result, tmp_path):
    direct, via_xarray = tmp_path / "direct.nc", tmp_path / "xarray.nc"
    result.write(direct)
    write_case(result.to_dataset(), via_xarray)
    return xr.open_dataset(direct).load(), xr.open_dataset(via_xarray).load()


def _same(a, b):
    for ds in (a, b):
        assert "written by lubecontact" in ds.attrs.pop("history")
    xr.testing.assert_identical(a, b)
    assert list(a.variables) == list(b.variables)
    for name in a.variables:
        enc_a = {k: a[name].encoding.get(k) for k in ENCODING_KEYS}
        enc_b = {k: b[name].encoding.get(k) for k in ENCODING_KEYS}
        np.testing.assert_equal(enc_a, enc_b, err_msg=name)


@pytest.mark.parametrize("overrides", [{"mesh.nx": 15, "mesh.ny": 11}, {"mesh.nx": 15, "mesh.ny": 1, "effects.cavitation": "jfo"}])
def test_direct_case_file_reads_as_the_xarray_written_one(overrides, tmp_path):
    result, _ = solve_case(load_scene({}, overrides), fields=True)
    assert set(result.fields) >= {"fluid_pressure", "deformation"}
    a, b = _both(result.with_attrs(workflow_fingerprint="abc"), tmp_path)
    _same(a, b)
    assert a["x"].size == result.x.size and "_FillValue" not in a["x"].encoding  # CF 2.5.1
    assert a["converged"].dtype == np.int32 and np.isnan(a["fluid_pressure"].encoding["_FillValue"])
    assert a.attrs["workflow_fingerprint"] == "abc"


def test_scalars_only_case_and_the_public_dataset(tmp_path):
    scene = load_scene({}, {"mesh.nx": 15, "mesh.ny": 1})
    result, _ = solve_case(scene)
    _same(*_both(result, tmp_path))
    ds = solve(scene)  # the public API: the same case as a Dataset
    assert ds.attrs["scene_hash"] == scene.hash and ds.attrs["validity"] == result.attrs["validity"]
    assert float(ds["contact_resistance"]) == float(result.scalars["contact_resistance"])


def test_missing_output_is_refused():
    from lubecontact.io.case_result import CaseResult

    with pytest.raises(KeyError, match="lacks"):
        CaseResult.build(load_scene({}), {"speed": 1.0}, None, None, {}, "", "ok")


def test_a_solve_job_and_the_cli_never_import_xarray(tmp_path):
    code = (
        "import sys, lubecontact\n"
        "from lubecontact.model.solve import solve_case\n"
        "from lubecontact.cli.main import main\n"
        f"r, _ = solve_case(lubecontact.load_scene({{}}, {{'mesh.nx': 15, 'mesh.ny': 1}}))\n"
        f"r.write({str(tmp_path / 'a.nc')!r})\n"
        f"main(['solve', '--set', 'mesh.nx=15', '--set', 'mesh.ny=1', '--out', {str(tmp_path / 'b.nc')!r}, "
        f"{str(Path(__file__).resolve().parents[1] / 'config' / 'scenes' / 'table1.yaml')!r}])\n"
        "print(sorted(m for m in ('xarray', 'pandas') if m in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env={"PYTHONPATH": str(SRC)}, check=True)
    assert done.stdout.strip().splitlines()[-1] == "[]"
    assert (tmp_path / "a.nc").exists() and (tmp_path / "b.nc").exists()
