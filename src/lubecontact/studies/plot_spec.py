"""What a figure's ``plot:`` section may name, checked when the workflow plans the figure
(workflow/rules/cases.smk), not when it draws it: a misspelt variable, a legend placeholder
or a display unit failed only in the plot job, after every solve, and the failed job took
the previous figure with it (plotting/figures.py draws what this allows).
"""

from __future__ import annotations

import string

from lubecontact.io.case_schema import SCALARS

# display unit in a legend or on a map axis -> (CF units of the coordinate, size of one
# display unit in them)
DISPLAY_UNITS = {
    "m": ("m", 1.0),
    "mm": ("m", 1e-3),
    "\u00b5m": ("m", 1e-6),
    "um": ("m", 1e-6),
    "nm": ("m", 1e-9),
    "N": ("N", 1.0),
    "mN": ("N", 1e-3),
    "Pa s": ("Pa s", 1.0),
    "mPa s": ("Pa s", 1e-3),
    "m/s": ("m s-1", 1.0),
}


def plot_problems(grid) -> list[str]:
    """Why the ``plot:`` section of ``grid`` (studies/figure_grids.FigureGrid) cannot be
    drawn, one message per problem naming the figure and the key: ``y`` must be a variable
    of the figure's dataset, ``legend.label``'s {placeholders}, ``legend.units``' keys and
    ``map`` must be its swept coordinates, every display unit one of DISPLAY_UNITS, and a
    speed of 0 needs a linear speed axis."""
    plot, where = grid.spec.get("plot") or {}, f"figure {grid.figure}, plot"
    swept = [name for dim in grid.dims[:-1] for name in dict.fromkeys((dim.name, *dim.coord_names()))]
    problems = []
    if plot.get("y") not in SCALARS:
        problems.append(f"{where}.y = {plot.get('y')!r}: not a variable of the figure's dataset; allowed: "
                        f"{', '.join(SCALARS)}")
    legend = plot.get("legend") or {}
    named = [field for _, field, _, _ in string.Formatter().parse(legend.get("label") or "") if field is not None]
    problems += [f"{where}.legend.label names {{{field}}}: not a swept coordinate; allowed: {', '.join(swept) or 'none'}"
                 for field in named if field not in swept]
    for section, units in (("legend.units", legend.get("units") or {}), ("units", plot.get("units") or {})):
        for coord, unit in units.items():
            if coord not in swept:
                problems.append(f"{where}.{section}.{coord}: not a swept coordinate; allowed: {', '.join(swept) or 'none'}")
            if unit not in DISPLAY_UNITS:
                problems.append(f"{where}.{section}.{coord} = {unit!r}: allowed {', '.join(DISPLAY_UNITS)}")
    problems += [f"{where}.map names {name!r}: not a swept coordinate; allowed: {', '.join(swept)}"
                 for name in plot.get("map") or [] if name not in swept]
    at_rest = [values[0] for values in grid.dims[-1].values if values[0] == 0.0]
    if at_rest and plot.get("kind", "curves") == "curves" and plot.get("xscale", "log") == "log":
        problems.append(f"figure {grid.figure}, speeds: 0 m/s has no place on the logarithmic speed axis (it was "
                        "solved and left out of the figure without a word); drop it, or set plot.xscale: linear")
    return problems
