"""Write the numbers the docs quote into README.md and results/README.md, so no such number
is typed by hand: the default run's cases, chunks, figures and cluster submissions, from the
workflow's own planning (between ``<!-- planned:NAME -->`` and ``<!-- /planned -->``), a
few cheap solves (51 x 51, seconds in all) between ``<!-- solved:NAME -->`` and
``<!-- /solved -->``, cheap analyses and the code's own constants (the measured sample
surfaces, the size estimator, E*, Hertz pressures, bandwidths, mesh columns) between
``<!-- computed:NAME -->`` and ``<!-- /computed -->``, and with ``--runs`` the blocks of long runs (transient stops, the
accuracy study, their times; scripts/doc_runs.py) between ``<!-- run:NAME -->`` and
``<!-- /run -->``. ``--check`` only says whether both files are current (exit 1 if not):
planned numbers exactly, solved and computed ones within 1 %, and of the long runs the cheap results
(``<!-- measured:NAME -->``, doc_runs.CHECKED) within 2 %; it never reruns a block, and
never checks a time. tests/test_docs.py runs it.

    .venv/bin/python scripts/doc_numbers.py           # rewrite the planned and solved numbers
    .venv/bin/python scripts/doc_numbers.py --runs    # and every run block (minutes: one core, by hand)
    .venv/bin/python scripts/doc_numbers.py --runs --resume   # go on from a killed --runs (bench/out/)
    .venv/bin/python scripts/doc_numbers.py --runs --accuracy-study results/accuracy/study.nc
                                                      # the accuracy table from the workflow's study
    .venv/bin/python scripts/doc_numbers.py --runs --only transient_accuracy \
        --transient-accuracy results/data/transient_accuracy.nc   # one group, from the workflow's table
    .venv/bin/python scripts/doc_numbers.py --runs --only grease   # the grease figure's cases (a minute)
    .venv/bin/python scripts/doc_numbers.py --check   # are they current?
"""

import argparse
import functools
import math
import re
import sys
from pathlib import Path

import yaml

import doc_runs
from lubecontact.model import resources
from lubecontact.model.auto_effects import DEFAULT_TOLERANCE, OPEN_CIRCUIT_RESISTANCE
from lubecontact.model.solve import solve
from lubecontact.model.validity import bandwidth
from lubecontact.numerics.mesh import build_mesh
from lubecontact.physics.electrical.film import simmons_specific_resistance
from lubecontact.physics.electrical.spots import MAX_AREA_FRACTION
from lubecontact.physics.film_estimates import hertz_half_width
from lubecontact.physics.materials import effective_modulus
from lubecontact.scene import load_scene
from lubecontact.surfaces.mccool import composite
from lubecontact.surfaces.measured import scene_roughness
from lubecontact.studies import figure_grids, transient_cases
from lubecontact.studies.sweep import sweep

ROOT = Path(__file__).resolve().parents[1]
FILES = [ROOT / "README.md", ROOT / "results" / "README.md"]
MARK = re.compile(r"<!-- (planned|solved|computed):(\w+) -->(.*?)<!-- /(?:planned|solved|computed) -->", re.S)
RUN = re.compile(r"<!-- run:(\w+) -->\n(.*?)\n<!-- /run -->", re.S)
MEASURED = re.compile(r"<!-- measured:(\w+) -->(.*?)<!-- /measured -->", re.S)
TABLE1 = ROOT / "config" / "scenes" / "table1.yaml"
# solved numbers: name -> overrides of Table 1 (51 x 51, F = 5 N); the contact resistance, ohm
SOLVED = {
    **{f"fig04_10_{tag}": {"operating.speed": 10.0, "roughness.sigma": sigma}
       for tag, sigma in (("s025", 0.25e-6), ("s05", 0.5e-6), ("s1", 1e-6), ("s2", 2e-6))},
    # Fig. 4 with alpha fixed: sigma R_peak = 0.5 um x 100 um
    **{f"alpha_10_{tag}": {"operating.speed": 10.0, "roughness.sigma": sigma, "roughness.asperity_radius": 5e-11 / sigma}
       for tag, sigma in (("s025", 0.25e-6), ("s1", 1e-6), ("s2", 2e-6))},
    **{f"{name}_10": {"operating.speed": 10.0, "roughness.surface": f"../surfaces/{name}.asc"}
       for name in ("ground", "honed")},
    # unequal roughness: all of it on the block (31 x 15, 1 m/s)
    **{f"split_{tag}": {"operating.speed": 1.0, "mesh.nx": 31, "mesh.ny": 15, "roughness.split": split}
       for tag, split in (("05", 0.5), ("1", 1.0))},
}
# solved fractions: name -> overrides of Table 1 (51 x 51 unless said); the fluid load fraction
FRACTION = {
    "fraction_slow": {"operating.speed": 1e-4},
    "fraction_001": {"operating.speed": 0.01},
    "fold_cold": {"operating.speed": 0.0158},
    **{f"{name}_fraction": overrides for name, overrides in SOLVED.items() if name.startswith("split_")},
}
# the whole electrical path (bench/full_path_numbers.py): name -> (overrides of Table 1, 51 x 51; variable)
FULL_PATH = {"effects.macro_constriction": True, "effects.film_conduction": True}
AT_REST = {"table1": {}, "r25": {"geometry.radius": 0.0025}}
FIGURE_TOPS = {"fig04": {"roughness.sigma": 0.25e-6}, "fig06": {"geometry.radius": 0.02},
               "fig08": {"operating.force": 1.0}, "fig10": {"lubricant.viscosity": 0.3}}
