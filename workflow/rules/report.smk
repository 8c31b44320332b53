# What the HTML report's landing page (workflow/report/workflow.rst) says about this run:
# lubecontact version, git commit of the tree, results directory and, for each figure, its
# base scene and what it sweeps; the transient, surface and accuracy figures. Included last:
# it reads what the other rule files define. Snakemake renders that page with the config only, so the
# facts go into config["_run"] (a key no config file may set: the schema forbids it).

import os
import subprocess


def _git_state(root):
    def git(*args):
        # GIT_OPTIONAL_LOCKS=0: `git status` at every parse must not take .git/index.lock,
        # which a user's own git command running at that moment would fail on
        return subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True, timeout=20,
                              env={**os.environ, "GIT_OPTIONAL_LOCKS": "0"})

    try:
        head = git("rev-parse", "--short=12", "HEAD")
        if head.returncode != 0:
            return "unknown (not a git checkout)"
        dirty = git("status", "--porcelain", "--untracked-files=no").stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown (git not available)"
    return head.stdout.strip() + (" with uncommitted changes" if dirty else "")


def _figure_facts(figure):
    g = GRIDS[figure]
    sweeps = "; ".join(
        f"{', '.join(d.keys)} = {', '.join(' x '.join(lcgrid.value_text(v) for v in vals) for vals in d.values)}"
        for d in g.dims[:-1]
    )
    speeds = g.dims[-1].values
    return {
        "figure": figure,
        "title": SPECS[figure]["title"],
        "scene": SPECS[figure]["scene"] + (f" with {SPECS[figure]['set']}" if SPECS[figure].get("set") else ""),
        "scene_hash": g.base.hash,
        "sweep": sweeps or "nothing",
        "speeds": f"{len(speeds)} speeds, {min(speeds)[0]:g} to {max(speeds)[0]:g} m/s",
    }


def _transient_facts(name):
    return {
        "figure": f"transient_{name}",
        "title": TRANSIENT["figures"][name]["title"],
        "cases": len(TRANSIENT_CASES[name]),
        "scene": TRANSIENT["base"],
    }


config["_run"] = {
    "version": lubecontact.__version__,
    "git": _git_state(workflow.basedir),
    "results": RESULTS,
    "figures": [_figure_facts(f) for f in FIGURES],
    "transient": [_transient_facts(f.removeprefix("transient_")) for f in TRANSIENT_FIGURES],
    "surfaces": SURFACE_FILES,
    "hysteresis": [{"figure": f"hysteresis_{name}", "title": SPECS[name]["title"], "curves": len(cases)}
                   for name, cases in HYSTERESIS.items()],
    "accuracy": ", ".join(str(n) for n in ACCURACY["meshes"]) + " nodes a side",
}
