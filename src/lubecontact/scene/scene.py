"""Scenes: the validated, frozen description of one physical problem (docs/DESIGN.md "Scene schema").

A scene is read from YAML (or a mapping), completed with the paper's Table 1 defaults,
checked, and frozen. SI units throughout. Each section is a frozen dataclass whose fields
carry their own rule (type, allowed range, unit), so this module's schema is the table
of fields below; ``load_scene`` only walks it.

Table 1 of Jackson & Angadi (2022): R = 0.01 m, Width = 0.001 m, sigma = 0.5 um,
eta = 1e9 1/m^2, R_peak = 100 um, E = 41.4 GPa, S_y = 14 MPa, nu = 0.36, mu = 0.1 Pa s,
rho = 1.15e-7 Ohm m, both bodies tin. The paper gives no boundary friction coefficient
(0.1 is our choice), nor force and speed beyond its figures (5 N, 0.1 m/s here).

Everything that is wrong with an input is reported at once in one ``SceneError``, one
problem per line, each naming the dotted key, the value given and what is allowed.
"""

from __future__ import annotations

import difflib
import hashlib
import io
import math
import numbers
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from functools import cache, cached_property
from pathlib import Path

import numpy as np
import yaml

from lubecontact.numerics.mesh import mesh_problems
from lubecontact.physics.viscosity_temperature import (
    D341_HIGHEST_TEMPERATURE,
    D341_LOWEST_VISCOSITY,
    KELVIN,
    WaltherLine,
    density,
)

AUTO = "auto"
# The YAML emitter of the canonical text (Scene.canonical_yaml): libyaml's where PyYAML has
# it (PyPI's wheels do), which writes the same text faster.
_SAFE_DUMPER = getattr(yaml, "CSafeDumper", yaml.SafeDumper)

# McCool (1986): sigma_s^2 = sigma^2 - 3.717e-4/(eta R_peak)^2 (docs/physics.md section 2).
MCCOOL_VARIANCE_CONSTANT = 3.717e-4
# Keys a measured surface (roughness.surface) sets; a scene with a surface must not set them.
SURFACE_SETS = ("sigma", "asperity_density", "asperity_radius")


# What a scene may hold. Table 1 is 2 kB and ~60 values; a long speed history goes in a
# motion.table file. Beyond these a scene is refused before anything walks it: a 100 MB
# scene once ran for minutes at 7.8 GB, and a few lines of YAML aliases ("billion laughs")
# expand to more values than memory holds.
MAX_SCENE_BYTES = 2**20
MAX_TABLE_BYTES = 16 * 2**20
MAX_VALUES = 100_000
MAX_DEPTH = 16
MAX_FLOW_DEPTH = 1000  # brackets the YAML reader is given at most
MAX_PROBLEM_CHARS = 500  # a message quotes at most this much of a value


def _shortened(text: str, limit: int = MAX_PROBLEM_CHARS) -> str:
    """``text`` with its middle left out beyond ``limit`` characters (a huge bad value is not
    echoed whole)."""
    if len(text) <= limit:
        return text
    keep = limit // 2
    return f"{text[:keep]} ... [{len(text) - 2 * keep} characters left out] ... {text[-keep:]}"


class SceneError(ValueError):
    """An unusable scene. ``problems`` holds one message per problem (also the lines of str())."""

    def __init__(self, origin: str, problems: list[str]):
        self.origin = origin
        self.problems = [_shortened(str(p)) for p in problems]
        super().__init__(f"invalid scene ({origin}):\n" + "\n".join(f"  {p}" for p in self.problems))

    def __reduce__(self):  # picklable across worker processes
        return type(self), (self.origin, self.problems)


# --- rules: convert one raw value or say why not -------------------------------------------


class _Invalid(Exception):
    """Raised by a rule; the message is the reason (the caller adds key, value and allowed)."""


_NUMBER = re.compile(r"[+-]?((0|[1-9]\d*)(\.\d*)?|\.\d+)([eE][+-]?\d+)?")  # decimal: 010 is refused


def _as_real(value) -> float:
    """A finite float from a number or a numeric string (PyYAML reads ``1e-6`` as a string)."""
    if isinstance(value, bool):
        raise _Invalid("a boolean, not a number")
    if isinstance(value, numbers.Real):
        x = float(value)
    elif isinstance(value, str) and _NUMBER.fullmatch(value.strip()):
        x = float(value)
    else:
        raise _Invalid("not a number")
    if not math.isfinite(x):
        raise _Invalid("not finite")
    return x


@dataclass(frozen=True)
class _Real:
    """A finite number with optional open or closed bounds."""

    unit: str
    low: float | None = None
    low_open: bool = True
    high: float | None = None
    high_open: bool = True
    reason: str = ""  # why the bounds are where they are, said with them

    @property
    def allowed(self) -> str:
        lo, hi = self.low, self.high
        if lo is not None and hi is not None:
            span = f"in {'(' if self.low_open else '['}{lo:g}, {hi:g}{')' if self.high_open else ']'}"
        elif lo is not None:
            span = f"{'>' if self.low_open else '>='} {lo:g}"
        elif hi is not None:
            span = f"{'<' if self.high_open else '<='} {hi:g}"
        else:
            span = ""
        unit = f"({self.unit})" if self.unit != "1" else ""
        reason = f"({self.reason})" if self.reason else ""
        return " ".join(filter(None, ["a finite number", span, unit, reason]))

    def __call__(self, value) -> float:
        x = _as_real(value)
        below = self.low is not None and (x <= self.low if self.low_open else x < self.low)
        above = self.high is not None and (x >= self.high if self.high_open else x > self.high)
        if below or above:
            raise _Invalid("out of range")
        return x

    def dump(self, value):
        return value


@dataclass(frozen=True)
class _Integer:
    """An integer >= minimum, or one of ``also``; whole floats (51.0, "5.1e1") are accepted."""

    minimum: int
    also: tuple[int, ...] = ()

    @property
    def allowed(self) -> str:
        extra = "".join(f"equal to {n} or " for n in self.also)
        return f"an integer {extra}>= {self.minimum}"

    def __call__(self, value) -> int:
        if isinstance(value, numbers.Integral) and not isinstance(value, bool):
            n = int(value)
        else:
            x = _as_real(value)
            if not x.is_integer():
                raise _Invalid("not a whole number")
            n = int(x)
        if n < self.minimum and n not in self.also:
            raise _Invalid("out of range")
        return n

    def dump(self, value):
        return value


@dataclass(frozen=True)
class _Flag:
    """A YAML boolean (true/false); 1/0 and strings are refused."""

    allowed = "true or false"

    def __call__(self, value) -> bool:
        if not isinstance(value, bool):
            raise _Invalid("not a boolean")
        return value

    def dump(self, value):
        return value


@dataclass(frozen=True)
class _Choice:
    options: tuple[str, ...]

    @property
    def allowed(self) -> str:
        return "one of " + ", ".join(repr(o) for o in self.options)

    def __call__(self, value) -> str:
        if value in self.options:
            return value
        close = difflib.get_close_matches(str(value), self.options, n=1)
        raise _Invalid(f"unknown option (did you mean {close[0]!r}?)" if close else "unknown option")

    def dump(self, value):
        return value