PARTS = {
    **{f"rest_{tag}_{part}": ({"operating.speed": 0.0, **extra, **FULL_PATH}, variable)
       for tag, extra in AT_REST.items()
       for part, variable in (("spots", "spot_resistance"), ("cluster", "macro_constriction_resistance"),
                              ("total", "contact_resistance"))},
    **{f"rest_{tag}_paper": ({"operating.speed": 0.0, **extra}, "contact_resistance") for tag, extra in AT_REST.items()},
    **{f"{figure}_top_{model}": ({"operating.speed": 10.0, **extra, **(FULL_PATH if model == "full" else {})},
                                "contact_resistance")
       for figure, extra in FIGURE_TOPS.items() for model in ("full", "paper")},
}
SURFACES = ROOT / "config" / "surfaces"
# the fold from below: a sweep along the figures' speeds (config/figures/fig04.yaml) up to this one
FOLD = 0.0158
PAPER = [f"fig{n:02d}" for n in range(3, 12)]


@functools.cache
def sample_surfaces() -> dict:
    """McCool's parameters of the sample maps and their composite, as ``lubecontact roughness``
    finds them with the default cut-off."""
    ground, _ = scene_roughness(SURFACES / "ground.asc")
    honed, _ = scene_roughness(SURFACES / "honed.asc")
    return {"ground": ground, "honed": honed, "composite": composite(ground.moments, honed.moments)[0]}


def surface_cell(sample: str, column: str) -> str:
    p = sample_surfaces()[sample]
    return {"sigma": shown(p.sigma * 1e6), "eta": shown(p.asperity_density, digits=3),
            "radius": shown(p.asperity_radius * 1e6), "alpha": doc_runs.num(p.alpha),
            "gamma": f"{p.gamma:.2f}"}[column]


def estimate_at(n: int) -> resources.Estimate:
    """The CLI's memory and time estimate of an n x n Table 1 solve."""
    return resources.estimate(load_scene(TABLE1, {"mesh.nx": n, "mesh.ny": n}))


def table1_alpha(overrides: dict) -> str:
    """Nayak's alpha that a scene's sigma, eta, R_peak imply (the bandwidth check)."""
    return doc_runs.num(bandwidth(load_scene(TABLE1, overrides).roughness))


def hertz_peak_mpa(overrides: dict) -> str:
    """Hertz line-contact peak pressure p0 = 2 w'/(pi b) of Table 1, MPa."""
    scene = load_scene(TABLE1, overrides)
    return f"{2 * scene.operating.force / scene.geometry.length / (math.pi * hertz_half_width(scene)) / 1e6:.2f}"


