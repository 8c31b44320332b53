"""Parameter grids of the paper's figures (Figs. 3-11) -> scenes -> cases -> one Dataset.

A figure grid (``config/figures/figNN.yaml``) names a base scene, fixed dotted-key
overrides (``set``), swept parameters (``sweep``) and the sliding speeds (``speeds``).
Every point of the grid is a scene; its content hash (``Scene.hash``) is the case id, so a
case shared by several figures (the Table 1 baseline curve) is one case, solved once, and
changing one value of one grid creates only the cases that value touches.

``sweep`` maps either a dotted scene key to its values (a dimension named after the key's
last part: ``roughness.sigma`` -> ``sigma``), or a dimension name to several keys varied
together (``mesh: {mesh.nx: [...], mesh.ny: [...]}``). Speeds are always the last
dimension, ``speed``.

This module is library code: it knows nothing of Snakemake. The workflow (``Snakefile``,
``workflow/rules/*.smk``) calls ``figure_spec``, ``expand``, ``plan_chunks`` and
``collect``; everything it hands to Snakemake is plain Python (str, int, float, list, dict).
"""

from __future__ import annotations

import ast
import hashlib
import math
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
import yaml

from lubecontact.numerics.mesh import nodes_x
from lubecontact.scene.scene import SceneError, load_scene

# Keys of a figure YAML that define its cases (``grid: figXX`` borrows exactly these).
GRID_KEYS = ("scene", "set", "sweep", "speeds", "max_nodes")
SPEED_KEY = "operating.speed"
# ``max_nodes`` leaves out the values of a swept dimension that sets these (fine meshes).
MESH_KEYS = {"mesh.nx", "mesh.ny"}
# Scene values the figures normalise by (Stribeck U/F, Hersey mu U/F): every collected
# Dataset carries them as coordinates, along their dimension when swept, else as scalars.
RECORDED_KEYS = ("operating.force", "lubricant.viscosity")
# Scene units (lubecontact.scene) -> CF/UDUNITS spelling used in the netCDF files.
CF_UNITS = {"m/s": "m s-1", "1/m^2": "m-2", "Ohm m": "ohm m", "mm^2/s": "mm2 s-1", "kg/m^3": "kg m-3"}


class GridError(ValueError):
    """A figure grid that cannot be expanded; the message names the figure and the key."""


# --- reading -------------------------------------------------------------------------------


class _Yaml12Loader(yaml.SafeLoader):
    """SafeLoader reading YAML 1.2 floats: ``1e-6`` (no dot) is a number, not text."""


_Yaml12Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:\d+\.?\d*|\.\d+)[eE][-+]?\d+$"),
    list("-+0123456789."),
)


def read_yaml(path) -> object:
    with open(path) as stream:
        return yaml.load(stream, Loader=_Yaml12Loader)


def merge(base: Mapping, override: Mapping) -> dict:
    """Deep merge: mappings merge key by key, anything else in ``override`` replaces."""
    out = dict(base)
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
            out[key] = merge(out[key], value)
        else:
            out[key] = value
    return out


def figure_spec(figure: str, figure_dir, overrides: Mapping | None = None) -> dict:
    """The figure's YAML deep-merged with ``overrides[figure]`` (the workflow config).

    ``grid: figXX`` makes the figure plot the cases of figXX: its grid keys are taken from
    figXX, itself resolved the same way (so an override of figXX reaches both figures).
    With ``also_set`` (dotted keys) those overrides are added to figXX's ``set``: the same
    grid with, e.g., other effects, as new cases.
    """
    return _resolve(figure, Path(figure_dir), overrides or {}, ())


