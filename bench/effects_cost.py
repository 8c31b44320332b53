"""Cost of each effect, and what ``effects: auto`` saves (issue "Simulate only the effects a
scene calls for").

1. Cost per effect: the Table 1 scene solved with all effects on and with each effect off
   (one at a time) in the three regimes (boundary 1e-3 m/s, mixed 0.1 m/s, full film
   10 m/s) on 51 x 51 and 201 x 201 meshes (``--quick``: 51 and 101); solve time (best of
   ``--repeat``, model assembly included) and the change of resistance and friction that
   the switch causes.
2. ``effects: auto`` on the Fig. 4 grid (config/figures/fig04.yaml: sigma = 0.25-2 um x
   26 speeds 1e-4-10 m/s) on a 31 x 21 mesh: auto against all effects, the largest
   deviations, what was dropped where, and the time saved.

Writes its section of bench/out/effects_cost.md (between the markers below; the rest of the
file is kept; --out for another file) and prints it. Run from the repository root:

    .venv/bin/python bench/effects_cost.py            # ~5-10 min on one idle core
    .venv/bin/python bench/effects_cost.py --quick    # ~2 min
"""

from __future__ import annotations

import argparse
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

import lubecontact as lc
from lubecontact.model.auto_effects import DEFAULT_TOLERANCE, EFFECTS, OPEN_CIRCUIT_RESISTANCE
from lubecontact.model.model import SolveError
from lubecontact.studies.figure_grids import expand, figure_spec

ROOT = Path(__file__).resolve().parents[1]
TABLE1 = ROOT / "config/scenes/table1.yaml"
REGIMES = {"boundary": 1e-3, "mixed": 0.1, "full film": 10.0}
BEGIN, END = "<!-- effects_cost: begin -->", "<!-- effects_cost: end -->"


def timed_solve(scene, repeat: int):
    """(Dataset of the last run, best solve_time in s) or (None, reason) if there is no solution."""
    best, ds = math.inf, None
    for _ in range(repeat):
        try:
            ds = lc.solve(scene)
        except SolveError as err:
            return None, f"no solution ({str(err).split('(')[0].strip()})"
        best = min(best, float(ds["solve_time"]))
    return ds, best


def relative(a: float, b: float) -> float:
    """|a/b - 1|, 0 when both are open circuits (astronomical)."""
    if a >= OPEN_CIRCUIT_RESISTANCE and b >= OPEN_CIRCUIT_RESISTANCE:
        return 0.0
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.inf
    return abs(a / b - 1.0)


