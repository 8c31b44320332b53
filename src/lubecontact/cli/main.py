"""Command line: ``lubecontact solve|sweep|transient|show|roughness``. Exit codes: 0 converged; 2 bad input
(scene, option, --out path, a solve too big for this machine: nothing is solved or written);
3 no converged result (not converged: the file is still written, with converged = 0; or
the file could not be written); 130 interrupted (nothing written to --out; a transient's
series so far goes to NAME.interrupted.nc beside it); 1 internal error (a bug:
the traceback is saved to a file named in the message)."""

from __future__ import annotations

import argparse
import signal
import sys

from lubecontact.cli.exit_codes import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_NOT_CONVERGED, EXIT_OK

# The commands' modules are imported where a command runs, not here: `lubecontact --help`
# and `show` then start without scipy and xarray (0.4-0.6 s), and `solve` without xarray
# (tests/test_startup.py).
MAX_SPEEDS = 10_000  # points of one sweep; each is a solve of its own
REPORT_TO = "the lubecontact maintainers (README.md, 'Reporting a bug')"


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
    solve.add_argument("--out", required=True, help="output netCDF file (new path or regular file; links are followed)")
    solve.add_argument("--force-size", action="store_true", help="solve even if the memory estimate exceeds this machine's")

    sweep = sub.add_parser("sweep", help="solve the scene over a list of speeds")
    scene_args(sweep)
    sweep.add_argument("--speeds", required=True,
                       help="comma list in m/s (0.001,0.01,0.1) or log range START:STOP:N (1e-4:10:25)")
    sweep.add_argument("--out", required=True, help="output netCDF file (new path or regular file; links are followed)")
    sweep.add_argument("--direction", choices=["up", "down", "both"], default="up",
                       help="order of the continuation: up (default) from the slowest speed, down from the fastest, "
                            "both: the two along a direction dimension, where a contact with two steady states "
                            "(lift-off and touch-down) differs (docs/physics.md section 23)")
    sweep.add_argument("--force-size", action="store_true", help="solve even if the memory estimate exceeds this machine's")

    transient = sub.add_parser("transient", help="follow the scene's motion: (stop, start, oscillation, table) in time")
    scene_args(transient)
    transient.add_argument("--out", required=True, help="output netCDF file (time series)")
    transient.add_argument("--force-size", action="store_true", help="run even if the memory estimate exceeds this machine's")

    show = sub.add_parser("show", help="validate a scene and print its canonical form and hash")
    scene_args(show)

    rough = sub.add_parser("roughness", help="McCool roughness parameters (sigma, eta, R_peak, alpha) of measured surfaces")
    rough.add_argument("surfaces", nargs="+", metavar="SURFACE",
                       help="instrument file (SurfaceTopography formats) or raw matrix (.txt/.npy with --size, --unit); "
                            "two files: also their composite")
    rough.add_argument("--size", nargs="+", type=float, metavar="L", help="raw matrix: LX [LY] in --unit")
    rough.add_argument("--unit", choices=["m", "mm", "um", "nm"], help="raw matrix: unit of --size and of the heights")
    rough.add_argument("--cutoff", type=float, metavar="LAMBDA_C",
                       help="short-wavelength cut-off of m2, m4 in m (default: 4 sampling intervals)")
    rough.add_argument("--periodic", action="store_true", help="raw matrix: the map wraps around (no window)")
    rough.add_argument("--out", help="write a roughness: section (YAML) a scene can include")
    return p


def parse_speeds(text: str) -> list[float]:
    """Speeds (m/s) from a comma list or a log range START:STOP:N; ValueError says what is allowed."""
    import math

    import numpy as np

    from lubecontact.studies.sweep import repeated_speeds

    allowed = (f"allowed: a comma list of finite speeds >= 0 m/s (0.001,0.01,0.1) or START:STOP:N with 0 < START, "
               f"STOP finite and 1 <= N <= {MAX_SPEEDS} (1e-4:10:25)")
    shown = text if len(text) <= 80 else f"{text[:40]}...{text[-20:]} ({len(text)} characters)"
    try:
        if ":" in text:
            start, stop, n = (float(v) for v in text.split(":"))
            if not (math.isfinite(start) and math.isfinite(stop) and start > 0 and stop > 0 and 1 <= n <= MAX_SPEEDS
                    and n.is_integer()):
                raise ValueError("out of range")
            if start == stop and n > 1:
                raise ValueError("START = STOP gives the same speed N times")
            return np.geomspace(start, stop, int(n)).tolist()
        if text.count(",") >= MAX_SPEEDS:
            raise ValueError(f"more than {MAX_SPEEDS} speeds")
        speeds = [float(v) for v in text.split(",") if v.strip()]
        if not speeds or not all(math.isfinite(v) and v >= 0 for v in speeds):
            raise ValueError("empty, not finite or negative")
        twice = repeated_speeds(speeds)
        if twice:
            raise ValueError(f"{', '.join(f'{v:g}' for v in twice)} listed more than once (each speed once)")
        return speeds
    except ValueError as err:
        raise ValueError(f"--speeds {shown!r}: {err}; {allowed}") from None


