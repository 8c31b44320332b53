# Snakemake's own cost while the jobs run. With a job rate limit (max-jobs-per-timespan;
# Snakemake 9 always has one, by default 100 jobs per 1 s) the scheduler re-examines its ready
# jobs one timespan after each pass, stating every input file of every ready job, and every
# finished job starts one more such cycle, so the passes per second grow with the jobs done.
# At the default the figure build's Snakemake process took a large share of the 2 cores the
# jobs needed (bench/EXPERIMENTS.md, forty-ninth session); the profile for this machine sets
# a timespan of a minute (workflow/profiles/default/config.yaml). Each cycle waits in a
# threading.Timer, and Python waits for those at exit: the run would end up to a timespan
# after its last job. They are cancelled once the run is over.

import threading


def cancel_scheduler_timers():
    """Cancel the scheduler's pending re-examinations (threading.Timer threads): the run is
    over, and its process then exits at once instead of a timespan later."""
    for thread in threading.enumerate():
        if isinstance(thread, threading.Timer):
            thread.cancel()


onsuccess:
    cancel_scheduler_timers()


onerror:
    cancel_scheduler_timers()