def _resolve(figure: str, figure_dir: Path, overrides: Mapping, referrers: tuple) -> dict:
    path = figure_dir / f"{figure}.yaml"
    if not path.is_file():
        raise GridError(f"{figure}: no grid file {path}")
    raw = read_yaml(path) or {}
    if not isinstance(raw, Mapping):
        raise GridError(f"{path}: a figure grid is a mapping, got {type(raw).__name__}")
    spec = merge(raw, overrides.get(figure) or {})
    parent = spec.get("grid")
    if parent is not None:
        if parent in referrers + (figure,):
            raise GridError(f"{path}: 'grid: {parent}' refers back to itself")
        own = sorted(k for k in GRID_KEYS if k in spec)
        if own:
            raise GridError(f"{path}: 'grid: {parent}' borrows the grid of {parent}; remove {', '.join(own)}")
        borrowed = _resolve(parent, figure_dir, overrides, referrers + (figure,))
        spec.update({k: borrowed[k] for k in GRID_KEYS if k in borrowed})
        if spec.get("also_set"):  # the borrowed grid with more overrides: its own cases
            spec["set"] = {**(spec.get("set") or {}), **spec["also_set"]}
    return spec


def log_speeds(start: float, stop: float, per_decade: int, digits: int = 3) -> list[float]:
    """Log-spaced speeds from ``start`` to ``stop`` (both included when they fall on the
    ladder 10^(k/per_decade)), rounded to ``digits`` significant digits."""
    lo, hi = math.log10(float(start)), math.log10(float(stop))
    k0, k1 = math.ceil(lo * per_decade - 1e-9), math.floor(hi * per_decade + 1e-9)
    return [float(f"{10.0 ** (k / per_decade):.{digits - 1}e}") for k in range(k0, k1 + 1)]


def speeds_of(spec: Mapping, where: str) -> list:
    speeds = spec.get("speeds")
    if isinstance(speeds, Mapping):
        return log_speeds(speeds["from"], speeds["to"], speeds["per_decade"])
    if isinstance(speeds, Sequence) and not isinstance(speeds, str) and speeds:
        return list(speeds)
    raise GridError(f"{where}: speeds must be a non-empty list or {{from, to, per_decade}}, got {speeds!r}")


# --- scene keys: units and meaning ------------------------------------------------------------


def key_value(scene, key: str):
    """The value of a dotted key in a validated scene (typed: float, int, str, bool)."""
    section, _, name = key.partition(".")
    return getattr(getattr(scene, section), name)


def key_attrs(scene, key: str) -> dict:
    """CF attrs (units, long_name) of a dotted scene key, from the scene's own schema."""
    section, _, name = key.partition(".")
    (field,) = [f for f in fields(getattr(scene, section)) if f.name == name]
    rule = field.metadata["rule"]
    unit = getattr(rule, "unit", None) or getattr(getattr(rule, "inner", None), "unit", None) or "1"
    return {"units": CF_UNITS.get(unit, unit), "long_name": field.metadata["doc"], "scene_key": key}


# --- expansion -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Dim:
    """One dimension of a figure's grid: ``keys`` set together, ``values[i]`` at position i."""

    name: str
    keys: tuple[str, ...]
    values: tuple[tuple, ...]

    def coord_names(self) -> tuple[str, ...]:
        """Coordinate name of each key: the dimension's own name for a single key."""
        return (self.name,) if len(self.keys) == 1 else tuple(k.rsplit(".", 1)[1] for k in self.keys)


@dataclass(frozen=True)
class CaseSpec:
    """One case: its id (scene hash), how to rebuild its scene (load_scene(scene, set)) and
    its mesh size (nodes, for a job's resource estimate)."""

    id: str
    scene: str
    set: dict
    nodes: int

    def plain(self) -> dict:
        return {"id": self.id, "scene": self.scene, "set": dict(self.set)}


