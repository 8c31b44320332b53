"""A workflow job's log: everything the job prints, and its traceback if it fails."""

from __future__ import annotations

import contextlib
import sys
import traceback


@contextlib.contextmanager
def job_log(path):
    """Send stdout and stderr to ``path`` while the block runs. An exception is written to
    the log with its full traceback before the streams are restored and it propagates (so
    Snakemake marks the job failed and shows the log)."""
    saved = sys.stdout, sys.stderr
    with open(path, "w") as log:
        sys.stdout = sys.stderr = log
        try:
            yield log
        except BaseException:
            traceback.print_exc(file=log)
            raise
        finally:
            log.flush()
            sys.stdout, sys.stderr = saved