@dataclass(frozen=True)
class _FlagOrChoice:
    """One of ``options``; ``true``/``false`` (the older boolean form) stand for
    ``options[0]``/``options[-1]``, and those two are written back as true/false, so that a
    scene's canonical form (and hash) is what it was before the choice had more options."""

    options: tuple[str, ...]

    @property
    def allowed(self) -> str:
        return "true, false or " + _Choice(self.options).allowed

    def __call__(self, value) -> str:
        if isinstance(value, bool):
            return self.options[0] if value else self.options[-1]
        return _Choice(self.options)(value)

    def dump(self, value):
        return {self.options[0]: True, self.options[-1]: False}.get(value, value)


@dataclass(frozen=True)
class _AutoOr:
    """'auto' (stored as None: the code chooses) or a value of the inner rule."""

    inner: _Real

    @property
    def allowed(self) -> str:
        return f"{AUTO!r} or {self.inner.allowed}"

    def __call__(self, value):
        return None if value is None or value == AUTO else self.inner(value)

    def dump(self, value):
        return AUTO if value is None else value


@dataclass(frozen=True)
class _NotGivenOr:
    """'none' or left out (stored as None: the key is not given) or a value of the inner rule."""

    inner: _Real

    @property
    def unit(self) -> str:
        return self.inner.unit

    @property
    def allowed(self) -> str:
        return f"none (not given) or {self.inner.allowed}"

    def __call__(self, value):
        return None if value is None or value == "none" else self.inner(value)

    def dump(self, value):
        return value


@dataclass(frozen=True)
class _OptionalPath:
    """A file path (text), or none."""

    allowed = "a file path (text) or none"

    def __call__(self, value):
        if value is None or value == "none":
            return None
        if not isinstance(value, str) or not value.strip():
            raise _Invalid("not a file path")
        return value

    def dump(self, value):
        return value


def _field(default, rule, doc: str):
    """A schema entry: default (Table 1), rule (type and range), doc (meaning, paper symbol)."""
    return field(default=default, metadata={"rule": rule, "doc": doc})


def _positive(unit):
    return _Real(unit, low=0.0)


def _nonnegative(unit):
    return _Real(unit, low=0.0, low_open=False)


# The physical range of the inputs the contact laws stand on, each orders of magnitude wider
# than any engineering contact. Outside it a value describes no contact the model is about,
# and double precision cannot hold what the laws compute from it: found by a sweep of
# extreme finite values over every positive input (session 56), a modulus of 5e-324 Pa made
# the Hertz width divide by zero, an asperity density of 1e308 1/m^2 overflowed the
# roughness bandwidth, a yield strength or sigma of 1e-300 gave a rough-contact table that
# is not monotone, a cylinder radius of 1e30 m asked for 394 PiB of mesh, and a viscosity of
# 5e-324 Pa s an infinite Poiseuille coefficient.
ATOM = 1.0e-10  # m: below it a length is not a continuum's
LONGEST = 1.0e3  # m: a cylinder beyond a kilometre is not a contact's


def _length():
    return _Real("m", low=ATOM, low_open=False, high=LONGEST, high_open=False,
                 reason="from an atom, 1e-10 m, to a kilometre")


def _stiffness():
    """A modulus or strength: at least a gel's; no upper bound (a rigid body may be given a
    large modulus, 1e300 Pa solves)."""
    return _Real("Pa", low=1.0e3, low_open=False, reason="at least a gel's 1 kPa")


class _Section:
    """Shared behaviour of the scene's sections."""

    @classmethod
    @cache
    def rules(cls) -> tuple[tuple[str, object], ...]:
        """(key, rule) of the section's scene keys (fields with a rule), in schema order;
        looked up once per section (planning the default workflow builds 1421 scenes)."""
        return tuple((f.name, f.metadata["rule"]) for f in fields(cls) if "rule" in f.metadata)

    @classmethod
    @cache
    def keys(cls) -> tuple[str, ...]:
        return tuple(name for name, _ in cls.rules())

    def to_dict(self):
        return {name: rule.dump(getattr(self, name)) for name, rule in self.rules()}


# --- the schema ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Geometry(_Section):
    radius: float = _field(0.01, _length(), "cylinder radius R")
    length: float = _field(0.001, _length(), "cylinder length along its axis (Table 1 'Width')")
    crown_radius: float | None = _field(
        None, _NotGivenOr(_length()),
        "crown radius R_c along the axis: the gap grows by R_c - sqrt(R_c^2 - y^2) towards the ends (none: a "
        "straight cylinder, as the paper's; docs/physics.md section 11)",
    )

    def to_dict(self):
        """A straight cylinder's crown left out, so scenes written before the key keep their hash."""
        return {k: v for k, v in super().to_dict().items() if v is not None}


@dataclass(frozen=True)
class Material(_Section):
    """One body; both are tin in Table 1."""

    youngs_modulus: float = _field(41.4e9, _stiffness(), "Young's modulus E")
    poisson_ratio: float = _field(0.36, _Real("1", low=-1.0, high=0.5), "Poisson ratio nu")
    yield_strength: float = _field(14.0e6, _stiffness(), "yield strength S_y")
    resistivity: float = _field(1.15e-7, _positive("Ohm m"), "electrical resistivity rho")


@dataclass(frozen=True)
class Roughness(_Section):
    """Combined roughness of the two surfaces (Greenwood-Williamson statistics, Eq. 11)."""

    sigma: float = _field(0.5e-6, _Real("m", low=ATOM, low_open=False, reason="at least an atom, 1e-10 m"),
                          "RMS roughness sigma")
    asperity_density: float = _field(
        1.0e9, _Real("1/m^2", low=1.0, low_open=False, high=ATOM**-2, high_open=False,
                     reason="from one asperity per m^2 to one per atom, 1e20"),
        "areal density of asperities eta")
    asperity_radius: float = _field(1.0e-4, _length(), "asperity tip radius R_peak")
    hardness_model: str = _field(
        "wadwalkar", _Choice(("wadwalkar", "jg2005")), "H_G/S_y: Eq. 8 (Wadwalkar 2010) or Jackson-Green 2005"
    )
    height_std: str = _field(
        "sigma", _Choice(("sigma", "mccool")), "std of asperity heights: sigma (paper) or McCool's sigma_s"
    )
    split: float = _field(
        0.5, _Real("1", low=0.0, low_open=False, high=1.0, high_open=False),
        "share of sigma^2 on the sliding block (the rest on the cylinder): Patir-Cheng shear flow factor",
    )
    # 1: the effective-medium law (docs/physics.md section 15); 1.3: the universal conductivity
    # exponent of 2-D percolation. Below 1 the flow's slope is infinite at the threshold.
    percolation_exponent: float = _field(
        1.0, _Real("1", low=1.0, low_open=False, high=2.0, high_open=False),
        "exponent t of the pressure flow between percolation (h = 0) and h = 0.5 sigma: k ~ share^t",
    )
    surface: str | None = _field(
        None, _OptionalPath(), "measured surface file, relative to the scene file; sets sigma, eta and R_peak"
    )
    surface_cutoff: float | None = _field(
        None, _AutoOr(_positive("m")), "short-wavelength cut-off of the surface's m2, m4 (auto: 4 samples)"
    )
    surface_sha256: str | None = None  # content of the surface file: what the case hash sees
    directory: str = field(default=".", compare=False)  # where a relative surface path starts

    def _all_keys(self):
        """Every key; the equal split (the default, where the shear flow factor vanishes) and
        the effective-medium percolation exponent 1 are left out, so that scenes written
        before the keys existed keep their canonical form and hash."""
        data = super().to_dict()
        for key, default in (("split", 0.5), ("percolation_exponent", 1.0)):
            if data[key] == default:
                del data[key]
        return data

    def to_dict(self):
        """Without a surface, as before; with one, its path and no sigma, eta, R_peak (they
        come from the file when the dict is loaded again)."""
        drop = SURFACE_SETS if self.surface is not None else ("surface", "surface_cutoff")
        return {k: v for k, v in self._all_keys().items() if k not in drop}

    def canonical_dict(self):
        """The case's identity: the file's content (sha256), not its name, with the
        parameters read from it."""
        if self.surface is None:
            return self.to_dict()
        return {**self._all_keys(), "surface": f"sha256:{self.surface_sha256}"}