@dataclass
class FigureGrid:
    figure: str
    spec: dict
    base: object  # Scene: base scene file + the figure's fixed overrides
    dims: tuple[Dim, ...]  # swept dimensions, then speed
    cases: np.ndarray  # CaseSpec per grid point, shape = sizes of dims

    @property
    def shape(self) -> tuple[int, ...]:
        return self.cases.shape

    def curves(self) -> Iterator[tuple[tuple[int, ...], list[CaseSpec]]]:
        """(index over the swept dims, the cases along speed) for every curve."""
        for index in np.ndindex(self.shape[:-1]):
            yield index, list(self.cases[index])

    def unique_cases(self) -> dict[str, CaseSpec]:
        return {c.id: c for c in self.cases.flat}

    def layout(self) -> dict:
        """Everything ``collect`` needs, as plain Python (safe for Snakemake params)."""
        recorded = {}
        for key in RECORDED_KEYS:
            name = key.rsplit(".", 1)[1]
            if not any(key in d.keys for d in self.dims):
                recorded[name] = {"value": key_value(self.base, key), "attrs": key_attrs(self.base, key)}
        return {
            "figure": self.figure,
            "dims": [
                {
                    "name": d.name,
                    "coords": [
                        {"name": c, "values": [v[i] for v in d.values], "attrs": key_attrs(self.base, k)}
                        for i, (c, k) in enumerate(zip(d.coord_names(), d.keys))
                    ],
                }
                for d in self.dims
            ],
            "recorded": recorded,
            "case_ids": np.vectorize(lambda c: c.id, otypes=[object])(self.cases).tolist(),
            "base_scene": self.base.canonical_yaml(),
            "grid": yaml.safe_dump({k: self.spec[k] for k in GRID_KEYS if k in self.spec}, sort_keys=False),
        }


def missing_comparisons(specs: Mapping[str, Mapping]) -> list[str]:
    """One message per figure whose ``compare: figXX`` is not among ``specs`` (the config's
    figures): its plot job would fail on a dataset nothing builds."""
    return [f"{name} draws {spec['compare']} beside it (compare: {spec['compare']}), which is not among the "
            f"figures: add {spec['compare']} to the config's figures, or drop {name}"
            for name, spec in specs.items() if spec.get("compare") and spec["compare"] not in specs]


def expand_all(specs: Mapping[str, Mapping], root=".") -> dict[str, FigureGrid]:
    """``expand`` for several figures; figures with the same grid keys (``grid: figXX``)
    share one expansion."""
    grids: dict[str, FigureGrid] = {}
    done: dict[str, FigureGrid] = {}
    for figure, spec in specs.items():
        key = yaml.safe_dump({k: spec.get(k) for k in GRID_KEYS})
        if key not in done:
            done[key] = expand(figure, spec, root)
        shared = done[key]
        grids[figure] = FigureGrid(figure, dict(spec), shared.base, shared.dims, shared.cases)
    return grids


def _sweep_dims(sweep: Mapping, where: str) -> list[tuple[str, tuple[str, ...], list[tuple]]]:
    """(name, keys, raw entries) per dimension from the YAML ``sweep`` mapping."""
    dims = []
    for name, entry in (sweep or {}).items():
        if isinstance(entry, Mapping):  # several keys varied together
            keys = tuple(entry)
            columns = [entry[k] for k in keys]
        else:
            keys, columns, name = (name,), [entry], name.rsplit(".", 1)[1]
        lengths = {len(c) if isinstance(c, Sequence) and not isinstance(c, str) else -1 for c in columns}
        if len(lengths) != 1 or min(lengths) < 1:
            raise GridError(f"{where}: sweep {name}: every key needs a non-empty list of values, all of one length")
        dims.append((name, keys, list(zip(*columns))))
    return dims


def _scene(base, overrides: Mapping, where: str):
    try:
        return load_scene(base, overrides)
    except SceneError as err:
        raise GridError(f"{where}: {err}") from err