# computed numbers: name -> what computes it (analyses and constants, well under a second each)
COMPUTED = {
    **{f"surface_{sample}_{column}": functools.partial(surface_cell, sample, column)
       for sample in ("ground", "honed", "composite") for column in ("sigma", "eta", "radius", "alpha", "gamma")},
    "surface_cutoff_um": lambda: f"{sample_surfaces()['ground'].moments.cutoff * 1e6:g}",
    "alpha_table1": lambda: table1_alpha({}),
    "alpha_s025": lambda: table1_alpha({"roughness.sigma": 0.25e-6}),
    "alpha_s2": lambda: table1_alpha({"roughness.sigma": 2e-6}),
    "alpha_s002": lambda: table1_alpha({"roughness.sigma": 0.02e-6}),
    "size_base_mb": lambda: f"{resources.BASE_MB:g}",
    "size_kb_per_node": lambda: f"{resources.MB_PER_NODE * 1e3:g}",
    "size_51_mb": lambda: f"{estimate_at(51).memory_mb:.0f}",
    "size_501_mb": lambda: f"{estimate_at(501).memory_mb:.0f}",
    "size_2000_gb": lambda: f"{estimate_at(2000).memory_mb / 1024:.1f}",
    "size_time_exponent": lambda: f"{resources.TIME_EXPONENT:g}",
    "size_201_s": lambda: f"{estimate_at(201).seconds:.2g}",
    "size_announce_s": lambda: f"{resources.ANNOUNCE_SECONDS:g}",
    "auto_tolerance_pct": lambda: f"{100 * DEFAULT_TOLERANCE:g}",
    "auto_open_ohm": lambda: shown(OPEN_CIRCUIT_RESISTANCE),
    "columns_10": lambda: str(build_mesh(load_scene(TABLE1, {"operating.speed": 10.0, "mesh.far_inlet": False})).shape[1]),
    "e_star_gpa": lambda: f"{effective_modulus(load_scene(TABLE1)) / 1e9:.2f}",
    "hertz_mpa": lambda: hertz_peak_mpa({}),
    "hertz_rigid_mpa": lambda: hertz_peak_mpa({"block.youngs_modulus": 1e15}),
    "tunnel_1nm_1ev": lambda: shown(float(simmons_specific_resistance(1e-9, 1.0))),
    "psi_clamp": lambda: f"{MAX_AREA_FRACTION:g}",
}


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
        **{name: None for name in [*SOLVED, *FRACTION, *PARTS, *COMPUTED, "fold_swept"]},  # on demand (solved_number)
        "paper_cases": str(len(paper_cases)),
        "paper_chunks": str(len(paper_chunks)),
        "cases": str(len(all_cases)),
        "chunks": str(len(all_chunks)),
        "figures": str(len(config["figures"])),
        "transient_cases": str(len(transients)),
        "submissions": str(math.ceil((len(all_chunks) + len(transients)) / per_submission)),
    }


def shown(x: float, digits: int = 2) -> str:
    """A number as the docs print it: 3 digits between 0.01 and 1e4, else 2.0e21 style
    (``digits`` significant digits)."""
    if 1e-2 <= x < 1e4:
        return f"{x:.{max(0, 2 - math.floor(math.log10(x)))}f}"
    mantissa, exponent = f"{x:.{digits - 1}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


@functools.cache
def solved(overrides: tuple):
    """Table 1 with ``overrides`` (a sorted tuple of items) solved once, however many numbers quote it."""
    ds = solve(load_scene(TABLE1, dict(overrides)))
    if int(ds["converged"]) != 1:
        raise RuntimeError(f"{dict(overrides)}: the solve did not converge; no number is quoted from it")
    return ds


def solved_number(name: str) -> str:
    if name in COMPUTED:
        return COMPUTED[name]()
    if name == "fold_swept":
        fig04 = figure_grids.read_yaml(ROOT / "config" / "figures" / "fig04.yaml")["speeds"]
        speeds = [u for u in figure_grids.log_speeds(fig04["from"], fig04["to"], fig04["per_decade"]) if u <= FOLD]
        ds = sweep(load_scene(TABLE1), speeds, progress=False).sel(speed=FOLD)
        if int(ds["converged"]) != 1:
            raise RuntimeError(f"{name}: the solve did not converge; no number is quoted from it")
        return f"{float(ds['fluid_load_fraction']):.3g}"
    overrides, variable = PARTS.get(name) or (SOLVED.get(name) or FRACTION[name],
                                              "contact_resistance" if name in SOLVED else "fluid_load_fraction")
    ds = solved(tuple(sorted(overrides.items())))
    if variable == "fluid_load_fraction":
        return f"{float(ds[variable]):.3g}"
    return shown(float(ds[variable]))


def current(text: str, values: dict) -> str:
    def fill(match):
        kind, name = match.group(1), match.group(2)
        if name not in values:
            raise KeyError(f"unknown {kind} number {name!r}; known: {', '.join(values)}")
        if values[name] is None:
            values[name] = solved_number(name)
        return f"<!-- {kind}:{name} -->{values[name]}<!-- /{kind} -->"

    return MARK.sub(fill, text)


def _same(kind: str, old: str, new: str) -> bool:
    """A planned number exactly; a solved or computed one within 1 % (round-off of another BLAS may move
    its last printed digit); a measured one within 2 % (a transient's steps may fall
    differently)."""
    if kind == "planned" or old == new:
        return old == new
    try:
        return math.isclose(float(old), float(new), rel_tol=2e-2 if kind == "measured" else 1e-2)
    except ValueError:
        return False