_D341_VISCOSITY = _Real("mm^2/s", low=D341_LOWEST_VISCOSITY, low_open=False)
# The lubricant keys of a yield-stress grease (docs/physics.md section 21), left out of the
# canonical form at their defaults.
RHEOLOGY_KEYS = ("rheology", "yield_stress", "flow_index", "creep_viscosity")


@dataclass(frozen=True)
class Lubricant(_Section):
    # <= 1e6 Pa s (far above any lubricant): 1e200 overflowed the film coefficients (issue 13)
    viscosity: float = _field(0.1, _Real("Pa s", low=1e-6, low_open=False, high=1e6, high_open=False,
                                         reason="from a tenth of a gas's to a stiff grease's"),
                              "dynamic viscosity mu (isoviscous)")
    # Mineral oils conduct 0.4-2.1 pS/m (Shell Vitrea, Harvey et al., as reported in
    # "Electrical conductivity of motor oil", qsstudy.com): 1 pS/m is 1e12 ohm m.
    resistivity: float = _field(
        1.0e12, _positive("Ohm m"), "electrical resistivity of the lubricant rho_f (effects.film_conduction)"
    )
    # The datasheet (docs/physics.md section 19): with operating.temperature these set viscosity.
    # Not below 0.21 mm^2/s, the end of D341's equations (below 0.115 log10 log10 Z fails).
    kinematic_viscosity_40: float | None = _field(
        None, _NotGivenOr(_D341_VISCOSITY), "datasheet kinematic viscosity at 40 C (cSt); sets viscosity (ASTM D341)"
    )
    kinematic_viscosity_100: float | None = _field(
        None, _NotGivenOr(_D341_VISCOSITY), "datasheet kinematic viscosity at 100 C (cSt); sets viscosity (ASTM D341)"
    )
    # API MPMS 11.1's density law holds for lubricating oils of 800-1164 kg/m^3 at 15 C.
    density: float | None = _field(
        None, _NotGivenOr(_Real("kg/m^3", low=800.0, low_open=False, high=1164.0, high_open=False)),
        "datasheet density at 15 C (ISO 12185 / ASTM D4052); mu = rho nu at operating.temperature",
    )
    pour_point: float | None = _field(
        None, _NotGivenOr(_Real("degC")), "datasheet pour point (optional): operating.temperature must be above it"
    )
    # A grease (docs/physics.md section 21): viscosity is then the plastic viscosity (bingham)
    # or the consistency K in Pa s^n (herschel_bulkley).
    rheology: str = _field(
        "newtonian", _Choice(("newtonian", "bingham", "herschel_bulkley")),
        "flow law of the Reynolds equation: newtonian, or a yield-stress grease (solved by one Newton)",
    )
    yield_stress: float = _field(0.0, _nonnegative("Pa"), "yield stress tau_y of a Bingham or Herschel-Bulkley grease")
    flow_index: float = _field(1.0, _positive("1"), "herschel_bulkley flow index n (viscosity is then K in Pa s^n)")
    # ASTM D1092 measures a grease's apparent viscosity from 25 to 100 000 P at 0.1 1/s: the
    # default is the top of that range, 1e4 Pa s.
    creep_viscosity: float = _field(
        1.0e4, _positive("Pa s"), "viscosity with which a grease creeps below its yield stress (bi-viscous law)"
    )

    def to_dict(self):
        """Keys not given left out (scenes without a datasheet keep their hash); with a
        datasheet, no viscosity (it comes from the datasheet when the dict is loaded again);
        the rheology keys left out at their defaults (a Newtonian lubricant keeps its hash)."""
        data = {k: v for k, v in super().to_dict().items() if v is not None}
        if self.kinematic_viscosity_40 is not None:
            del data["viscosity"]
        for key in RHEOLOGY_KEYS:
            if getattr(self, key) == getattr(Lubricant, key):
                del data[key]
        return data

    def canonical_dict(self):
        """The case's identity: the datasheet with the viscosity derived from it."""
        return {**self.to_dict(), "viscosity": self.viscosity}


@dataclass(frozen=True)
class Interface(_Section):
    boundary_friction: float = _field(
        0.1, _nonnegative("1"), "friction coefficient of solid contact mu_b (not in the paper)"
    )
    # Hydrocarbon chains: 1.42 eV measured through alkanethiol monolayers (Wang, Lee & Reed,
    # Phys. Rev. B 68 (2003) 035416).
    barrier_height: float = _field(
        1.4, _positive("eV"), "tunnelling barrier height phi of the film (effects.tunnelling, Simmons 1963)"
    )
    # Connector discontinuity tests count an event above 10 ohm (EIA-364-46 / -87 practice).
    open_resistance: float = _field(
        10.0, _positive("ohm"), "contact resistance above which the contact counts as open"
    )
    # EIA-364-87 counts discontinuities of 1 us and longer (some tests go to nanoseconds).
    min_event_duration: float = _field(
        1.0e-6, _nonnegative("s"), "transient: shortest time above a resistance threshold that counts as an event"
    )

    def to_dict(self):
        """min_event_duration is left out at its default, so that scenes written before the
        key existed keep their canonical form and hash."""
        data = super().to_dict()
        if self.min_event_duration == Interface.min_event_duration:
            del data["min_event_duration"]
        return data


@dataclass(frozen=True)
class Operating(_Section):
    force: float = _field(5.0, _positive("N"), "normal force on the cylinder F")
    speed: float = _field(0.1, _nonnegative("m/s"), "sliding speed U of the block")
    temperature: float | None = _field(
        None, _NotGivenOr(_Real("degC", low=-KELVIN, high=D341_HIGHEST_TEMPERATURE, high_open=False)),
        "temperature of the oil (with the lubricant's datasheet keys it sets lubricant.viscosity)",
    )

    def to_dict(self):
        """Without the temperature when it is not given (older scenes keep their hash)."""
        return {k: v for k, v in super().to_dict().items() if k != "temperature" or v is not None}


