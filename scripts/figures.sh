#!/usr/bin/env bash
# Set up .venv if needed, then regenerate every figure (results/figures/) with Snakemake.
# Extra arguments go to snakemake, e.g. `bash scripts/figures.sh results/figures/fig04.png`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
exec .venv/bin/snakemake --workflow-profile workflow/profiles/default "$@"
