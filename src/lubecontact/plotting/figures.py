"""Figures 3-11 of Jackson & Angadi (2022) drawn from a collected figure Dataset.

The input is ``results/data/figNN.nc`` (``lubecontact.studies.collect``): a quantity over the
swept dimensions and ``speed``. One curve is drawn per combination of the swept
dimensions, in one panel per x quantity: the sliding speed U (Figs. 3-11), the Stribeck
normalisation U/F (Figs. 8-9) or the Hersey number mu U/F (Figs. 10-11).

Nothing is hidden: a point outside a sub-model's range gets a hollow marker for each kind of
breach its case raised (``validity_flags``, see :mod:`lubecontact.model.validity`; the legend
says each in words; data without the flags: a hollow circle where ``valid`` = 0); a point
that did not converge (``converged`` = 0) gets a red cross; a
point whose value is +inf (``contact_resistance`` of an open circuit) is drawn as a
triangle on the top edge of the panel, where the value leaves the axis. A NaN is an error.

Library code: uses matplotlib's object API (no pyplot state), reads no files.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import xarray as xr
import yaml
from matplotlib import colormaps
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from lubecontact.io.case_schema import VALIDITY_FLAGS
from lubecontact.model.validity import (
    GW_MAX_AREA_FRACTION,
    INLET_FILM_DEFICIT,
    LINE_YIELD_ONSET,
    MIN_BANDWIDTH,
    MIN_FLOW_FACTOR_FILM,
)
from lubecontact.studies.plot_spec import DISPLAY_UNITS

# x quantities: name -> (long_name, CF units, function of the figure Dataset)
X_QUANTITIES = {
    "speed": ("sliding speed U", "m s-1", lambda ds: ds["speed"]),
    "speed_per_force": ("Stribeck normalisation U/F", "m s-1 N-1", lambda ds: ds["speed"] / ds["force"]),
    "hersey": ("Hersey number \u03bcU/F", "m-1", lambda ds: ds["viscosity"] * ds["speed"] / ds["force"]),
}

# CF units -> how an axis label writes them
UNIT_LABELS = {
    "ohm": "\u03a9",
    "m s-1": "m/s",
    "m s-1 N-1": "m/(s N)",
    "m-1": "1/m",
    "m-2": "1/m\u00b2",
    "m2": "m\u00b2",
    "ohm m": "\u03a9 m",
    "degC": "\u00b0C",
    "1": "\u2013",
}

NOT_CONVERGED_STYLE = {"marker": "x", "color": "tab:red", "markersize": 8, "markeredgewidth": 1.6, "linestyle": "none"}
OPEN_STYLE = {"marker": "^", "markersize": 7, "linestyle": "none", "clip_on": False}
OUTSIDE_STYLE = {"marker": "o", "markersize": 5, "markerfacecolor": "white", "linestyle": "none"}
# each kind of breach its own hollow marker (the case's validity_flags), with what it means
FLAG_MARKERS = {"gw_area": "s", "area_capped": "D", "bulk_yield": "P", "bandwidth": "*", "flow_factor_range": "v",
                "inlet": "<"}
FLAG_LABELS = {
    "gw_area": f"A_r/A_n > {GW_MAX_AREA_FRACTION:g}: beyond GW's light contact",
    "area_capped": "A_r/A_n > 1 at a node: counted as full contact",
    "bulk_yield": f"pressure > {LINE_YIELD_ONSET:g} S_y: bulk yield (bodies modelled elastic)",
    "bandwidth": f"bandwidth α < {MIN_BANDWIDTH:g}: no Gaussian surface has these summits",
    "flow_factor_range": f"h/σ < {MIN_FLOW_FACTOR_FILM:g} under pressure: flow below Patir-Cheng's fit (percolation law)",
    "inlet": f"inlet short of the flooded film by ≥ {100 * INLET_FILM_DEFICIT:g} %",
}


def unit_label(units: str) -> str:
    return UNIT_LABELS.get(units, units)


def axis_label(long_name: str, units: str) -> str:
    """'name (unit)'; a long_name's own parenthetical remark (equation numbers) is left out."""
    return f"{long_name.split(' (')[0]} ({unit_label(units)})"


