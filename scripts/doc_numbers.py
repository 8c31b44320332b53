"""Write the numbers the docs quote about the default run (cases, chunks, figures, cluster
submissions) into README.md and results/README.md, from the workflow's own planning, so no
such number is typed by hand. Each stands between markers ``<!-- planned:NAME -->`` and
``<!-- /planned -->``. ``--check`` only says whether both files are current (exit 1 if
not); tests/test_docs.py runs it.

    .venv/bin/python scripts/doc_numbers.py           # rewrite the numbers
    .venv/bin/python scripts/doc_numbers.py --check   # are they current?
"""

import argparse
import math
import re
import sys
from pathlib import Path

import yaml

from lubecontact.studies import figure_grids, transient_cases

ROOT = Path(__file__).resolve().parents[1]
FILES = [ROOT / "README.md", ROOT / "results" / "README.md"]
MARK = re.compile(r"<!-- planned:(\w+) -->(.*?)<!-- /planned -->", re.S)
PAPER = [f"fig{n:02d}" for n in range(3, 12)]


def numbers() -> dict[str, str]:
    """Each quoted number by name, planned from config/config.yaml as the Snakefile plans it."""
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    figure_dir = ROOT / config["figure_dir"]

    def plan(figures):
        specs = {f: figure_grids.figure_spec(f, figure_dir, config["figures"]) for f in figures}
        grids = figure_grids.expand_all(specs, root=ROOT)
        cases = {case for grid in grids.values() for case in grid.unique_cases()}
        return cases, figure_grids.plan_chunks(grids.values(), None)

    paper_cases, paper_chunks = plan(PAPER)
    all_cases, all_chunks = plan(list(config["figures"]))
    spec = transient_cases.study_spec(ROOT / "config" / "transient.yaml", None)
    transients = transient_cases.case_overrides(spec, transient_cases.figure_cases(spec))
    profile = yaml.safe_load((ROOT / "workflow" / "profiles" / "slurm" / "config.yaml").read_text())
    per_submission = profile["group-components"]["solve"]
    return {
        "paper_cases": str(len(paper_cases)),
        "paper_chunks": str(len(paper_chunks)),
        "cases": str(len(all_cases)),
        "chunks": str(len(all_chunks)),
        "figures": str(len(config["figures"])),
        "transient_cases": str(len(transients)),
        "submissions": str(math.ceil((len(all_chunks) + len(transients)) / per_submission)),
    }


def current(text: str, values: dict[str, str]) -> str:
    def fill(match):
        if match.group(1) not in values:
            raise KeyError(f"unknown planned number {match.group(1)!r}; known: {', '.join(values)}")
        return f"<!-- planned:{match.group(1)} -->{values[match.group(1)]}<!-- /planned -->"

    return MARK.sub(fill, text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a quoted number is not current")
    args = parser.parse_args(argv)
    values = numbers()
    stale = []
    for path in FILES:
        text = path.read_text()
        wanted = current(text, values)
        if wanted != text:
            stale.append(str(path.relative_to(ROOT)))
            if not args.check:
                path.write_text(wanted)
    if args.check and stale:
        print(f"not current: {', '.join(stale)}: run python scripts/doc_numbers.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
