"""lubecontact: lubricated, sliding, rough electrical contacts (after Jackson & Angadi 2022).

Public surface (see DESIGN.md): ``load_scene``, ``solve``, ``sweep``, ``rough_contact``, ``transient``.
"""

__all__ = ["__version__", "load_scene", "solve", "sweep", "rough_contact", "SceneError", "transient"]


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("lubecontact")
    except PackageNotFoundError:  # running from a source tree that is not installed
        return "0+unknown"


def __getattr__(name):
    # Lazy imports keep `import lubecontact` (and the CLI's --help) fast: scipy and xarray
    # load only when a solver piece is used, importlib.metadata only for __version__.
    if name == "__version__":
        value = globals()["__version__"] = _version()  # looked up once
        return value
    if name in ("load_scene", "SceneError", "Scene"):
        from . import scene

        return getattr(scene, name)
    if name == "solve":
        from .solver import solve

        return solve
    if name == "sweep":
        from .speed_sweep import sweep

        return sweep
    if name == "rough_contact":
        from .rough_surface import rough_contact

        return rough_contact
    if name == "transient":
        from .unsteady import transient

        return transient
    raise AttributeError(f"module 'lubecontact' has no attribute {name!r}")