def _load(args):
    from lubecontact.scene.scene import load_scene, parse_override

    overrides = dict(parse_override(item) for item in args.overrides)
    return load_scene(args.scene, overrides)


_JUDGED = ("converged", "valid", "open_circuit")  # read by _converged and _findings, not shown as values
_SHOWN = ("contact_resistance", "spot_resistance", "macro_constriction_resistance", "film_resistance",
          "friction_coefficient", "contact_force", "fluid_force",
          "min_film_thickness", "iterations", "force_residual", "solve_time")


def _summary(effects_run: str, values) -> str:
    """What the terminal shows of a case or a sweep; ``values[name]`` is an array (one value
    a point) of each name in _SHOWN and of ``converged``."""
    import numpy as np

    from lubecontact.io.case_schema import SCALARS

    lines = [f"effects run: {effects_run}"]
    for name in _SHOWN:
        flat = np.asarray(values[name]).ravel()
        shown = f"{flat[0]:.6g}" if flat.size == 1 else f"{flat.min():.4g} .. {flat.max():.4g}"
        lines.append(f"{name:>22s} = {shown} {SCALARS[name][0]}")
    lines.append(f"{'converged':>22s} = {'yes' if _converged(values) else 'NO'}")
    return "\n".join(lines)


def _findings(values, speeds, validity_notes: str, open_resistance: float) -> list[str]:
    """What an engineer must know of the numbers above, in words: whether each point stays on
    its sub-models' ground (one line per flag raised), the open circuits, a negative film."""
    import numpy as np

    def at(mask) -> str:
        picked = [f"{u:g}" for u in np.asarray(speeds)[mask]]
        return f"{', '.join(picked[:8])}{' ...' if len(picked) > 8 else ''} m/s"

    valid = np.asarray(values["valid"]).ravel() == 1
    lines = [f"{'valid':>22s} = " + ("yes (every sub-model within its range)" if valid.all() else
                                     f"NO at {int((~valid).sum())} of {valid.size} point(s): left a sub-model's ground")]
    lines += [f"  validity {line}" for line in validity_notes.splitlines()]
    resistance = np.asarray(values["contact_resistance"]).ravel()
    open_ = np.asarray(values["open_circuit"]).ravel() == 1
    if open_.any():
        lines.append(f"  open circuit at {at(open_)}: contact_resistance up to {resistance[open_].max():.4g} ohm > "
                     f"interface.open_resistance = {open_resistance:g} ohm")
    film = np.asarray(values["min_film_thickness"]).ravel()
    if (film < 0).any():
        lines.append(f"  min_film_thickness < 0 at {at(film < 0)}: the mean planes of the rough surfaces "
                     f"interpenetrate (asperities carry load); it is a separation, not a gap")
    return lines


def _converged(values) -> bool:
    import numpy as np

    return int(np.asarray(values["converged"]).min()) == 1


class _BadInput(Exception):
    """An expected refusal before solving: exit 2 with the message."""


def _checked(args, scene, points: int):
    """The resolved --out path, after the path and size checks (nothing solved yet)."""
    from lubecontact.io.output_path import OutputPathError, check_output_path
    from lubecontact.model import resources

    try:
        out = check_output_path(args.out, inputs=[args.scene, *scene.input_files()])
    except OutputPathError as err:
        raise _BadInput(str(err)) from None
    est = resources.estimate(scene, points)
    refusal = resources.too_big(est)
    if refusal and not args.force_size:
        raise _BadInput(refusal)
    if est.seconds > resources.ANNOUNCE_SECONDS or refusal:
        print(f"lubecontact: {est.describe()} (estimate)", file=sys.stderr)
    return out, est


