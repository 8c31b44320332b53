"""A workflow job's log: everything the job prints, and its traceback if it fails."""

from __future__ import annotations

import contextlib
import sys
import traceback

# The exit status of a process stopped by SIGINT (128 + 2), as a shell reports it.
INTERRUPTED_STATUS = 130


@contextlib.contextmanager
def job_log(path):
    """Send stdout and stderr to ``path`` while the block runs. An exception is written to
    the log with its full traceback before the streams are restored and it propagates (so
    Snakemake marks the job failed and shows the log).

    An interruption (Ctrl-C: the terminal sends SIGINT to Snakemake and to every job it
    runs) is not a failure of the job's code: the log says where it stopped, and the
    terminal gets one line instead of each job's traceback; the job exits with status 130,
    so Snakemake still sees it fail and removes its unfinished outputs (complete case files
    are written atomically and kept by update())."""
    saved = sys.stdout, sys.stderr
    interrupted = ""
    # line-buffered: each line is in the file as soon as it is printed, so that a long job's
    # progress (a chunk's "case ...: converged" lines) can be followed with tail -f; block
    # buffering kept a chunk of 201 x 201 cases silent for minutes (thirty-fifth session)
    with open(path, "w", buffering=1) as log:
        sys.stdout = sys.stderr = log
        try:
            yield log
        except KeyboardInterrupt:
            where = traceback.extract_tb(sys.exc_info()[2])[-1]
            interrupted = f"interrupted (Ctrl-C or SIGINT) in {where.name}, {where.filename}:{where.lineno}"
            print(f"job {interrupted}; what it wrote before is kept", file=log)
        except BaseException:
            traceback.print_exc(file=log)
            raise
        finally:
            log.flush()
            sys.stdout, sys.stderr = saved
    if interrupted:
        print(f"lubecontact job {interrupted}; its log: {path}", file=sys.stderr)
        raise SystemExit(INTERRUPTED_STATUS)