@dataclass(frozen=True)
class Effects(_Section):
    """Physical effects to simulate (docs/DESIGN.md "Effects"); ``effects: auto`` turns all on
    and leaves ``auto`` set, so the canonical form keeps saying ``auto``. Setting any one
    flag (``effects.hydrodynamics=false``) makes the effects explicit: auto ends, the
    other flags stay on. The electrical-path effects (macro_constriction,
    film_conduction, tunnelling) go beyond the paper: off by default and under auto."""

    hydrodynamics: bool = _field(True, _Flag(), "modified Reynolds fluid pressure (Eq. 1)")
    flow_factors: bool = _field(True, _Flag(), "Patir-Cheng flow factors (Eq. 2)")
    cavitation: str = _field(
        "reynolds", _FlagOrChoice(("reynolds", "jfo", "none")),
        "reynolds: Swift-Stieber p >= 0 (true); jfo: mass-conserving JFO with film content; none: full Sommerfeld (false)",
    )
    asperity_contact: bool = _field(True, _Flag(), "statistical rough contact (Eqs. 6-13)")
    plasticity: bool = _field(True, _Flag(), "Jackson-Green elastic-plastic asperities")
    elastic_deformation: bool = _field(True, _Flag(), "macro deformation by influence coefficients")
    alleviation: bool = _field(True, _Flag(), "alleviation factor Psi (Eq. 16)")
    macro_constriction: bool = _field(False, _Flag(), "Greenwood cluster constriction in series (not in the paper)")
    film_conduction: bool = _field(False, _Flag(), "ohmic conduction of the lubricant film (not in the paper)")
    tunnelling: bool = _field(False, _Flag(), "Simmons tunnelling through thin films (not in the paper)")
    auto: bool = False

    def to_dict(self):
        return AUTO if self.auto else super().to_dict()


@dataclass(frozen=True)
class MeshSettings(_Section):
    nx: int = _field(51, _Integer(3), "nodes along x (sliding), ends included")
    ny: int = _field(51, _Integer(3, also=(1,)), "nodes along y (cylinder axis); 1 = line contact")
    x_min: float | None = _field(None, _AutoOr(_Real("m")), "inlet end of the domain (auto: mesh.domain_x)")
    x_max: float | None = _field(None, _AutoOr(_Real("m")), "outlet end of the domain (auto: mesh.domain_x)")
    far_inlet: bool | None = _field(
        None, _AutoOr(_Flag()),
        "the rigid film upstream of the automatic domain as its boundary condition, in place of the inlet columns "
        "(a line: Martin's film; a straight cylinder: its sine modes across the length; docs/physics.md section 17, "
        "\"The far inlet\"): auto (the default) wherever the long inlet would add columns and it fits (a steady "
        "Newtonian contact between rough surfaces, a straight cylinder; a motion keeps the columns), true to ask "
        "for it (refused where it does not fit), false for the long inlet",
    )

    def to_dict(self):
        """The default (auto) is left out, so scenes written before the key keep their hash (the
        solver's fingerprint in each case file re-solves what the default changed)."""
        data = super().to_dict()
        if self.far_inlet is None:
            del data["far_inlet"]
        return data


@dataclass(frozen=True)
class SolverSettings(_Section):
    tolerance: float = _field(1.0e-6, _Real("1", low=0.0, high=0.1), "relative force-balance tolerance")
    max_iterations: int = _field(200, _Integer(1), "iteration limit of the force balance")
    method: str = _field(
        "nested", _Choice(("nested", "newton")),
        "nested: force balance inside a deformation fixed point (model/coupling.py); newton: one semismooth "
        "Newton on the whole residual (model/monolithic_newton.py), steady and at every time step",
    )

    def to_dict(self):
        """The default method is left out, so scenes written before the key keep their hash."""
        data = super().to_dict()
        if self.method == "nested":
            del data["method"]
        return data


@dataclass(frozen=True)
class _SpeedTable:
    """Rows (t s, U m/s), times strictly increasing from t = 0: a list of pairs, or the path
    of a text file with two columns. The canonical form holds the rows, so the table's
    content (not a file name) enters the case hash."""

    allowed = "a list of [t (s), U (m/s)] rows (or a two-column text file), t increasing from 0"

    def __call__(self, value):
        if value is None:
            return None
        if isinstance(value, str):
            try:
                size = os.path.getsize(value)
                if size > MAX_TABLE_BYTES:
                    raise _Invalid(f"the table file is {size / 2**20:.3g} MB; at most {MAX_TABLE_BYTES / 2**20:g} MB")
                value = np.loadtxt(value, ndmin=2).tolist()
            except (OSError, ValueError) as err:
                raise _Invalid(f"cannot read the table file ({err})") from None
        try:
            rows = tuple((_as_real(t), _as_real(u)) for t, u in value)
        except (TypeError, ValueError):
            raise _Invalid("not a list of [t, U] pairs") from None
        times = [t for t, _ in rows]
        if len(rows) < 2 or times[0] != 0.0 or any(b <= a for a, b in zip(times, times[1:])):
            raise _Invalid("needs >= 2 rows, the first at t = 0, times strictly increasing")
        return rows

    def dump(self, value):
        return None if value is None else [list(row) for row in value]


