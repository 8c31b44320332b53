"""Issue 13 in the pipeline's library pieces: a case file counts only if complete
(lubecontact.io.case_files), job logs keep tracebacks (lubecontact.io.job_log), job plans are files
rewritten only on change (lubecontact.io.job_plans). End to end: test_workflow.py."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from lubecontact.io import case_files as casefiles
from lubecontact.io import job_log as joblog
from lubecontact.io import job_plans as plans
from lubecontact.io.case_schema import write_case
from lubecontact.model.auto_effects import decreasing_root
from lubecontact.model.solve import solve
from lubecontact.scene.scene import load_scene


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    scene = load_scene({}, {"mesh.nx": 15, "mesh.ny": 1})
    ds = solve(scene)
    ds.attrs[casefiles.FINGERPRINT] = "abc"
    path = tmp_path_factory.mktemp("case") / f"{scene.hash}.nc"
    write_case(ds, path)
    return path, scene.hash


def test_complete_case_and_every_kind_of_incomplete_one(case, tmp_path):
    path, case_id = case
    assert casefiles.case_problem(path, case_id) is None
    assert casefiles.case_problem(path, case_id, "abc") is None
    assert casefiles.case_problem(path, case_id, "other") == "solved by other solver sources"
    assert casefiles.case_problem(path, "0" * 16).startswith("scene_hash is")
    assert casefiles.case_problem(tmp_path / "none.nc", case_id) == "missing"
    data = path.read_bytes()
    for name, content in {"truncated": data[: len(data) // 2], "empty": b"", "text": b"not netcdf"}.items():
        bad = tmp_path / f"{name}.nc"
        bad.write_bytes(content)
        assert casefiles.case_problem(bad, case_id).startswith("unreadable"), name
        with pytest.raises(RuntimeError, match=f"(?s)case file {re.escape(str(bad))} does not read.*run snakemake again"):
            casefiles.read_case(bad)


def test_read_case_gives_what_xarray_reads(case):
    """collect's netCDF4 reader against xarray's decoding of the same file: every 0-d
    variable with its value (inf and NaN included), dtype and attributes, and the globals."""
    import numpy as np
    import xarray as xr

    path, case_id = case
    record = casefiles.read_case(path)
    expected = casefiles.CaseRecord.from_dataset(xr.load_dataset(path))
    assert record.attrs == expected.attrs and record.attrs["scene_hash"] == case_id
    assert list(record.scalars) == list(expected.scalars) and "film_resistance" in record.scalars
    assert np.isinf(record.scalars["film_resistance"][0])  # no metallic path through a dry film
    for name, (value, attrs) in expected.scalars.items():
        got, got_attrs = record.scalars[name]
        assert got.dtype == value.dtype and got.shape == (), name
        np.testing.assert_array_equal(got, value, err_msg=name)
        assert got_attrs.keys() == attrs.keys(), name  # values may be arrays (a bit field's flag_masks)
        assert all(np.array_equal(got_attrs[key], attrs[key]) for key in attrs), name


def test_quarantine_moves_only_bad_files_and_remembers_good_ones(case, tmp_path):
    path, case_id = case
    good = tmp_path / f"{case_id}.nc"
    good.write_bytes(path.read_bytes())
    bad = tmp_path / "0123456789abcdef.nc"
    bad.write_bytes(path.read_bytes()[:3000])
    memo = tmp_path / ".complete.json"
    cases = {case_id: str(good), "0123456789abcdef": str(bad), "fedcba9876543210": str(tmp_path / "absent.nc")}
    moved = casefiles.quarantine(cases, memo)
    assert len(moved) == 1 and moved[0].startswith(f"{bad}: unreadable") and not bad.exists()
    assert len(list((tmp_path / ".corrupt").iterdir())) == 1 and good.exists()
    # remembered: not read again while size, mtime and inode stay (a stub reader proves it)
    reads = []
    original = casefiles.case_problem
    casefiles.case_problem = lambda *a, **k: reads.append(a) or original(*a, **k)
    try:
        assert casefiles.quarantine(cases, memo) == [] and reads == []
        good.write_bytes(path.read_bytes()[:100])  # truncated in place: re-read and moved
        assert len(casefiles.quarantine(cases, memo)) == 1 and len(reads) == 1
    finally:
        casefiles.case_problem = original


def test_a_product_that_does_not_read_back_is_moved_aside(case, tmp_path):
    path, _ = case
    good, bad = tmp_path / "fig04.nc", tmp_path / "fig06.nc"
    good.write_bytes(path.read_bytes())
    bad.write_bytes(path.read_bytes()[:500])
    moved = casefiles.quarantine_datasets([str(good), str(bad), str(tmp_path / "absent.nc")], tmp_path / ".complete.json")
    assert len(moved) == 1 and moved[0].startswith(f"{bad}: unreadable") and moved[0].endswith("it will be built again")
    assert good.exists() and not bad.exists() and len(list((tmp_path / ".corrupt").iterdir())) == 1


def test_job_log_keeps_the_traceback_and_restores_the_streams(tmp_path):
    log = tmp_path / "job.log"
    saved = sys.stdout, sys.stderr
    with pytest.raises(ZeroDivisionError):
        with joblog.job_log(log):
            print("working")
            1 / 0
    assert (sys.stdout, sys.stderr) == saved
    text = log.read_text()
    assert text.startswith("working\n") and "Traceback" in text and "ZeroDivisionError" in text


def test_a_job_log_shows_each_line_as_soon_as_it_is_printed(tmp_path):
    log = tmp_path / "job.log"
    with joblog.job_log(log):
        print("case 1: converged")
        assert log.read_text() == "case 1: converged\n"  # while the job still runs (tail -f)
        print("case 2: ", end="")
        assert log.read_text() == "case 1: converged\n"


def test_an_interrupted_job_says_where_in_its_log_and_one_line_on_the_terminal(tmp_path, capsys):
    """Ctrl-C reaches every job Snakemake runs: each used to print its KeyboardInterrupt
    traceback on the terminal. Now the log says where the job stopped, the terminal gets one
    line, and the job still exits non-zero (130, as a shell reports SIGINT)."""
    log = tmp_path / "job.log"

    def force_at(z):
        raise KeyboardInterrupt

    def solving():  # interrupted inside the package's code (in a callback of it, as numpy's would be)
        decreasing_root(force_at, 0.0, 1.0, 1e-9)

    with pytest.raises(SystemExit) as stopped:
        with joblog.job_log(log):
            print("case 1: converged")
            solving()
    assert stopped.value.code == 130
    text = log.read_text()
    assert text.startswith("case 1: converged\n") and "interrupted (Ctrl-C or SIGINT) in decreasing_root" in text
    assert "Traceback" not in text
    err = capsys.readouterr().err
    assert "Traceback" not in err and err.count("\n") == 1 and str(log) in err


def test_a_rule_script_interrupted_while_it_imports_exits_with_one_line(tmp_path):
    """Ctrl-C can reach a job before its log is open (its imports take a second or more):
    workflow/scripts/this_tree.py, which every rule script imports first, ends it with one
    line and status 130 instead of an import traceback."""
    script = tmp_path / "plot.py"
    script.write_text("import os, signal, time\nimport this_tree\nos.kill(os.getpid(), signal.SIGINT)\ntime.sleep(5)\n")
    scripts = Path(__file__).resolve().parents[1] / "workflow" / "scripts"
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=60,
                         env={**os.environ, "PYTHONPATH": str(scripts)})
    assert run.returncode == 130, run.stderr
    assert run.stderr == "lubecontact job plot.py interrupted (Ctrl-C or SIGINT) while starting\n"


def test_plan_file_is_rewritten_only_when_it_changes(tmp_path):
    path = tmp_path / "plans" / "solve" / "x.json"
    plans.write_plan(path, [{"id": "a", "set": {"k": 1.0}}])
    os.utime(path, ns=(1, 1))
    plans.write_plan(path, [{"id": "a", "set": {"k": 1.0}}])
    assert path.stat().st_mtime_ns == 1  # same plan: untouched, so no rerun
    plans.write_plan(path, [{"id": "a", "set": {"k": 2.0}}])
    assert path.stat().st_mtime_ns > 1 and plans.read_plan(path) == [{"id": "a", "set": {"k": 2.0}}]
