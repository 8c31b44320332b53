"""Imported first by every rule script: this tree's src/ goes first on sys.path, so a job runs
the very library files the workflow declares as its inputs (workflow/rules/common.smk), not
a lubecontact installed elsewhere. Snakemake puts this folder on a script's path."""

import sys
from pathlib import Path

SOURCE = str(Path(__file__).resolve().parents[2] / "src")
if SOURCE not in sys.path:
    sys.path.insert(0, SOURCE)