def cost_table(sizes, repeat_small: int) -> list[str]:
    lines = ["## Cost per effect", "",
             "Table 1 scene, one effect off at a time. Time: best solve time (s; model assembly and, for the",
             "rough contact, its table included). dR, df: relative change of contact resistance and friction",
             "coefficient against all effects on (what switching the effect off costs in accuracy).",
             "Alleviation changes no mechanics (the same iterations run with it off), so its row shows the",
             "timing noise of the machine; an effect switched off also changes the solution, hence the",
             "iterations: a row above 100 % is a harder (or noisier) solve, not a costlier effect.", ""]
    for n in sizes:
        repeat = repeat_small if n <= 101 else 1
        lines += [f"### {n} x {n} mesh", "",
                  "| effect off | " + " | ".join(f"{name} ({speed:g} m/s): time, dR, df" for name, speed in REGIMES.items()) + " |",
                  "|---|" + "---|" * len(REGIMES)]
        reference = {}
        rows = {}
        for regime, speed in REGIMES.items():
            base = lc.load_scene(TABLE1, {"mesh.nx": n, "mesh.ny": n, "operating.speed": speed})
            for effect in ("none", *EFFECTS):
                scene = base if effect == "none" else base.replace({f"effects.{effect}": False})
                ds, t = timed_solve(scene, repeat)
                if ds is None:
                    rows.setdefault(effect, []).append(t)
                    continue
                note = "" if int(ds["converged"]) == 1 else " (not converged)"
                if effect == "none":
                    reference[regime] = ds
                    rows.setdefault(effect, []).append(f"**{t:.3g} s**{note}")
                else:
                    ref = reference[regime]
                    dr = relative(float(ds["contact_resistance"]), float(ref["contact_resistance"]))
                    df = relative(float(ds["friction_coefficient"]), float(ref["friction_coefficient"]))
                    share = t / float(ref["solve_time"]) if float(ref["solve_time"]) > 0 else math.nan
                    rows.setdefault(effect, []).append(f"{t:.3g} s ({share:.0%}), {dr:.2g}, {df:.2g}{note}")
                print(f"{n}x{n} {regime:9s} {effect:20s} {rows[effect][-1]}", flush=True)
        for effect, cells in rows.items():
            lines.append(f"| {'(all on)' if effect == 'none' else effect} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines


def validation(nx: int, ny: int, tolerance: float) -> list[str]:
    spec = figure_spec("fig04", ROOT / "config/figures", {"fig04": {"set": {"mesh.nx": nx, "mesh.ny": ny}}})
    grid = expand("fig04", spec, root=ROOT)
    time_full = time_auto = 0.0
    worst_r = worst_f = 0.0
    where_r = where_f = ""
    dropped_at: dict[str, list[str]] = {}
    failures = []
    n = 0
    for case in grid.cases.flat:
        full = lc.load_scene(ROOT / case.scene, case.set)
        auto = full.replace({"effects": "auto"})
        a = lc.solve(full)
        b = lc.solve(auto)
        time_full += float(a["solve_time"])
        time_auto += float(b["solve_time"])
        n += 1
        label = f"sigma = {full.roughness.sigma * 1e6:g} um, U = {full.operating.speed:.3g} m/s"
        dr = relative(float(b["contact_resistance"]), float(a["contact_resistance"]))
        df = relative(float(b["friction_coefficient"]), float(a["friction_coefficient"]))
        if dr > worst_r:
            worst_r, where_r = dr, label
        if df > worst_f:
            worst_f, where_f = df, label
        if dr > tolerance or df > tolerance or int(b["converged"]) != 1:
            failures.append(f"{label}: dR = {dr:.3g}, df = {df:.3g}, converged = {int(b['converged'])}")
        gone = sorted(set(a.attrs["effects_run"].split(",")) - set(b.attrs["effects_run"].split(",")))
        if gone:
            dropped_at.setdefault(", ".join(gone), []).append(label)
    lines = ["## `effects: auto` on the Fig. 4 grid", "",
             f"config/figures/fig04.yaml ({n} points: sigma = 0.25, 0.5, 1, 2 um x 26 speeds 1e-4-10 m/s), "
             f"{nx} x {ny} mesh, tolerance {tolerance:.0%}.", "",
             f"- largest resistance deviation: {worst_r:.3g} ({where_r or 'none'}; both open circuits count as equal)",
             f"- largest friction deviation: {worst_f:.3g} ({where_f or 'none'})",
             f"- points outside the tolerance or not converged: {len(failures)}",
             f"- solve time, all effects: {time_full:.1f} s; auto (decision included): {time_auto:.1f} s "
             f"(saved {1 - time_auto / time_full:.0%})", ""]
    lines += [f"  - {f}" for f in failures]
    lines += ["| dropped by auto | points |", "|---|---|"]
    lines += [f"| {k} | {len(v)}: {'; '.join(v)} |" for k, v in dropped_at.items()] or ["| (nothing) | |"]
    lines.append("")
    return lines


def write_section(path: Path, lines: list[str]) -> None:
    section = "\n".join([BEGIN, *lines, END]) + "\n"
    text = path.read_text() if path.exists() else "# Effects: cost and automatic selection\n\n"
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        text = head + section + rest.split(END, 1)[1].lstrip("\n")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    path.write_text(text)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="51 and 101 nodes a side instead of 51 and 201")
    p.add_argument("--repeat", type=int, default=2, help="runs per solve on meshes up to 101 (best is kept)")
    p.add_argument("--no-validation", action="store_true", help="skip the Fig. 4 auto-vs-full comparison")
    p.add_argument("--out", default=str(ROOT / "bench/out/effects_cost.md"))
    args = p.parse_args(argv)
    sizes = (51, 101) if args.quick else (51, 201)
    start = time.perf_counter()
    lc.solve(lc.load_scene(TABLE1, {"mesh.nx": 21, "mesh.ny": 11}))  # imports first
    lines = [f"Measured {time.strftime('%Y-%m-%d')} on {platform.node()} ({platform.processor() or platform.machine()}, "
             f"Python {sys.version.split()[0]}, numpy {np.__version__}), lubecontact {lc.__version__}; "
             f"`python bench/effects_cost.py{' --quick' if args.quick else ''}`.", ""]
    lines += cost_table(sizes, args.repeat)
    if not args.no_validation:
        lines += validation(31, 21, DEFAULT_TOLERANCE)
    lines.append(f"Total bench time {time.perf_counter() - start:.0f} s.")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    write_section(Path(args.out), lines)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
