"""What a workflow job is to do, in a small JSON file instead of Snakemake params (params
are printed with every job and every dry run; a chunk's case list is long).

The file is rewritten only when its content changes, so its modification time is the
time of the last change of the plan: Snakemake reruns the job then, and only then (the
role the params rerun trigger had).
"""

from __future__ import annotations

import json
import shlex
from pathlib import Path

from lubecontact.io.atomic_write import write_text


def write_plan(path, data) -> str:
    """Write ``data`` as JSON to ``path`` unless the file already holds exactly that."""
    path = Path(path)
    text = json.dumps(data, indent=1, sort_keys=True) + "\n"
    try:
        if path.read_text() == text:
            return str(path)
    except OSError:
        pass
    path.parent.mkdir(parents=True, exist_ok=True)
    write_text(path, text)
    return str(path)


def read_plan(path):
    return json.loads(Path(path).read_text())


def solve_command(case: dict, out: str) -> str:
    """The command line that solves a plan's case ({id, scene, set}) on its own and writes
    it to ``out``, run from the directory the plan's scene path is relative to (the
    repository's root): ``lubecontact solve SCENE --set KEY=VALUE ... --out OUT``, shell-quoted,
    each value as JSON, which the CLI's YAML reading of --set gives back unchanged."""
    overrides = [f"--set={key}={json.dumps(value)}" for key, value in case["set"].items()]
    return shlex.join(["lubecontact", "solve", case["scene"], *overrides, "--out", str(out)])