@dataclass(frozen=True)
class Motion(_Section):
    """What the block does in time (docs/DESIGN.md "Time"; lubecontact.transient). The
    default (steady at operating.speed) is left out of the canonical form, so scenes
    without ``motion:`` keep their hash."""

    kind: str = _field(
        "steady", _Choice(("steady", "stop", "start", "oscillation", "table")),
        "steady | stop (slide, ramp down, rest) | start (ramp up from rest) | oscillation | table",
    )
    speed: float | None = _field(None, _AutoOr(_nonnegative("m/s")), "sliding speed before a stop / after a start (auto: operating.speed)")
    stop_time: float = _field(0.0, _nonnegative("s"), "time the deceleration (stop) begins")
    ramp: float = _field(1.0e-3, _nonnegative("s"), "duration of the linear deceleration / acceleration")
    duration: float = _field(10.0, _positive("s"), "simulated time after stop_time (after t = 0 for other kinds; an oscillation runs at least its cycles)")
    amplitude: float = _field(1.0e-4, _positive("m"), "oscillation: amplitude of the block's displacement")
    frequency: float = _field(10.0, _positive("Hz"), "oscillation: frequency")
    cycles: int = _field(3, _Integer(1), "oscillation: number of cycles, then rest")
    table: tuple | None = _field(None, _SpeedTable(), "table: rows (t, U), linear in between, the last U after")
    reconnect_factor: float = _field(2.0, _Real("1", low=1.0), "reconnected when R <= this x the resistance at rest; above it a relative event")
    tolerance: float = _field(1.0e-3, _Real("1", low=0.0, high=0.5), "relative local error of a time step (film)")
    error_bar: bool = _field(
        False, _Flag(), "run again at tolerance/10 and report reconnect_time's time-integration error (twice the cost)"
    )
    mesh_error_bar: bool = _field(
        True, _Flag(),
        "where a reconnection is timed, run again on a mesh twice as fine along x (at rest: motion.rest_refinement "
        "doubled) and report reconnect_time's mesh error and reconnect_time_extrapolated, the reconnect time on a "
        "converged mesh (a second run, about three times the first's on the Table 1 stop); false: the one run, "
        "its reconnect time short by its mesh error",
    )
    error_norm: str = _field(
        "rms", _Choice(("rms", "max")),
        "how a step's node errors make its error: rms (their root mean square) | max (the largest, which does not "
        "loosen as the mesh refines; docs/physics.md section 14)",
    )
    mass: float = _field(0.0, _nonnegative("kg"), "moving mass of the contact (0: massless, in force balance at every instant)")
    spring_stiffness: float = _field(
        0.0, _nonnegative("N/m"), "stiffness of the connector's spring; operating.force is its preload at the start"
    )
    vibration: str = _field(
        "none", _Choice(("none", "sine", "sine_sweep", "random", "half_sine_shock")),
        "normal base excitation of the connector: none | sine | sine_sweep | random | half_sine_shock (needs motion.mass > 0)",
    )
    vibration_acceleration: float = _field(
        0.0, _Real("m/s^2"),
        "peak acceleration of the base excitation (random: its RMS), normal to the contact: > 0 toward the block, "
        "< 0 away (lifts a shock)",
    )
    vibration_frequency: float = _field(
        100.0, _positive("Hz"), "sine: frequency of the base excitation; sine_sweep, random: the lowest"
    )
    vibration_frequency_end: float = _field(
        1000.0, _positive("Hz"), "sine_sweep: frequency at the end of motion.duration; random: the highest of its band"
    )
    vibration_seed: int = _field(0, _Integer(0), "random: seed of the phases (the same seed, the same signal)")
    shock_duration: float = _field(1.0e-3, _positive("s"), "half_sine_shock: duration of the half sine")
    rest_refinement: int = _field(
        1, _Integer(1),
        "at rest, the steps go on on the contact's own domain (x in [-x_max, x_max]) with this many times the nodes "
        "per metre along x of the motion's mesh (automatic domain only; docs/physics.md section 14)",
    )

    table_file: str | None = field(default=None, compare=False)  # the file motion.table was read from

    # keys added after scenes were written: left out at their defaults (to_dict), so no hash changes.
    # Not mesh_error_bar: its default turned from false to true, so a motion's hash says which it is
    LATER_KEYS = ("mass", "spring_stiffness", "vibration", "vibration_acceleration", "vibration_frequency",
                  "vibration_frequency_end", "vibration_seed", "shock_duration", "rest_refinement", "error_norm")

    def to_dict(self):
        """None for the default motion; ``error_bar`` and the keys added later (LATER_KEYS) left
        out at their defaults, so scenes written before them keep their hash."""
        if self == Motion():
            return None
        data = super().to_dict()
        if not self.error_bar:
            del data["error_bar"]
        for key in self.LATER_KEYS:
            if data[key] == getattr(Motion, key):
                del data[key]
        return data


@dataclass(frozen=True)
class Scene:
    """One validated physical problem. Build it with ``load_scene``."""

    geometry: Geometry = field(default_factory=Geometry)
    cylinder: Material = field(default_factory=Material)
    block: Material = field(default_factory=Material)
    roughness: Roughness = field(default_factory=Roughness)
    lubricant: Lubricant = field(default_factory=Lubricant)
    interface: Interface = field(default_factory=Interface)
    operating: Operating = field(default_factory=Operating)
    effects: Effects = field(default_factory=Effects)
    mesh: MeshSettings = field(default_factory=MeshSettings)
    solver: SolverSettings = field(default_factory=SolverSettings)
    motion: Motion = field(default_factory=Motion)

    def input_files(self) -> tuple[str, ...]:
        """The data files the scene was read from besides its own: a measured surface
        (roughness.surface) and a speed table (motion.table), which no output may replace."""
        files = []
        if self.roughness.surface is not None:
            files.append(str(Path(self.roughness.directory) / self.roughness.surface))
        if self.motion.table_file is not None:
            files.append(self.motion.table_file)
        return tuple(files)

    def to_dict(self) -> dict:
        """Plain Python types; ``auto`` where the scene says auto; default sections that
        would change old hashes (``motion``) left out."""
        sections = {f.name: getattr(self, f.name).to_dict() for f in fields(self)}
        return {name: value for name, value in sections.items() if value is not None}

    def canonical_yaml(self) -> str:
        """Sorted keys, every default filled, floats written from repr(float): equal scenes
        give equal text however they were spelt. A measured surface appears by content."""
        return self._canonical_yaml

    @cached_property
    def _canonical_yaml(self) -> str:
        # built once per scene (the scene is frozen): each solve needs it for its hash and
        # its dataset's attributes. libyaml's emitter writes the same text as PyYAML's
        # pure-Python one (all 1174 scenes of config/config.yaml) in a tenth of the time:
        # planning the default workflow hashed 1421 scenes in 5.7 s with the latter.
        data = {**self.to_dict(), "roughness": self.roughness.canonical_dict(),
                "lubricant": self.lubricant.canonical_dict()}
        return yaml.dump(data, Dumper=_SAFE_DUMPER, sort_keys=True, default_flow_style=False)

    @cached_property
    def hash(self) -> str:
        """Content hash (16 hex digits of sha256 of the canonical YAML): the case identity."""
        return hashlib.sha256(self.canonical_yaml().encode()).hexdigest()[:16]

    def replace(self, overrides: Mapping) -> Scene:
        """A new validated scene with dotted-key overrides applied (same rules as load_scene)."""
        return load_scene(self, overrides)


SECTIONS: dict[str, type[_Section]] = {f.name: f.default_factory for f in fields(Scene)}
_ALL_KEYS = [f"{s}.{k}" for s, cls in SECTIONS.items() for k in cls.keys()]


# --- loading -------------------------------------------------------------------------------


class _UniqueKeyLoader(yaml.CSafeLoader):
    """SafeLoader that refuses a key given twice in one mapping (PyYAML keeps the last)."""

    def construct_mapping(self, node, deep=False):
        keys = [self.construct_object(k, deep=deep) for k, _ in node.value]
        twice = sorted({str(k) for k in keys if keys.count(k) > 1})
        if twice:
            raise yaml.constructor.ConstructorError(
                None, None, f"key {', '.join(twice)} given twice", node.start_mark
            )
        return super().construct_mapping(node, deep=deep)


# Numbers in scenes are decimal only. YAML 1.1 (PyYAML) also reads 0x10 as 16, 010 as 8,
# 1_000 as 1000 and 1:20 as 80 (base 60): such values stay strings here and are refused
# ("not a number"), like every other non-number. 1e-6 is read as a number (YAML 1.2).
_DECIMAL_RESOLVERS = (
    ("tag:yaml.org,2002:int", re.compile(r"^[-+]?(0|[1-9][0-9]*)$"), list("-+0123456789")),
    ("tag:yaml.org,2002:float",
     re.compile(r"^[-+]?(\d+\.\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?(0|[1-9]\d*)[eE][-+]?\d+$|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$"),
     list("-+0123456789.")),
)
_UniqueKeyLoader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag not in {t for t, _, _ in _DECIMAL_RESOLVERS}]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
for _tag, _regexp, _first in _DECIMAL_RESOLVERS:
    _UniqueKeyLoader.add_implicit_resolver(_tag, _regexp, _first)


def _yaml_value(text: str):
    """One YAML value with the scene loader's rules (decimal numbers only)."""
    return yaml.load(text, Loader=_UniqueKeyLoader)


