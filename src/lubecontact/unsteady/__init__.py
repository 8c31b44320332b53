"""Time (unsteady model): the lubricated contact after its motion changes (DESIGN.md Part II; physics.md 14-16).

motion.py (U(t) of the scene's ``motion:``), integrator.py (adaptive BDF2 with the squeeze
term in the Reynolds equation, a coupled solve per step), series.py (the Dataset along
``time``, reconnect_time, oscillation metrics), api.py (``transient(scene)``).
"""

__all__ = ["transient"]


def __getattr__(name):
    # Lazy, like the package's own __init__: the workflow plans its transient cases with
    # study.py at parse time, which needs neither the solver (scipy) nor xarray (~0.2 s).
    if name == "transient":
        from .api import transient

        return transient
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
