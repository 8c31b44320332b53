"""The package's layers (docs/DESIGN.md "Layout"): each folder imports only from the folders
before it, no module imports another's private names, and imports sit at the top of a
module except the lazy ones listed here with their measured reason."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "lubecontact"
# Lowest first. A module may import from its own layer and the layers before it.
LAYERS = ["io", "surfaces", "physics", "numerics", "scene", "model", "unsteady", "studies", "plotting", "cli"]
# Imports inside functions that start-up time needs (importing module, imported module).
LAZY = {
    # load_scene stays free of importlib.metadata and SurfaceTopography (tests/test_startup.py)
    ("scene/scene.py", "lubecontact.surfaces.measured"): "importlib.metadata at load_scene",
    ("scene/scene.py", "lubecontact.surfaces.reading"): "as above",
    # scipy.optimize costs 0.14 s on top of scipy.sparse.linalg in every solve process
    ("model/auto_effects.py", "scipy.optimize"): "only effects: auto needs it",
    ("physics/inlet.py", "scipy.optimize"): "only a short inlet needs it",
    ("physics/yield_stress_flow.py", "scipy.optimize"): "only a grease's flowing viscosity needs it",
    # a solve job and `lubecontact solve` write with netCDF4 and never load xarray (0.3-0.4 s)
    ("physics/rough_surface.py", "xarray"): "only the rough_contact API returns a Dataset",
    ("io/case_result.py", "xarray"): "only solve() returns a Dataset",
    # tqdm costs 25 ms and is shown only on a terminal
    ("studies/sweep.py", "tqdm.auto"): "progress bar",
    ("unsteady/integrator.py", "tqdm.auto"): "progress bar",
    ("model/resources.py", "tqdm.auto"): "progress bar",
    # instrument formats only: a plain text surface needs none of it
    ("surfaces/reading.py", "SurfaceTopography"): "instrument files",
}


def modules():
    return sorted(p for p in PACKAGE.rglob("*.py"))


def layer(name: str) -> int | None:
    """Layer index of a dotted module below lubecontact (None: the package's own __init__)."""
    top = name.split(".")[0]
    return LAYERS.index(top) if top in LAYERS else None


def own_imports(path: Path):
    """(node, imported module below lubecontact, imported names) of each import of the package."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("lubecontact"):
            assert node.level == 0, f"{path}: relative import"
            yield node, node.module.removeprefix("lubecontact").lstrip("."), [a.name for a in node.names]


def test_every_module_sits_in_a_layer():
    loose = [p.name for p in PACKAGE.glob("*.py") if p.name != "__init__.py"]
    assert loose == []
    folders = sorted(p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__")
    assert folders == sorted(LAYERS)


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_imports_go_down_the_layers(path):
    rel = path.relative_to(PACKAGE)
    if rel.parts == ("__init__.py",):
        return  # the public surface re-exports from every layer, lazily
    own = LAYERS.index(rel.parts[0])
    for node, module, names in own_imports(path):
        targets = [f"{module}.{n}" if module in ("", *LAYERS) else module for n in names]
        for target in targets:
            assert layer(target) is not None, f"{rel}:{node.lineno} imports the package root ({target})"
            assert layer(target) <= own, f"{rel}:{node.lineno} imports {target} from a higher layer"


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_private_names_across_modules(path):
    for node, module, names in own_imports(path):
        private = [n for n in names if n.startswith("_")]
        assert not private, f"{path.relative_to(PACKAGE)}:{node.lineno} imports {private} from {module}"


@pytest.mark.parametrize("path", modules(), ids=lambda p: str(p.relative_to(PACKAGE)))
def test_imports_at_the_top(path):
    rel = path.relative_to(PACKAGE)
    if path.name == "__init__.py" or rel.parts[0] == "cli":
        return  # lazy public surface; the CLI imports each command's modules when it runs
    tree = ast.parse(path.read_text())
    top = {id(n) for n in tree.body}
    for n in tree.body:
        if isinstance(n, (ast.If, ast.Try)):  # TYPE_CHECKING blocks
            top |= {id(m) for m in ast.walk(n)}
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)) and id(node) not in top:
            module = node.module if isinstance(node, ast.ImportFrom) else node.names[0].name
            assert (str(rel), module) in LAZY, f"{rel}:{node.lineno} imports {module} inside a function"


def test_the_lazy_list_is_current():
    """Each listed lazy import still exists (a stale entry would hide a new one)."""
    found = set()
    for path in modules():
        tree = ast.parse(path.read_text())
        top = {id(n) for n in tree.body}
        for node in ast.walk(tree):
            if isinstance(node, (ast.Import, ast.ImportFrom)) and id(node) not in top:
                module = node.module if isinstance(node, ast.ImportFrom) else node.names[0].name
                found.add((str(path.relative_to(PACKAGE)), module))
    assert set(LAZY) <= found