EMPTY_SCENE = (
    "the scene file is empty; for the Table 1 scene write {} in it (every key then takes its "
    "Table 1 default) or use config/scenes/table1.yaml"
)


def _read(source) -> tuple[object, str]:
    """(raw data, origin for messages) from a path, a mapping or a Scene."""
    if isinstance(source, Scene):
        return source.to_dict(), "scene"
    if isinstance(source, Mapping):
        return source, "mapping"
    if isinstance(source, (str, os.PathLike)):
        path = Path(source)
        try:
            size = path.stat().st_size
            if size > MAX_SCENE_BYTES:
                raise SceneError(str(path), [
                    f"the scene file is {size / 2**20:.3g} MB; allowed: at most {MAX_SCENE_BYTES / 2**20:g} MB "
                    "(a long speed history goes in a motion.table file)"
                ])
            text = path.read_text(encoding="utf-8")
            brackets = text.count("[") + text.count("{")  # counted in C: the scan below only when it matters
            if brackets > MAX_FLOW_DEPTH and _flow_depth(text) > MAX_FLOW_DEPTH:  # libyaml crashes near 50 000
                raise SceneError(str(path), [f"the YAML nests brackets deeper than {MAX_FLOW_DEPTH} levels; "
                                             f"allowed: {MAX_DEPTH}"])
            stream = io.StringIO(text)
            stream.name = str(path)  # YAML error marks name the file
            raw = yaml.load(stream, Loader=_UniqueKeyLoader)
        except OSError as err:
            raise SceneError(str(path), [f"cannot read scene file: {err.strerror or err}"]) from err
        except UnicodeDecodeError as err:
            line = err.object.count(b"\n", 0, err.start) + 1
            raise SceneError(str(path), [f"not UTF-8 text: byte {err.object[err.start]:#04x} on line {line} (a "
                                         "degree sign or accent saved as Latin-1?); save the scene as UTF-8"]) from None
        except yaml.YAMLError as err:
            raise SceneError(str(path), [f"invalid YAML: {err}"]) from err
        except RecursionError:
            raise SceneError(str(path), [f"the YAML nests deeper than Python can read; allowed: {MAX_DEPTH} levels"]) from None
        if raw is None:
            raise SceneError(str(path), [EMPTY_SCENE])
        return raw, str(path)
    raise TypeError(f"load_scene expects a path, a mapping or a Scene, not {type(source).__name__}")


def _flow_depth(text: str) -> int:
    """The deepest nesting of YAML flow brackets ([ and {) outside quotes in ``text``."""
    depth = deepest = 0
    quote = None
    for char in text:
        if quote:
            quote = None if char == quote else quote
        elif char in "'\"":
            quote = char
        elif char in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in "]}":
            depth -= 1
    return deepest


def _bounded(raw, origin: str) -> None:
    """SceneError unless ``raw`` holds at most MAX_VALUES values nested at most MAX_DEPTH
    deep, counted as they expand (a YAML alias counts each time it is used), so that nothing
    later walks or prints an unbounded structure."""
    count, todo = 0, [(raw, 1)]
    while todo:
        value, depth = todo.pop()
        count += 1
        if count > MAX_VALUES or depth > MAX_DEPTH:
            what = f"holds more than {MAX_VALUES} values" if count > MAX_VALUES else f"nests deeper than {MAX_DEPTH} levels"
            raise SceneError(origin, [
                f"the scene {what} (YAML aliases count each time they are used); allowed: sections of "
                "keys with numbers, words or short lists (a long speed history goes in a motion.table file)"
            ])
        if isinstance(value, Mapping):
            todo.extend((v, depth + 1) for v in value.values())
        elif isinstance(value, (list, tuple)):
            todo.extend((v, depth + 1) for v in value)


def _unknown_key(key: str) -> str:
    """'key: unknown key; did you mean ...?' with the nearest known key."""
    if key == "effects.auto":
        return f"{key}: unknown key; write effects: auto (override effects=auto) for automatic effects"
    section, _, name = key.partition(".")
    leaf = name or section
    elsewhere = [k for k in _ALL_KEYS if k.rsplit(".", 1)[1] == leaf]  # right name, wrong section
    if name and section in SECTIONS:
        siblings = SECTIONS[section].keys()
        near = difflib.get_close_matches(f"{section}.{name}", [f"{section}.{k}" for k in siblings], n=1)
        allowed = f"keys of {section}: " + ", ".join(siblings)
    else:
        near = difflib.get_close_matches(section, list(SECTIONS), n=1)
        allowed = "sections: " + ", ".join(SECTIONS)
    guess = elsewhere or near or difflib.get_close_matches(key, _ALL_KEYS, n=1)
    return f"{key}: unknown key; " + (f"did you mean {' or '.join(guess)}?" if guess else allowed)


def _apply_overrides(raw, overrides: Mapping, problems: list[str]):
    """Copy of raw with dotted-key overrides set; string values are read as YAML."""
    if not isinstance(raw, Mapping):
        return raw
    data = {k: dict(v) if isinstance(v, Mapping) else v for k, v in raw.items()}
    for key, value in overrides.items():
        key = str(key)
        if isinstance(value, str):
            try:
                value = _yaml_value(value)
            except yaml.YAMLError:
                problems.append(f"{key} = {value!r}: not a valid YAML value")
                continue
        section, _, name = key.partition(".")
        current = data.get(section)
        if not name:  # a whole section: merge a mapping into a mapping, replace otherwise
            both = isinstance(value, Mapping) and isinstance(current, Mapping)
            data[section] = {**current, **value} if both else value
            continue
        if section == "effects" and current == AUTO:  # an explicit flag ends auto
            current = {f.name: f.default for f in fields(Effects) if "rule" in f.metadata}
        if current is None:
            current = {}
        if not isinstance(current, Mapping):
            problems.append(f"{key}: cannot set, {section} is {current!r}, not a mapping")
            continue
        data[section] = {**current, name: value}
    return data


def _build_section(name: str, raw, problems: list[str]):
    """The section's dataclass from its raw mapping, or None (problems appended)."""
    cls = SECTIONS[name]
    if name == "effects" and raw == AUTO:
        return Effects(auto=True)
    if raw is None:
        raw = {}
    if not isinstance(raw, Mapping):
        extra = f" or {AUTO!r}" if name == "effects" else ""
        problems.append(f"{name} = {raw!r}: not a mapping; allowed: a mapping of {', '.join(cls.keys())}{extra}")
        return None
    n_before = len(problems)
    problems.extend(_unknown_key(f"{name}.{k}") for k in raw if k not in cls.keys())
    values = {}
    for key, rule in cls.rules():
        if key not in raw:
            continue
        value = raw[key]
        try:
            values[key] = rule(value)
        except _Invalid as why:
            problems.append(f"{name}.{key} = {value!r}: {why}; allowed: {rule.allowed}")
    return cls(**values) if len(problems) == n_before else None


def _directory(source) -> str:
    """Where a relative ``roughness.surface`` or ``motion.table`` starts: the scene file's
    directory, a Scene's own, else the current directory."""
    if isinstance(source, Scene):
        return source.roughness.directory
    if isinstance(source, (str, os.PathLike)):
        return str(Path(source).resolve().parent)
    return str(Path.cwd())


