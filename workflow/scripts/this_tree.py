"""Imported first by every rule script: this tree's src/ goes first on sys.path, so a job runs
the very library files the workflow declares as its inputs (workflow/rules/common.smk), not
a lubecontact installed elsewhere. Snakemake puts this folder on a script's path.

Also: Ctrl-C (SIGINT to Snakemake and every job) while the script is still importing
(numpy, xarray: a second or more) ends the job with one line and exit status 130, not an
import traceback on the terminal; from the job's log on, lubecontact.io.job_log says where the
job stopped."""

import signal
import sys
from pathlib import Path

SOURCE = str(Path(__file__).resolve().parents[2] / "src")
if SOURCE not in sys.path:
    sys.path.insert(0, SOURCE)


def interrupted_while_starting(signum, frame):
    print(f"lubecontact job {Path(sys.argv[0]).name} interrupted (Ctrl-C or SIGINT) while starting", file=sys.stderr)
    raise SystemExit(128 + signum)


if signal.getsignal(signal.SIGINT) is signal.default_int_handler:  # not where SIGINT is ignored
    signal.signal(signal.SIGINT, interrupted_while_starting)
