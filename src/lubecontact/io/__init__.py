"""Files: atomic writes, what a case holds and how it is written and checked, job plans
and logs, ``--out`` paths. The lowest layer: it knows nothing of the physics."""
