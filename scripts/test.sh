#!/usr/bin/env bash
# Set up .venv if needed, then run the test suite. Extra arguments go to one pytest run as
# they are (serial: bash scripts/test.sh -k reynolds -x).
#
# Without arguments, the whole suite: one worker per core (pytest-xdist, each test file on
# one worker, so a module's fixtures are built once), one BLAS thread each so that the
# workers do not oversubscribe the cores; then the live-SLURM test alone, after the others,
# since its jobs need the cores the workers would be using (it is skipped unless
# LUBECONTACT_CLUSTER_TESTS=1, as .ci/run sets where it can install SLURM).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ "$#" -gt 0 ]; then
    exec .venv/bin/python -m pytest "$@"
fi
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 \
    .venv/bin/python -m pytest -n auto --dist loadfile -m "not cluster"
exec .venv/bin/python -m pytest -m cluster