def expand(figure: str, spec: Mapping, root=".") -> FigureGrid:
    """All cases of one figure grid, each scene validated now (a bad value fails here,
    before anything runs, with the figure, the key and the value in the message)."""
    where = f"figure {figure}"
    if "scene" not in spec:
        raise GridError(f"{where}: no base scene (key 'scene')")
    scene_path = str(spec["scene"])
    fixed = dict(spec.get("set") or {})
    raw_dims = _sweep_dims(spec.get("sweep"), where)
    swept = [k for _, keys, _ in raw_dims for k in keys]
    every = swept + list(fixed) + [SPEED_KEY]
    clashes = sorted({k for k in every if every.count(k) > 1})
    if clashes:
        raise GridError(f"{where}: {', '.join(clashes)} set twice (sweep, set and speeds must not overlap)")
    # Names in the collected Dataset: dimensions, the coordinates of keys varied together,
    # the recorded scalars; each must be unique.
    names = ["speed"] + [k.rsplit(".", 1)[1] for k in RECORDED_KEYS if k not in swept]
    for name, keys, _ in raw_dims:
        names += [name] + ([k.rsplit(".", 1)[1] for k in keys] if len(keys) > 1 else [])
    doubled = sorted({n for n in names if names.count(n) > 1})
    if doubled:
        raise GridError(f"{where}: name {', '.join(doubled)} used twice in the figure's Dataset; rename the sweep entry")

    base = _scene(Path(root) / scene_path, fixed, f"{where}, scene {scene_path} with set {fixed}")
    max_nodes = spec.get("max_nodes")
    dims = []
    for name, keys, entries in raw_dims + [("speed", (SPEED_KEY,), [(s,) for s in speeds_of(spec, where)])]:
        typed = []
        for entry in entries:
            point = dict(zip(keys, entry))
            scene = _scene(base, point, f"{where}, {name} = {point}")
            if max_nodes is not None and MESH_KEYS & set(keys) and scene.mesh.nx * scene.mesh.ny > max_nodes:
                continue
            typed.append(tuple(key_value(scene, k) for k in keys))
        if not typed:
            raise GridError(f"{where}: no value of {name} is left (max_nodes = {max_nodes})")
        if len(set(typed)) != len(typed):
            raise GridError(f"{where}: {name} lists a value twice: {typed}")
        dims.append(Dim(name, keys, tuple(typed)))

    cases = np.empty(tuple(len(d.values) for d in dims), dtype=object)
    for index in np.ndindex(cases.shape):
        point = {k: v for d, i in zip(dims, index) for k, v in zip(d.keys, d.values[i])}
        scene = _scene(base, point, f"{where}, point {point}")
        cases[index] = CaseSpec(scene.hash, scene_path, {**fixed, **point}, nodes_x(scene) * scene.mesh.ny)
    return FigureGrid(figure, dict(spec), base, tuple(dims), cases)


# --- jobs ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Chunk:
    """The cases one job solves, one after the other, each from a cold start (the answers
    do not depend on the chunking). ``name`` = claiming figure + hash of the member ids."""

    name: str
    cases: tuple[CaseSpec, ...]


def plan_chunks(grids: Iterable[FigureGrid], cases_per_job: int | None = None) -> list[Chunk]:
    """Every unique case in exactly one chunk.

    A case belongs to the first grid (in the order given) that has it. Each curve's cases
    that are its own, in speed order, form one chunk (``cases_per_job`` None) or chunks of
    at most ``cases_per_job``. A chunk's name, ``<figure>_<swept values>_<digest>``, says
    which curve it solves and changes only when its members do.
    """
    if cases_per_job is not None and cases_per_job < 1:
        raise GridError(f"cases_per_job must be >= 1 or 'curve', got {cases_per_job}")
    claimed: set[str] = set()
    chunks = []
    for grid in grids:
        for index, curve in grid.curves():
            own = []
            for case in curve:
                if case.id not in claimed:
                    claimed.add(case.id)
                    own.append(case)
            size = cases_per_job or len(own) or 1
            for start in range(0, len(own), size):
                members = tuple(own[start : start + size])
                digest = hashlib.sha256("\n".join(c.id for c in members).encode()).hexdigest()[:CHUNK_DIGEST]
                readable = f"{grid.figure}_{_curve_label(grid, index)}"[: CHUNK_NAME - CHUNK_DIGEST - 1]
                chunks.append(Chunk(f"{readable.rstrip('_')}_{digest}", members))
    return chunks


