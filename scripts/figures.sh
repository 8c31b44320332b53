#!/usr/bin/env bash
# Set up .venv if needed, then regenerate every figure (results/figures/) with Snakemake.
# Extra arguments go to snakemake, e.g. `bash scripts/figures.sh results/figures/fig04.png`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# On a terminal, progress bars (the rich logger); redirected to a file or a pipe, a line per
# started and finished job (snakemake's own logger), which a bar cannot give.
logger=()
if [ -t 1 ]; then
    logger=(--logger rich)
fi
exec .venv/bin/snakemake --workflow-profile workflow/profiles/default "${logger[@]}" "$@"
