"""Command line: ``lubecontact solve|sweep|transient|show``. Exit codes: 0 converged, 2 bad input,
3 not converged (the file is still written, with converged = 0)."""

from __future__ import annotations

import argparse
import sys

EXIT_OK, EXIT_BAD_INPUT, EXIT_NOT_CONVERGED = 0, 2, 3


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="lubecontact", description=__doc__)
    sub = p.add_subparsers(dest="command", required=True)

    def scene_args(sp):
        sp.add_argument("scene", help="scene YAML file (see config/scenes/table1.yaml)")
        sp.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                        help="dotted override, e.g. roughness.sigma=1e-6 (repeatable)")

    solve = sub.add_parser("solve", help="solve one operating point and write a netCDF case file")
    scene_args(solve)
    solve.add_argument("--fields", action="store_true", help="also write pressure, film and deformation fields")
    solve.add_argument("--out", required=True, help="output netCDF file")

    sweep = sub.add_parser("sweep", help="solve the scene over a list of speeds")
    scene_args(sweep)
    sweep.add_argument("--speeds", required=True,
                       help="comma list in m/s (0.001,0.01,0.1) or log range START:STOP:N (1e-4:10:25)")
    sweep.add_argument("--out", required=True, help="output netCDF file")

    transient = sub.add_parser("transient", help="follow the scene's motion: (stop, start, oscillation, table) in time")
    scene_args(transient)
    transient.add_argument("--out", required=True, help="output netCDF file (time series)")

    show = sub.add_parser("show", help="validate a scene and print its canonical form and hash")
    scene_args(show)
    return p


def parse_speeds(text: str) -> list[float]:
    import numpy as np

    try:
        if ":" in text:
            start, stop, n = text.split(":")
            return np.geomspace(float(start), float(stop), int(n)).tolist()
        return [float(v) for v in text.split(",") if v.strip()]
    except ValueError as err:
        raise ValueError(f"--speeds {text!r}: expected a comma list or START:STOP:N ({err})") from None


def _load(args):
    from .scene import load_scene, parse_override

    overrides = dict(parse_override(item) for item in args.overrides)
    return load_scene(args.scene, overrides)


def _summary(ds) -> str:
    lines = [f"effects run: {ds.attrs['effects_run']}"]
    for name in ("contact_resistance", "friction_coefficient", "contact_force", "fluid_force",
                 "min_film_thickness", "iterations", "force_residual", "solve_time"):
        var = ds[name]
        values = var.values.ravel()
        shown = f"{values[0]:.6g}" if values.size == 1 else f"{values.min():.4g} .. {values.max():.4g}"
        lines.append(f"{name:>22s} = {shown} {var.attrs['units']}")
    ok = int(ds["converged"].values.min())
    lines.append(f"{'converged':>22s} = {'yes' if ok else 'NO'}")
    return "\n".join(lines)


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    from .scene import SceneError

    try:
        scene = _load(args)
        speeds = parse_speeds(args.speeds) if args.command == "sweep" else None
    except (SceneError, ValueError) as err:
        print(f"lubecontact: bad input:\n{err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if args.command == "show":
        print(f"# hash: {scene.hash}")
        print(scene.canonical_yaml(), end="")
        return EXIT_OK
    from .output import write_case

    if args.command == "solve":
        from .solver import solve

        ds = solve(scene, fields=args.fields)
    elif args.command == "transient":
        from .unsteady.cli import run_transient

        return run_transient(scene, args.out)
    else:
        from .speed_sweep import sweep

        ds = sweep(scene, speeds)
    write_case(ds, args.out)
    print(_summary(ds))
    print(f"wrote {args.out}")
    if int(ds["converged"].values.min()) != 1:
        print("lubecontact: the solve did NOT converge (converged = 0 in the file)", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