def _table_beside_scene(raw: Mapping, directory: str) -> Mapping:
    """``raw`` with a relative ``motion.table`` file taken from ``directory`` (the scene
    file's, as a relative ``roughness.surface`` is), not from the current directory."""
    motion = raw.get("motion")
    if not isinstance(motion, Mapping) or not isinstance(motion.get("table"), str) or Path(motion["table"]).is_absolute():
        return raw
    return {**raw, "motion": {**motion, "table": str(Path(directory) / motion["table"])}}


def _with_table_file(motion, raw):
    """The motion section with the file its table was read from (Motion.table_file)."""
    if motion is None or not isinstance(raw, Mapping) or not isinstance(raw.get("table"), str):
        return motion
    return replace(motion, table_file=raw["table"])


def _surface_replaces(raw, overrides: Mapping):
    """An override of roughness.surface replaces sigma, eta and R_peak of the scene it
    overrides (they come from the file); overriding them as well is still refused."""
    if "roughness.surface" not in overrides or not isinstance(raw, Mapping) or not isinstance(raw.get("roughness"), Mapping):
        return raw
    return {**raw, "roughness": {k: v for k, v in raw["roughness"].items() if k not in SURFACE_SETS}}


def _datasheet_replaces(raw, overrides: Mapping):
    """An override of the lubricant's datasheet (lubricant.kinematic_viscosity_40, ...) replaces
    the viscosity of the scene it overrides (it comes from the datasheet), as a surface
    replaces sigma; overriding the viscosity as well is still refused."""
    keys = {k for k in DATASHEET_KEYS if k.startswith("lubricant.")}
    if not keys & set(overrides) or not isinstance(raw, Mapping) or not isinstance(raw.get("lubricant"), Mapping):
        return raw
    return {**raw, "lubricant": {k: v for k, v in raw["lubricant"].items() if k != "viscosity"}}


def _measured(roughness, raw, directory: str, problems: list[str]):
    """The roughness section with sigma, eta and R_peak from ``roughness.surface``
    (McCool's method, lubecontact.surfaces); unchanged without a surface."""
    if roughness is not None and roughness.surface is None and roughness.surface_cutoff is not None:
        problems.append(
            f"roughness.surface_cutoff = {roughness.surface_cutoff!r}: no roughness.surface to apply it to; "
            f"allowed: 'auto' without a surface"
        )
        return None
    if roughness is None or roughness.surface is None:  # the directory serves later overrides
        return roughness if roughness is None else replace(roughness, directory=directory)
    given = [k for k in SURFACE_SETS if k in (raw or {})]
    if given:
        problems.extend(
            f"roughness.{k} = {raw[k]!r}: set by roughness.surface = {roughness.surface!r}; allowed: "
            f"leave out {', '.join(SURFACE_SETS)} when a surface is given" for k in given
        )
        return None
    from lubecontact.surfaces.measured import scene_roughness
    from lubecontact.surfaces.reading import SizeNotGiven, SurfaceError

    try:
        params, digest = scene_roughness(Path(directory) / roughness.surface, roughness.surface_cutoff)
    except SizeNotGiven as err:  # its words are the command line's (--size), which a scene has not
        problems.append(
            f"roughness.surface = {roughness.surface!r}: {err.what}, and a scene cannot give a file "
            f"its size or unit; allowed: an instrument file, or for a raw height matrix the roughness section that `lubecontact "
            f"roughness FILE --size LX [LY] --unit U --out section.yaml` writes, in place of roughness.surface"
        )
        return None
    except SurfaceError as err:
        problems.append(
            f"roughness.surface = {roughness.surface!r}: {err}; allowed: a surface file with its size and unit "
            f"(an instrument format; check it with lubecontact roughness), relative to {directory}"
        )
        return None
    values = dict(zip(SURFACE_SETS, (params.sigma, params.asperity_density, params.asperity_radius)))
    return replace(roughness, **values, surface_sha256=digest, directory=directory)


# The lubricant's datasheet: all of these, or none (docs/physics.md section 19).
DATASHEET_KEYS = ("lubricant.kinematic_viscosity_40", "lubricant.kinematic_viscosity_100", "lubricant.density",
                  "operating.temperature")
DATASHEET_ALLOWED = (
    "all of " + ", ".join(DATASHEET_KEYS) + " (lubricant.viscosity is then derived from them), or none of them"
)


def _datasheet_value(sections: dict, key: str):
    section, _, name = key.partition(".")
    return getattr(sections[section], name)


def _at_temperature(sections: dict, raw, problems: list[str]):
    """The lubricant section with its viscosity from the datasheet at operating.temperature
    (ASTM D341 and the API density law, docs/physics.md section 19); unchanged without a
    datasheet. A partial datasheet, a viscosity given as well, an oil that thickens as it
    warms, a temperature at or below the pour point or a result outside D341 are refused."""
    lubricant, operating = sections["lubricant"], sections["operating"]
    if lubricant is None or operating is None:
        return lubricant
    given = {k: _datasheet_value(sections, k) for k in DATASHEET_KEYS if _datasheet_value(sections, k) is not None}
    if not given:
        if lubricant.pour_point is not None:
            problems.append(f"lubricant.pour_point = {lubricant.pour_point!r}: no operating.temperature to check; "
                            f"allowed: with {DATASHEET_ALLOWED}")
            return None
        return lubricant
    missing = [k for k in DATASHEET_KEYS if k not in given]
    if missing:
        grade = (" (an ISO VG grade, ISO 3448, fixes only the 40 C viscosity, within 10 %: the 100 C value "
                 "from the datasheet gives the slope)") if "lubricant.kinematic_viscosity_100" in missing else ""
        problems.append(
            f"{', '.join(f'{k} = {v!r}' for k, v in given.items())}: the datasheet lacks {', '.join(missing)}"
            f"{grade}; allowed: {DATASHEET_ALLOWED}"
        )
        return None
    if isinstance(raw, Mapping) and "viscosity" in raw:
        problems.append(f"lubricant.viscosity = {raw['viscosity']!r}: derived from the datasheet; allowed: leave out "
                        f"lubricant.viscosity when the datasheet is given ({DATASHEET_ALLOWED})")
        return None
    nu_40, nu_100, temperature = lubricant.kinematic_viscosity_40, lubricant.kinematic_viscosity_100, operating.temperature
    if nu_100 >= nu_40:
        problems.append(f"lubricant.kinematic_viscosity_100 = {nu_100!r}: not below lubricant.kinematic_viscosity_40 = "
                        f"{nu_40!r}; allowed: < kinematic_viscosity_40 (an oil thins as it warms)")
        return None
    if lubricant.pour_point is not None and temperature <= lubricant.pour_point:
        problems.append(f"operating.temperature = {temperature!r}: at or below lubricant.pour_point = "
                        f"{lubricant.pour_point!r}; allowed: above the pour point (ASTM D341 holds for a homogeneous "
                        f"liquid only)")
        return None
    viscosity_rule = dict(Lubricant.rules())["viscosity"]
    too_viscous = (f"operating.temperature = {temperature!r}: the oil of this datasheet is too viscous there; allowed: "
                   f"a temperature where the derived lubricant.viscosity is {viscosity_rule.allowed}")
    try:
        nu = WaltherLine.of_datasheet(nu_40, nu_100).kinematic_viscosity(temperature)
    except OverflowError:
        problems.append(too_viscous)
        return None
    if nu < D341_LOWEST_VISCOSITY:
        problems.append(
            f"operating.temperature = {temperature!r}: the datasheet gives a kinematic viscosity of {nu:.3g} mm^2/s "
            f"there; allowed: a temperature where it is >= {D341_LOWEST_VISCOSITY} mm^2/s (ASTM D341's equations)"
        )
        return None
    try:  # only the upper bound can fail here
        viscosity = viscosity_rule(density(lubricant.density, temperature) * nu * 1e-6)
    except _Invalid:
        problems.append(too_viscous)
        return None
    return replace(lubricant, viscosity=viscosity)