# the measurements of the last --runs (git-ignored): --resume goes on from them
RECORD = ROOT / "bench" / "out" / "doc_runs.json"
GREASE_RECORD = ROOT / "bench" / "out" / "doc_runs_grease.json"
STUDY = ROOT / "bench" / "out" / "doc_runs_study.nc"


RUN_GROUPS = ("transient", "accuracy", "transient_accuracy", "grease")  # --only: the groups of run blocks


def run_blocks(accuracy_study: Path | None, transient_accuracy: Path | None, resume: bool,
               only: tuple[str, ...] = RUN_GROUPS) -> dict[str, str]:
    """The blocks of the long runs by name (scripts/doc_runs.py) of the groups ``only``, run
    now (with ``resume``, the stops in RECORD and GREASE_RECORD and the study in STUDY are kept)."""
    blocks = doc_runs.transient_blocks(RECORD, resume, progress) if "transient" in only else {}
    if "accuracy" in only:
        if accuracy_study is None and resume and STUDY.is_file():
            accuracy_study = STUDY
        blocks["accuracy"] = doc_runs.accuracy_block(accuracy_study, progress, keep=STUDY)
    if "transient_accuracy" in only:
        blocks["transient_accuracy"] = doc_runs.transient_accuracy_block(transient_accuracy, progress)
    if "grease" in only:
        blocks["grease"] = doc_runs.grease_block(GREASE_RECORD, resume, progress)
    return blocks


def progress(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def with_runs(text: str, blocks: dict[str, str], complete: bool = True) -> str:
    """``text`` with its run blocks rewritten from ``blocks``; a block not in ``blocks`` is
    an error when they are ``complete`` (every group was run), else kept as it is."""
    def fill(match):
        name = match.group(1)
        if name not in blocks:
            if complete:
                raise KeyError(f"unknown run block {name!r}; known: {', '.join(blocks)}")
            return match.group(0)
        return f"<!-- run:{name} -->\n{blocks[name]}\n<!-- /run -->"

    return RUN.sub(fill, text)


def stale_measured(text: str) -> list[str]:
    """The cheap results of the long runs (doc_runs.CHECKED) that a run now does not reproduce."""
    stale = []
    for name, old in MEASURED.findall(text):
        if name in doc_runs.CHECKED:
            new = doc_runs.checked_number(name)
            if not _same("measured", old, new):
                stale.append(f"{name} = {old} (now {new})")
    return stale


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a quoted number is not current")
    parser.add_argument("--runs", action="store_true", help="also rerun the long runs and rewrite their blocks (minutes)")
    parser.add_argument("--resume", action="store_true", help="with --runs: keep the runs of the last --runs "
                        f"({RECORD.relative_to(ROOT)}, {STUDY.relative_to(ROOT)}) and run only what is missing")
    parser.add_argument("--accuracy-study", type=Path, metavar="STUDY_NC",
                        help="with --runs: take the accuracy study from this file (the workflow's "
                             "results/accuracy/study.nc) instead of running it")
    parser.add_argument("--transient-accuracy", type=Path, metavar="TABLE_NC",
                        help="with --runs: take the transient's accuracy ladders from this file (the workflow's "
                             "results/data/transient_accuracy.nc) instead of running them")
    parser.add_argument("--only", nargs="+", choices=RUN_GROUPS, default=list(RUN_GROUPS),
                        help="with --runs: rewrite only these groups of run blocks, keep the others")
    args = parser.parse_args(argv)
    if args.check and args.runs:
        parser.error("--check never reruns the long runs: give --check or --runs")
    if (args.accuracy_study or args.transient_accuracy or args.resume) and not args.runs:
        parser.error("--accuracy-study, --transient-accuracy and --resume go with --runs")
    for given in (args.accuracy_study, args.transient_accuracy):
        if given and not given.is_file():
            parser.error(f"{given}: no such file")
    values = numbers()
    only = tuple(args.only)
    blocks = run_blocks(args.accuracy_study, args.transient_accuracy, args.resume, only) if args.runs else None
    stale = []
    for path in FILES:
        text = path.read_text()
        wanted = current(with_runs(text, blocks, complete=only == RUN_GROUPS) if blocks else text, values)
        if args.check:
            stale += [f"{path.relative_to(ROOT)}: {name} = {old} (now {new})"
                      for (kind, name, old), (_, _, new) in zip(MARK.findall(text), MARK.findall(wanted))
                      if not _same(kind, old, new)]
            stale += [f"{path.relative_to(ROOT)}: {line}" for line in stale_measured(text)]
        elif wanted != text:
            path.write_text(wanted)
    if args.check and stale:
        print("not current (run python scripts/doc_numbers.py):\n" + "\n".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
