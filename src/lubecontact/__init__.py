"""lubecontact: lubricated, sliding, rough electrical contacts (after Jackson & Angadi 2022).

Public surface (docs/DESIGN.md): ``load_scene``, ``solve``, ``sweep``, ``rough_contact``, ``transient``.
"""

__all__ = ["__version__", "load_scene", "solve", "sweep", "rough_contact", "SceneError", "transient"]


def __getattr__(name):
    # Lazy imports keep `import lubecontact` (and the CLI's --help) fast: scipy and xarray
    # load only when a solver piece is used (0.4-0.6 s), importlib.metadata only for
    # __version__ (tests/test_startup.py holds `import lubecontact` and load_scene to that).
    if name == "__version__":
        from lubecontact.io.version import package_version

        value = globals()["__version__"] = package_version()  # looked up once
        return value
    if name in ("load_scene", "SceneError", "Scene"):
        from lubecontact import scene

        return getattr(scene, name)
    if name == "solve":
        from lubecontact.model.solve import solve

        return solve
    if name == "sweep":
        from lubecontact.studies.sweep import sweep

        return sweep
    if name == "rough_contact":
        from lubecontact.physics.rough_surface import rough_contact

        return rough_contact
    if name == "transient":
        from lubecontact.unsteady.transient import transient

        return transient
    raise AttributeError(f"module 'lubecontact' has no attribute {name!r}")