def _rheology_problems(lubricant, effects) -> list[str]:
    """The yield-stress keys (docs/physics.md section 21) that do not fit together."""
    if lubricant is None:
        return []
    law, problems = lubricant.rheology, []
    if law == "newtonian":
        problems += [
            f"lubricant.{key} = {getattr(lubricant, key)!r}: a key of a yield-stress grease; allowed: only with "
            f"lubricant.rheology 'bingham' or 'herschel_bulkley' (got 'newtonian')"
            for key in RHEOLOGY_KEYS[1:] if getattr(lubricant, key) != getattr(Lubricant, key)
        ]
        return problems
    if lubricant.yield_stress == 0.0:
        problems.append(
            f"lubricant.yield_stress = 0.0 with lubricant.rheology = {law!r}: without a yield stress Bingham is the "
            f"Newtonian law, and Herschel-Bulkley a power law whose flux is singular at rest; allowed: > 0 Pa"
        )
    if law == "bingham" and lubricant.flow_index != 1.0:
        problems.append(f"lubricant.flow_index = {lubricant.flow_index!r}: Bingham's is 1; allowed: only with "
                        f"lubricant.rheology 'herschel_bulkley'")
    if law == "bingham" and lubricant.creep_viscosity <= lubricant.viscosity:
        problems.append(
            f"lubricant.creep_viscosity = {lubricant.creep_viscosity!r}: not above lubricant.viscosity = "
            f"{lubricant.viscosity!r}, so the grease would flow faster below its yield stress than above; allowed: "
            f"> lubricant.viscosity"
        )
    if effects is not None and effects.cavitation == "jfo":
        problems.append(
            f"effects.cavitation = 'jfo' with lubricant.rheology = {law!r}: the one Newton's mass-conserving "
            f"cavitation carries a Newtonian film's Couette flux, not yet a grease's; allowed: 'reynolds' or 'none'"
        )
    return problems


def _cross_problems(s: dict) -> list[str]:
    """Rules between keys; each runs only if its sections are valid."""
    problems = []
    geometry, roughness, effects, operating = (s.get(k) for k in ("geometry", "roughness", "effects", "operating"))
    if geometry is not None and roughness is not None and roughness.sigma > geometry.radius / 100:
        problems.append(
            f"roughness.sigma = {roughness.sigma!r}: too large against the cylinder; allowed: "
            f"<= geometry.radius/100 = {geometry.radius / 100:g} m"
        )
    if geometry is not None and geometry.crown_radius is not None:
        if geometry.crown_radius <= geometry.length / 2:
            problems.append(f"geometry.crown_radius = {geometry.crown_radius!r}: the crown's circle must span the "
                            f"cylinder; allowed: > geometry.length/2 = {geometry.length / 2:g} m")
        mesh = s.get("mesh")
        if mesh is not None and mesh.ny == 1:
            problems.append("geometry.crown_radius with mesh.ny = 1: a line contact has one row standing for the "
                            "whole length, with no axis to crown; allowed: mesh.ny > 1, or no crown_radius")
    if roughness is not None and roughness.height_std == "mccool":
        eta_r = roughness.asperity_density * roughness.asperity_radius
        variance = roughness.sigma**2 - MCCOOL_VARIANCE_CONSTANT / eta_r**2
        if variance <= 0:
            problems.append(
                f"roughness.height_std = 'mccool': McCool's sigma_s^2 = sigma^2 - 3.717e-4/(eta R_peak)^2 = "
                f"{variance:.3g} m^2 is not positive; allowed: 'mccool' only when roughness.sigma > "
                f"{math.sqrt(MCCOOL_VARIANCE_CONSTANT) / eta_r:.3g} m, else 'sigma'"
            )
    problems.extend(_rheology_problems(s.get("lubricant"), effects))
    motion = s.get("motion")
    if motion is not None and motion.kind == "table" and motion.table is None:
        problems.append("motion.kind = 'table': motion.table is missing; allowed: rows [t (s), U (m/s)] or a file")
    if effects is not None and operating is not None and not effects.asperity_contact:
        if not effects.hydrodynamics or operating.speed == 0:
            problems.append(
                f"effects.asperity_contact = False: nothing carries the load: smooth surfaces need a fluid "
                f"film, i.e. effects.hydrodynamics = true (got {effects.hydrodynamics}) and "
                f"operating.speed > 0 (got {operating.speed!r}); allowed: enable asperity_contact"
            )
    return problems


def load_scene(path_or_mapping, overrides: Mapping | None = None) -> Scene:
    """Read, complete (Table 1 defaults), override and validate a scene.

    ``path_or_mapping``: a YAML file path, a mapping of sections, or a Scene.
    ``overrides``: dotted keys to values, e.g. ``{"roughness.sigma": "1e-6"}``; a string
    value is read as YAML first, a section name takes a whole section (``effects=auto``).
    Raises SceneError listing every problem.
    """
    raw, origin = _read(path_or_mapping)
    _bounded(raw, origin)
    _bounded(dict(overrides or {}), "overrides")
    problems: list[str] = []
    replaced = _datasheet_replaces(_surface_replaces(raw, overrides or {}), overrides or {})
    raw = _apply_overrides(replaced, overrides or {}, problems)
    if not isinstance(raw, Mapping):
        raise SceneError(origin, problems + [f"{raw!r}: a scene is a mapping of sections {', '.join(SECTIONS)}"])
    problems.extend(_unknown_key(str(k)) for k in raw if k not in SECTIONS)
    directory = _directory(path_or_mapping)
    raw = _table_beside_scene(raw, directory)
    sections = {name: _build_section(name, raw.get(name), problems) for name in SECTIONS}
    sections["motion"] = _with_table_file(sections["motion"], raw.get("motion"))
    sections["roughness"] = _measured(sections["roughness"], raw.get("roughness"), directory, problems)
    sections["lubricant"] = _at_temperature(sections, raw.get("lubricant"), problems)
    problems.extend(_cross_problems(sections))
    if problems:
        raise SceneError(origin, problems)
    scene = Scene(**sections)
    problems.extend(mesh_problems(scene))
    if problems:
        raise SceneError(origin, problems)
    return scene


def parse_override(text: str) -> tuple[str, object]:
    """'key=value' (CLI --set) -> (key, value read as YAML)."""
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not key:
        raise SceneError("override", [f"{text!r}: expected key=value, e.g. roughness.sigma=1e-6"])
    try:
        return key, _yaml_value(value)
    except yaml.YAMLError as err:
        raise SceneError("override", [f"{key} = {value!r}: not a valid YAML value ({err})"]) from err
