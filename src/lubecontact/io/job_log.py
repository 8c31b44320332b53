"""A workflow job's log: everything the job prints, and its traceback if it fails."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import traceback
from pathlib import Path

# The exit status of a process stopped by SIGINT (128 + 2), as a shell reports it.
INTERRUPTED_STATUS = 130
PACKAGE = str(Path(__file__).resolve().parents[1])  # src/lubecontact: where an interruption is said to be


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
    if signal.getsignal(signal.SIGINT) not in (signal.SIG_IGN, signal.SIG_DFL):
        # Python's own handler again (a rule script replaces it while it imports, to exit
        # quietly: workflow/scripts/this_tree.py), so that an interruption is caught below
        signal.signal(signal.SIGINT, signal.default_int_handler)
    # line-buffered: each line is in the file as soon as it is printed, so that a long job's
    # progress (a chunk's "case ...: converged" lines) can be followed with tail -f; block
    # buffering kept a chunk of 201 x 201 cases silent for minutes (thirty-fifth session)
    with open(path, "w", buffering=1) as log:
        sys.stdout = sys.stderr = log
        try:
            yield log
        except KeyboardInterrupt:
            frames = traceback.extract_tb(sys.exc_info()[2])
            # the innermost frame of this package's code or of a rule script, not numpy's
            ours = [f for f in frames if f.filename != __file__ and (f.filename.startswith(PACKAGE)
                                                                     or f"{os.sep}scripts{os.sep}" in f.filename)]
            where = (ours or frames)[-1]
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