def x_quantity(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The x values of a panel, with units and long_name."""
    if name not in X_QUANTITIES:
        raise ValueError(f"unknown x quantity {name!r}; allowed: {', '.join(X_QUANTITIES)}")
    long_name, units, f = X_QUANTITIES[name]
    return f(ds).assign_attrs(units=units, long_name=long_name)


def _display(ds: xr.Dataset, coord: str, unit: str | None) -> float:
    """A 0-d coordinate in the display unit (its own unit when None); a file (a measured
    surface) by its name, not the path the scene gave."""
    value = ds[coord].values.item()
    if isinstance(value, str):
        return Path(value).name
    if unit is None:
        return value
    if unit not in DISPLAY_UNITS:
        raise ValueError(f"legend unit {unit!r} for {coord}: allowed {', '.join(DISPLAY_UNITS)}")
    base, size = DISPLAY_UNITS[unit]
    if ds[coord].attrs.get("units") != base:
        raise ValueError(f"legend unit {unit!r} does not fit {coord} in {ds[coord].attrs.get('units')!r}")
    return value / size


def render(ds: xr.Dataset, plot: Mapping, title: str = "", reference: xr.Dataset | None = None) -> Figure:
    """The figure of ``plot`` = {y, x: [quantities], xscale, yscale, legend} from ``ds``;
    ``kind: speed_limit`` draws :func:`render_speed_limit` instead. ``reference`` (a figure
    Dataset with the same swept dimensions, e.g. the paper's model beside the full path) is
    drawn dashed in the same colours, clipped to the axes ``ds`` sets."""
    if plot.get("kind", "curves") == "speed_limit":
        return render_speed_limit(ds, plot, title)
    y_name = plot["y"]
    y = ds[y_name]
    values = y.values
    if np.isnan(values).any():
        bad = ds["case_id"].values[np.isnan(values)]
        raise ValueError(f"{y_name} is NaN in case(s) {', '.join(bad)}: the solver must not return NaN")
    if np.isneginf(values).any():
        raise ValueError(f"{y_name} is -inf somewhere; only +inf (open circuit) can be drawn")
    dims = [d for d in y.dims if d != "speed"]
    swept = [c for c in ds.coords if ds[c].ndim == 1 and ds[c].dims[0] in dims]
    panels = list(plot["x"])
    fig = Figure(figsize=(4.8 * len(panels) + 1.0, 4.2), layout="constrained")
    axes = fig.subplots(1, len(panels), squeeze=False, sharey=True)[0]
    shape = [ds.sizes[d] for d in dims]
    colours = curve_colours(int(np.prod(shape)))
    marks = {"not converged": False, "open": False, "outside": False}
    flagged: set[str] = set()
    for ax, x_name in zip(axes, panels):
        x_all = x_quantity(ds, x_name)
        x_all, y_all = xr.broadcast(x_all, y)
        for k, index in enumerate(np.ndindex(*shape)):
            at = dict(zip(dims, index))
            curve = ds.isel(at)
            xs = x_all.isel(at).transpose("speed").values
            ys = y_all.isel(at).transpose("speed").values
            infinite = ~np.isfinite(ys)
            failed = curve["converged"].transpose("speed").values == 0
            label = _label(curve, swept, plot.get("legend")) if dims else None
            ax.plot(xs, np.where(infinite, np.nan, ys), marker="o", markersize=3, color=colours[k], label=label)
            if "validity_flags" in curve:  # each kind of breach its own hollow marker
                bits = curve["validity_flags"].transpose("speed").values
                for bit, flag in enumerate(VALIDITY_FLAGS):
                    raised = ((bits >> bit) & 1).astype(bool) & ~infinite
                    if raised.any():
                        ax.plot(xs[raised], ys[raised], marker=FLAG_MARKERS[flag], markersize=7, markerfacecolor="none",
                                markeredgecolor=colours[k], linestyle="none")
                        flagged.add(flag)
            elif "valid" in curve:  # data without the flags' kinds: hollow, outside a sub-model's range
                outside = (curve["valid"].transpose("speed").values == 0) & ~infinite
                ax.plot(xs[outside], ys[outside], markeredgecolor=colours[k], **OUTSIDE_STYLE)
                marks["outside"] |= bool(outside.any())
            # +inf is drawn on the top edge: x in data, y in axes coordinates (1 = top)
            top = ax.get_xaxis_transform()
            if infinite.any():
                ax.plot(xs[infinite], np.ones(infinite.sum()), transform=top, color=colours[k], **OPEN_STYLE)
                marks["open"] = True
            if (failed & ~infinite).any():
                ax.plot(xs[failed & ~infinite], ys[failed & ~infinite], **NOT_CONVERGED_STYLE)
            if (failed & infinite).any():
                ax.plot(xs[failed & infinite], np.ones((failed & infinite).sum()), transform=top, clip_on=False, **NOT_CONVERGED_STYLE)
            marks["not converged"] |= bool(failed.any())
        ax.set_xscale(plot.get("xscale", "log"))
        ax.set_yscale(plot.get("yscale", "log"))
        if reference is not None:
            _draw_reference(ax, reference, x_name, y_name, dims, colours)
        ax.set_xlabel(axis_label(x_all.attrs["long_name"], x_all.attrs["units"]))
        ax.grid(True, which="major", alpha=0.3)
    axes[0].set_ylabel(axis_label(_long_name(ds, y_name), y.attrs["units"]))
    handles, labels = axes[-1].get_legend_handles_labels()
    if marks["not converged"]:
        handles.append(Line2D([], [], **NOT_CONVERGED_STYLE))
        labels.append("not converged")
    if reference is not None:
        handles.append(Line2D([], [], color="0.3", linestyle="--"))
        labels.append(reference.attrs.get("reference_label", "dashed: the paper's model (spots only)"))
    if marks["outside"]:
        handles.append(Line2D([], [], markeredgecolor="0.3", **OUTSIDE_STYLE))
        labels.append("outside a sub-model's range (case validity)")
    for flag in VALIDITY_FLAGS:
        if flag in flagged:
            handles.append(Line2D([], [], marker=FLAG_MARKERS[flag], markersize=7, markerfacecolor="none",
                                  markeredgecolor="0.3", linestyle="none"))
            labels.append(FLAG_LABELS[flag])
    if marks["open"]:
        handles.append(Line2D([], [], color="0.3", **OPEN_STYLE))
        labels.append(f"{y_name.replace('_', ' ')} = \u221e (open circuit), at top edge")
    if handles:
        legend = plot.get("legend") or {}
        axes[-1].legend(handles, labels, title=legend.get("title"), fontsize="small", title_fontsize="small")
    if title:
        fig.suptitle(title, fontsize="medium")
    return fig


def _long_name(ds: xr.Dataset, name: str) -> str:
    """The variable's long name, or for contact_resistance the path the cases modelled: the
    paper's model has the metal spots only (no film conduction, no cluster constriction)."""
    if name != "contact_resistance" or "scene" not in ds:
        return ds[name].attrs["long_name"]
    effects = yaml.safe_load(str(ds["scene"].values.flat[0])).get("effects") or {}
    if effects.get("macro_constriction") or effects.get("film_conduction"):
        return ds[name].attrs["long_name"]
    return "contact resistance of the metal spots (the paper's model)"


def _draw_reference(ax, reference: xr.Dataset, x_name: str, y_name: str, dims: Sequence[str], colours) -> None:
    """The reference's curves, dashed; the y range reaches down to the reference's smallest
    value but its top stays that of the data drawn solid (the paper's open contacts reach
    1e66 ohm: above the top they are clipped)."""
    bottom, top = ax.get_ylim()
    finite = reference[y_name].values[np.isfinite(reference[y_name].values)]
    if finite.size and finite.min() < bottom and (ax.get_yscale() != "log" or finite.min() > 0):
        bottom = finite.min() / 2 if ax.get_yscale() == "log" else finite.min()
    x_all, y_all = xr.broadcast(x_quantity(reference, x_name), reference[y_name])
    shape = [reference.sizes[d] for d in dims]
    for k, index in enumerate(np.ndindex(*shape)):
        at = dict(zip(dims, index))
        ys = y_all.isel(at).transpose("speed").values
        ax.plot(x_all.isel(at).transpose("speed").values, np.where(np.isfinite(ys), ys, np.nan),
                linestyle="--", linewidth=1.0, color=colours[k])
    ax.set_ylim(bottom, top)


def highest_closed_speed(ds: xr.Dataset) -> xr.DataArray:
    """Per swept combination: the highest speed U* (m/s) at which contact_resistance is still
    below the scene's interface.open_resistance, from the first opening along speed,
    interpolated in log R against log U between the last closed and the first open speed.
    NaN where the contact is open at the lowest speed; +inf where it never opens."""
    threshold = yaml.safe_load(str(ds["scene"].values.flat[0]))["interface"]["open_resistance"]
    resistance = ds["contact_resistance"].transpose(..., "speed")
    speeds = ds["speed"].values
    out = np.full(resistance.shape[:-1], np.nan)
    for index in np.ndindex(out.shape):
        r = resistance.values[index]
        opened = np.flatnonzero(~(r <= threshold))
        if opened.size == 0:
            out[index] = np.inf
        elif opened[0] > 0:
            i = opened[0]
            lo, hi = np.log(r[i - 1]), np.log(min(r[i], np.finfo(float).max))
            t = (np.log(threshold) - lo) / (hi - lo)
            out[index] = float(np.exp(np.log(speeds[i - 1]) + t * (np.log(speeds[i]) - np.log(speeds[i - 1]))))
    dims = [d for d in resistance.dims if d != "speed"]
    return xr.DataArray(out, dims=dims, coords={d: ds[d] for d in dims},
                        attrs={"units": "m s-1", "long_name": "highest sliding speed with the contact closed",
                               "open_resistance": threshold})


def render_speed_limit(ds: xr.Dataset, plot: Mapping, title: str = "") -> Figure:
    """A map of :func:`highest_closed_speed` over the two swept dimensions (``plot['map']``:
    [x dimension, y dimension]), log colour scale, each cell labelled with its value. The
    colour bar carries a second scale in mu U (Pa m), the group the steady film depends on,
    and the title says how to read the map for another viscosity."""
    limit = highest_closed_speed(ds)
    x_dim, y_dim = plot.get("map") or [d for d in limit.dims]
    limit = limit.transpose(y_dim, x_dim)
    speeds = ds["speed"].values
    shown = np.clip(np.nan_to_num(limit.values, nan=speeds.min(), posinf=speeds.max()), speeds.min(), speeds.max())
    fig = Figure(figsize=(6.4, 4.8), layout="constrained")
    ax = fig.subplots()
    xs, ys = np.arange(limit.sizes[x_dim]), np.arange(limit.sizes[y_dim])
    mesh = ax.pcolormesh(xs, ys, shown, norm=LogNorm(speeds.min(), speeds.max()), cmap="viridis", shading="nearest")
    for j in ys:
        for i in xs:
            value = limit.values[j, i]
            text = (f"> {speeds.max():g}" if value == np.inf else f"< {speeds.min():g}" if np.isnan(value)
                    else f"{float(f'{value:.2g}'):g}")  # 140, not 1.4e+02
            ax.text(i, j, text, ha="center", va="center", fontsize="small",
                    color="white" if shown[j, i] < np.sqrt(speeds.min() * speeds.max()) else "black")
    for axis, dim, ticks in ((ax.xaxis, x_dim, xs), (ax.yaxis, y_dim, ys)):
        coord = ds[dim]
        axis.set_ticks(ticks, [f"{v:g}" for v in coord.values / _unit_size(plot, dim, coord)])
    units = plot.get("units") or {}
    ax.set_xlabel(f"{ds[x_dim].attrs.get('long_name', x_dim).split(' (')[0]} ({units.get(x_dim, unit_label(ds[x_dim].attrs.get('units', '')))})")
    ax.set_ylabel(f"{ds[y_dim].attrs.get('long_name', y_dim).split(' (')[0]} ({units.get(y_dim, unit_label(ds[y_dim].attrs.get('units', '')))})")
    scene = yaml.safe_load(str(ds["scene"].values.flat[0]))
    viscosity = float(scene["lubricant"]["viscosity"])
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label(f"highest sliding speed with R < {limit.attrs['open_resistance']:g} Ω (m/s)")
    # the steady isoviscous film depends on mu U alone (Reynolds, docs/physics.md section 3):
    # the same map read for any lubricant
    product = bar.ax.secondary_yaxis("left", functions=(lambda u: u * viscosity, lambda m: m / viscosity))
    product.set_ylabel("the same as viscosity × speed μU (Pa m)")
    # a cell with a solve that did not converge is marked, not trusted silently
    failed = (ds["converged"].transpose(y_dim, x_dim, "speed").values == 0).any(axis=-1)
    if failed.any():
        rows, columns = np.nonzero(failed)
        ax.plot(columns + 0.35, rows + 0.3, **NOT_CONVERGED_STYLE)
        ax.legend([Line2D([], [], **NOT_CONVERGED_STYLE)], ["a solve of this cell did not converge"],
                  loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize="small", frameon=False)
    what = (f"μ = {viscosity:g} Pa s, σ = {scene['roughness']['sigma'] * 1e6:g} µm, "
            f"speeds {speeds.min():g} to {speeds.max():g} m/s; another lubricant μ': U* × μ/μ'")
    fig.suptitle(f"{title}\n{what}" if title else what, fontsize="medium")
    return fig


def _unit_size(plot: Mapping, dim: str, coord: xr.DataArray) -> float:
    """Size of the display unit of a map axis (``plot['units'][dim]``) in the coordinate's units."""
    unit = (plot.get("units") or {}).get(dim)
    if unit is None:
        return 1.0
    base, size = DISPLAY_UNITS[unit]
    if coord.attrs.get("units") != base:
        raise ValueError(f"display unit {unit!r} does not fit {dim} in {coord.attrs.get('units')!r}")
    return size


def curve_colours(n: int) -> list:
    """One colour for each of ``n`` curves, along viridis (its yellow end left out)."""
    cmap = colormaps["viridis"]
    return [cmap(0.85 * k / max(n - 1, 1)) for k in range(n)]


def _label(curve: xr.Dataset, swept: Sequence[str], legend: Mapping | None) -> str:
    """Legend text of one curve: ``legend['label']`` formatted with the curve's swept
    coordinates (converted to ``legend['units']``), else 'name = value unit' each."""
    if legend and legend.get("label"):
        units = legend.get("units") or {}
        return legend["label"].format(**{c: _display(curve, c, units.get(c)) for c in swept})
    return ", ".join(f"{c} = {curve[c].values.item():g} {unit_label(curve[c].attrs.get('units', ''))}" for c in swept)


def save(fig: Figure, paths: Sequence) -> None:
    """Write the figure to each path (format from the suffix); PDFs without a date stamp."""
    for path in paths:
        metadata = {"CreationDate": None} if str(path).endswith(".pdf") else None
        fig.savefig(path, dpi=150, metadata=metadata)