# Chunk names become rule names (solve_<name>), and Snakemake names a SLURM bundle's job
# script after its first five rule names plus a uuid: a file name, at most 255 bytes. With
# names of at most 33 characters (solve_ 6 + figure and curve label, cut to 20, + _ 1 +
# digest 6) that file name stays below 250 bytes; longer names made every bundle fail to
# submit.
CHUNK_NAME = 27
CHUNK_DIGEST = 6


def value_text(value) -> str:
    """A swept value as text: numbers in %g form, anything else (a surface file) as it is."""
    return f"{value:g}" if isinstance(value, float) else str(value)


def _curve_label(grid, index) -> str:
    """'sigma_5e_07_' for the curve at ``index`` of the swept dims: readable rule and log
    names (cut with the figure id to CHUNK_NAME - CHUNK_DIGEST - 1 characters)."""
    words = [
        f"{dim.name}_" + "_".join(value_text(v) for v in dim.values[i])
        for dim, i in zip(grid.dims[:-1], index)
    ]
    label = re.sub(r"[^0-9A-Za-z]+", "_", "_".join(words)).strip("_")
    return f"{label}_" if label else ""


# --- which code decides a case -----------------------------------------------------------------

# A case's result is decided by the solver and by the scene (validation, canonical form).
# The modules whose imports decide a case: the steady solve and the scene; the transient.
SOLVER_ROOTS = ("model.solve", "scene")
TRANSIENT_ROOTS = ("unsteady.transient", "scene")


def _imported_modules(tree: ast.AST, prefix: tuple[str, ...] = ()) -> Iterator[str]:
    """Dotted names (below the package) of the package's own modules a module imports,
    relative or lubecontact.*; ``prefix``: the importing module's subpackage ("surfaces",)
    or () at the top. ``from .a import b`` yields "a" and "a.b" (b may be a module)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level == 0:
                if not module.startswith("lubecontact"):
                    continue
                base = module.split(".")[1:]
            elif node.level - 1 > len(prefix):
                continue
            else:
                base = list(prefix[: len(prefix) - (node.level - 1)]) + (module.split(".") if module else [])
            if base:
                yield ".".join(base)
            # from . import x: x is a module or a name of __init__
            yield from (".".join(base + [alias.name]) for alias in node.names)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("lubecontact."):
                    yield alias.name.split(".", 1)[1]


def solver_sources(package_dir, roots: Sequence[str] = SOLVER_ROOTS) -> list[Path]:
    """The package's source files that ``roots`` import (at the top or inside functions),
    directly or through each other, and ``__init__.py``: the files whose edits can change a
    case's result. ``__init__``'s own lazy re-exports (the public surface) are not followed,
    so the plotting, grid, sweep and CLI modules count only if the solver imports them.
    A module of a subpackage brings the subpackage's ``__init__.py`` (run on import)."""
    package_dir = Path(package_dir)
    todo, found = list(roots), {"__init__": package_dir / "__init__.py"}
    while todo:
        name = todo.pop()
        parts = name.split(".")
        module, package = package_dir.joinpath(*parts).with_suffix(".py"), package_dir.joinpath(*parts, "__init__.py")
        if name in found or not (module.is_file() or package.is_file()):
            continue
        found[name] = module if module.is_file() else package
        prefix = tuple(parts[:-1]) if module.is_file() else tuple(parts)
        todo.extend(".".join(parts[:k]) for k in range(1, len(parts)))  # parent packages run first
        todo.extend(_imported_modules(ast.parse(found[name].read_text(), filename=str(found[name])), prefix))
    return sorted(found.values())


def sources_fingerprint(paths: Iterable) -> str:
    """sha256 over the files' paths inside the package and their contents (not where the
    tree is, nor time stamps)."""
    digest = hashlib.sha256()
    for path in sorted(Path(p) for p in paths):
        inside = path.parts[len(path.parts) - path.parts[::-1].index("lubecontact"):] if "lubecontact" in path.parts else (path.name,)
        digest.update("/".join(inside).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


# --- collect -----------------------------------------------------------------------------------
