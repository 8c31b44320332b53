"""The workflow on a live one-node SLURM cluster (tests/cluster/run_slurm.sh).

The script installs Debian's slurm-wlm and munge if missing, starts munged, slurmctld and
slurmd, runs config/test.yaml through workflow/profiles/slurm and checks, against a local
run of the same workflow (the independent truth here):
  - every figure and dataset comes out, netCDF values equal to the local run's, and a
    second run has nothing to do;
  - the solve jobs are bundled (fewer submissions than solve jobs, as many as the dry run
    plans) and collect/plot are never submitted (local rules);
  - a solve job cancelled mid-run (scancel) fails the run, leaves only complete cases, and
    the rerun resubmits only what is missing;
  - a crash (SIGKILL to Snakemake and every job process, no clean-up anywhere) leaves only
    complete case files (atomic writes), and the rerun keeps them byte for byte (both faults
    on the study's solve jobs only).
It takes about seven minutes on two cores (416 s in CI on 2026-11-30) and needs root, so it
runs only when asked: LUBECONTACT_CLUSTER_TESTS=1 (.ci/run sets it on machines with root and
apt-get).
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

SCRIPT = Path(__file__).parent / "cluster" / "run_slurm.sh"
TIMEOUT = 30 * 60  # s; a normal run takes about 7 min


def _skip_reason() -> str | None:
    if os.environ.get("LUBECONTACT_CLUSTER_TESTS") != "1":
        return "live SLURM test: set LUBECONTACT_CLUSTER_TESTS=1 to run it (root, apt-get, ~7 min)"
    if os.geteuid() != 0:
        return "live SLURM test needs root: it installs slurm-wlm/munge and runs their daemons"
    if shutil.which("apt-get") is None:
        return "live SLURM test needs apt-get to install slurm-wlm and munge (Debian/Ubuntu)"
    return None


pytestmark = [
    pytest.mark.cluster,
    pytest.mark.slow,
    pytest.mark.skipif(_skip_reason() is not None, reason=_skip_reason() or ""),
]


def test_workflow_on_live_slurm_cluster(capsys):
    proc = subprocess.Popen(["bash", str(SCRIPT)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        output, _ = proc.communicate(timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.terminate()  # SIGTERM: the script's trap cancels the jobs and stops the daemons
        output, _ = proc.communicate(timeout=120)
        pytest.fail(f"run_slurm.sh did not finish in {TIMEOUT} s:\n{output[-8000:]}")
    assert proc.returncode == 0, f"run_slurm.sh failed (exit {proc.returncode}):\n{output[-8000:]}"
    assert "run_slurm: OK:" in output, output[-8000:]
    with capsys.disabled():  # the CI log shows the run's wall times and submission counts
        print("\n" + "\n".join(line for line in output.splitlines() if line.startswith("run_slurm:")))
