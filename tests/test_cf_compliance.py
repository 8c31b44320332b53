"""CF-1.10 compliance of what the CLI writes (issue 13), judged by the IOOS compliance
checker, not by our own reading of the conventions: no _FillValue on coordinate variables,
a history attribute. The pipeline's collected and accuracy datasets: test_workflow.py."""

from pathlib import Path

from cfcheck import cf_findings

from lubecontact.cli import main as cli

SCENE = str(Path(__file__).resolve().parents[1] / "config" / "scenes" / "table1.yaml")
COARSE = ["--set", "mesh.nx=15", "--set", "mesh.ny=11"]


def test_case_with_fields_and_sweep_pass_the_cf_checker(tmp_path):
    case, swept = tmp_path / "case.nc", tmp_path / "sweep.nc"
    assert cli.main(["solve", SCENE, *COARSE, "--fields", "--out", str(case)]) == 0
    assert cli.main(["sweep", SCENE, *COARSE, "--speeds", "0.01,1", "--out", str(swept)]) == 0
    both = tmp_path / "both.nc"  # a sweep both ways: a (direction, speed) file with a text coordinate
    assert cli.main(["sweep", SCENE, *COARSE, "--speeds", "0.01,1", "--direction", "both", "--out", str(both)]) == 0
    assert cf_findings(case) + cf_findings(swept) + cf_findings(both) == []


def test_the_checker_sees_a_fill_value_on_a_coordinate(tmp_path):
    """The check can fail: the same sweep written by plain xarray (the state before issue 13)."""
    import xarray as xr

    swept = tmp_path / "sweep.nc"
    assert cli.main(["sweep", SCENE, *COARSE, "--speeds", "0.01", "--out", str(swept)]) == 0
    ds = xr.load_dataset(swept)
    del ds.attrs["history"]
    ds.to_netcdf(tmp_path / "plain.nc")
    findings = "\n".join(cf_findings(tmp_path / "plain.nc"))
    assert "'speed' must not have the _FillValue" in findings and "history" in findings