def _interrupt(signum, frame):
    """SIGTERM (a cluster's time limit, ``kill``) as Ctrl-C: a transient keeps what it computed."""
    raise KeyboardInterrupt


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    previous = signal.signal(signal.SIGTERM, _interrupt)
    try:
        return _run(args)
    except _BadInput as err:
        print(f"lubecontact: bad input: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("lubecontact: interrupted; nothing was written", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as err:  # a bug: one line here, the traceback in a file
        import tempfile
        import traceback

        fd, path = tempfile.mkstemp(prefix="lubecontact-crash-", suffix=".txt")
        with open(fd, "w") as fh:
            fh.write(f"lubecontact {' '.join(sys.argv[1:] if argv is None else argv)}\n")
            traceback.print_exc(file=fh)
        print(f"lubecontact: internal error ({type(err).__name__}: {err}); this is a bug, please report it "
              f"to {REPORT_TO} with the traceback saved in {path}", file=sys.stderr)
        return EXIT_INTERNAL
    finally:
        signal.signal(signal.SIGTERM, previous)


def _run(args) -> int:
    if args.command == "roughness":
        from lubecontact.cli.roughness import run

        return run(args)
    from lubecontact.scene.scene import SceneError

    try:
        scene = _load(args)
        speeds = parse_speeds(args.speeds) if args.command == "sweep" else None
    except (SceneError, ValueError) as err:
        print(f"lubecontact: bad input:\n{err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    from lubecontact.model.validity import scene_warnings

    for warning in scene_warnings(scene):
        print(f"lubecontact: warning: {warning}", file=sys.stderr)
    if args.command in ("solve", "sweep") and scene.motion.kind != "steady":
        print(f"lubecontact: warning: motion.kind = {scene.motion.kind} is a motion in time, which "
              f"`lubecontact transient` follows; `{args.command}` solves the steady point at operating.speed "
              "and reads no motion.* key", file=sys.stderr)
    if args.command == "show":
        if scene.motion.kind != "steady":  # what `lubecontact transient` would refuse of this scene
            from lubecontact.unsteady.motion import motion_problems

            for problem in motion_problems(scene):
                print(f"lubecontact: warning: `lubecontact transient` refuses this scene: {problem}", file=sys.stderr)
        print(f"# hash: {scene.hash}")
        print(scene.canonical_yaml(), end="")
        return EXIT_OK
    from lubecontact.model.resources import elapsed_bar

    ways = 2 if getattr(args, "direction", "up") == "both" else 1  # a sweep both ways solves each speed twice
    out, est = _checked(args, scene, 1 if speeds is None else ways * len(speeds))
    if args.command == "solve":  # no xarray: the case is written with netCDF4 (case_result)
        from lubecontact.model.model import SolveError
        from lubecontact.model.solve import solve_case

        try:
            with elapsed_bar(est):
                result, _ = solve_case(scene, fields=args.fields)
        except SolveError as err:  # every solver raised before it had a state: nothing to write
            print(f"lubecontact: the solve did NOT converge and left no state to write ({err}); nothing was "
                  f"written", file=sys.stderr)
            return EXIT_NOT_CONVERGED
        write, effects_run, values = result.write, result.attrs["effects_run"], result.scalars
        why = result.attrs["notes"]  # a point that did not converge says why (the file has it too)
        more_lines = [f"{'mesh':>22s}: {result.attrs['mesh']}"]
        speeds, validity_notes = [scene.operating.speed], result.attrs["validity_notes"]
    elif args.command == "transient":
        from lubecontact.cli.transient import run_transient

        return run_transient(scene, out, args.scene)
    else:
        import numpy as np

        from lubecontact.io.case_schema import write_case
        from lubecontact.studies.sweep import sweep

        ds = sweep(scene, speeds, direction=args.direction)
        write, effects_run = (lambda path: write_case(ds, path)), ds.attrs["effects_run"]
        values = {name: ds[name].values for name in (*_SHOWN, *_JUDGED)}
        speeds, validity_notes = ds["speed"].values, ds.attrs["validity_notes"]
        why, more_lines = "each point's notes are in the file", []
        points = [f"{u:g} m/s" for u in speeds]
        if "direction" in ds.dims:  # (direction, speed): each value with its speed, and how the two differ
            points = [f"{u:g} m/s {way}" for way in ds["direction"].values for u in speeds]
            speeds = np.broadcast_to(speeds, ds["contact_resistance"].shape).ravel()
            more_lines.append(f"  hysteresis: {ds.attrs['hysteresis']}")
        restarted = [point for point, flag in zip(points, ds["cold_restart"].values.ravel()) if flag == 1]
        if restarted:
            more_lines.append(f"  cold restart at {', '.join(restarted)}: the state continued from the previous speed "
                               "did not converge there, and a cold start did (cold_restart = 1: the branch followed "
                               "may end there)")
    try:
        write(out)
    except OSError as err:
        print(f"lubecontact: could not write {args.out}: {err.strerror or err}; the result is lost", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    print(_summary(effects_run, values))
    print("\n".join([*_findings(values, speeds, validity_notes, scene.interface.open_resistance), *more_lines]))
    print(f"wrote {args.out}")
    if not _converged(values):
        print(f"lubecontact: the solve did NOT converge (converged = 0 in the file): {why}", file=sys.stderr)
        return EXIT_NOT_CONVERGED
    return EXIT_OK


if __name__ == "__main__":
    sys.exit(main())
