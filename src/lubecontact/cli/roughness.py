"""``lubecontact roughness``: McCool's parameters of measured surfaces printed with their units,
the sampling and cut-off they were taken at, and a ``roughness:`` scene section."""

from __future__ import annotations

import math
import sys

import yaml

from lubecontact.io.atomic_write import write_text
from lubecontact.io.output_path import OutputPathError, check_output_path
from lubecontact.surfaces.mccool import McCool, composite, parameters
from lubecontact.surfaces.moments import DEFAULT_CUTOFF_INTERVALS, spectral_moments
from lubecontact.surfaces.reading import Surface, SurfaceError, read_surface


def describe(title: str, p: McCool) -> list[str]:
    """Lines of one surface's (or the composite's) parameters, each with its unit."""
    m = p.moments
    dirs = ("x", "y")[: len(m.m2)]
    lines = [f"{title}"]
    lines.append(f"  sampling       = {', '.join(f'd{d} {s * 1e6:.4g} um' for d, s in zip(dirs, m.sampling))}")
    lines.append(f"  cut-off        = lambda_c {m.cutoff * 1e6:.4g} um (spectral moments, window {m.window}, {m.detrending})")
    lines.append(f"  m0             = {m.m0:.6g} m^2")
    for name, values, unit in (("m2", m.m2, "1 (mean square slope)"), ("m4", m.m4, "m^-2 (mean square curvature)")):
        lines.append(f"  {name:<14s} = {', '.join(f'{v:.6g} ({d})' for v, d in zip(values, dirs))} {unit}")
    lines += [
        f"  sigma          = {p.sigma:.6g} m ({p.sigma * 1e6:.4g} um)",
        f"  eta            = {p.asperity_density:.6g} 1/m^2",
        f"  R_peak         = {p.asperity_radius:.6g} m ({p.asperity_radius * 1e6:.4g} um)",
        f"  alpha          = {p.alpha:.4g} (eta R_peak sigma = {p.asperity_density * p.asperity_radius * p.sigma:.4g})",
        f"  sigma_s        = {p.summit_sigma:.6g} m (McCool summit heights)",
        f"  gamma          = {'n/a (profile)' if p.gamma is None else f'{p.gamma:.4g}'}"
        + ("" if p.isotropic is None else f" ({'isotropic' if p.isotropic else 'anisotropic'})"),
    ]
    lines += [f"  note: {n}" for n in p.notes()]
    return lines


def section_yaml(p: McCool, sources: list[str], split: tuple[float, float] | None = None) -> str:
    """A ``roughness:`` section a scene can include; the rest as comments."""
    m = p.moments
    head = [
        f"# lubecontact roughness: McCool (1986) parameters of {' + '.join(sources)}",
        f"# cut-off lambda_c = {m.cutoff:.6g} m (default {DEFAULT_CUTOFF_INTERVALS:g} sampling intervals), "
        f"window {m.window}, {m.detrending}",
        f"# m0 = {m.m0:.6g} m^2, m2 = {', '.join(f'{v:.6g}' for v in m.m2)}, m4 = {', '.join(f'{v:.6g}' for v in m.m4)} m^-2",
        f"# alpha = {p.alpha:.6g}, sigma_s = {p.summit_sigma:.6g} m, gamma = {p.gamma}",
    ]
    if split is not None:
        head.append(f"# sigma split V_r1, V_r2 = {split[0]:.6g}, {split[1]:.6g} (sigma_i^2 / sigma^2, shear flow factor)")
    head += [f"# note: {n}" for n in p.notes()]
    body = {"roughness": {"sigma": p.sigma, "asperity_density": p.asperity_density, "asperity_radius": p.asperity_radius}}
    return "\n".join(head) + "\n" + yaml.safe_dump(body, sort_keys=False)


def check_cutoff_option(cutoff: float | None) -> None:
    """Refuse a --cutoff that is not a length (0, negative, NaN, infinite), as a scene's
    ``roughness.surface_cutoff`` is refused: the automatic cut-off is had by omitting it."""
    if cutoff is not None and not (math.isfinite(cutoff) and cutoff > 0.0):
        raise SurfaceError(
            f"--cutoff {cutoff:g}: the cut-off wavelength must be a finite length > 0 in m; "
            f"omit --cutoff for the automatic one ({DEFAULT_CUTOFF_INTERVALS:g} sampling intervals)"
        )


def common_cutoff(cutoff: float | None, surfaces: list[Surface]) -> float:
    """One cut-off for every surface: the given one, else the default of the coarsest sampling."""
    if cutoff is not None:
        return cutoff
    return DEFAULT_CUTOFF_INTERVALS * max(max(s.dx, s.dy or 0.0) for s in surfaces)


def run(args) -> int:
    """``lubecontact roughness``: 0 done, 2 bad input (the reason on stderr, nothing written).
    ``--out`` is checked as every command's is, before any surface is read (io/output_path.py):
    never a device, a directory or one of the surfaces; a link is followed."""
    try:
        out = None if args.out is None else check_output_path(args.out, inputs=args.surfaces)
    except OutputPathError as err:
        print(f"lubecontact: bad input: {err}", file=sys.stderr)
        return 2
    try:
        if len(args.surfaces) > 2:
            raise SurfaceError(f"{len(args.surfaces)} surfaces given; allowed: one, or two for their composite")
        check_cutoff_option(args.cutoff)
        surfaces = [read_surface(f, args.size, args.unit, args.periodic) for f in args.surfaces]
        cutoff = common_cutoff(args.cutoff, surfaces)
        params = [parameters(spectral_moments(s, cutoff)) for s in surfaces]
        blocks = [describe(f"surface {f}", p) for f, p in zip(args.surfaces, params)]
        split = None
        result = params[0]
        if len(params) == 2:
            result, split = composite(params[0].moments, params[1].moments)
            blocks.append(describe("composite (moments added: independent surfaces)", result)
                          + [f"  sigma split    = V_r1 {split[0]:.4g}, V_r2 {split[1]:.4g} (sigma_i^2/sigma^2)"])
    except SurfaceError as err:
        print(f"lubecontact: bad input: {err}", file=sys.stderr)
        return 2
    print("\n".join(line for block in blocks for line in block))
    if out is not None:
        try:
            write_text(out, section_yaml(result, list(args.surfaces), split))
        except OSError as err:
            print(f"lubecontact: cannot write {args.out}: {err.strerror or err}", file=sys.stderr)
            return 2
        print(f"wrote {args.out}")
    return 0
