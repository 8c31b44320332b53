"""Figures of the full electrical path (lubecontact.plotting.figures): the paper's curves dashed on
the full path's axes, hollow points outside a sub-model's range, and the design map of the
highest closed speed against a resistance law whose crossing is known exactly."""

import numpy as np
import pytest
import xarray as xr

from lubecontact import load_scene
from lubecontact.plotting import figures as plotting

SPEEDS = [1e-2, 1e-1, 1.0, 10.0]


def dataset(resistance, dims, coords, valid=None):
    scene = load_scene({}).canonical_yaml()  # interface.open_resistance = 10 ohm
    resistance = np.asarray(resistance, dtype=float)
    return xr.Dataset(
        {
            "contact_resistance": (dims, resistance, {"units": "ohm", "long_name": "contact resistance"}),
            "converged": (dims, np.ones(resistance.shape, np.int32), {"units": "1", "long_name": "converged"}),
            "valid": (dims, np.ones(resistance.shape, np.int32) if valid is None else valid, {"units": "1", "long_name": "valid"}),
            "case_id": (dims, np.full(resistance.shape, "c")),
            "scene": (dims, np.full(resistance.shape, scene, dtype=object).astype(str)),
        },
        coords={"force": ((), 5.0, {"units": "N", "long_name": "force"}), "viscosity": ((), 0.1, {"units": "Pa s", "long_name": "mu"}),
                **coords, "speed": ("speed", SPEEDS, {"units": "m s-1", "long_name": "sliding speed U"})},
    )


def test_highest_closed_speed_is_the_crossing_of_a_power_law():
    """R = 4 U^2 ohm crosses 10 ohm at U = sqrt(2.5) = 1.581 m/s (exact in log-log
    interpolation); one curve never opens (> 10 m/s: +inf), one is open from the start (NaN)."""
    force = ("force", [1.0, 10.0, 30.0], {"units": "N", "long_name": "normal force"})
    u = np.array(SPEEDS)
    r = np.stack([4 * u**2, np.full(4, 1e-3), np.full(4, 1e3)])
    limit = plotting.highest_closed_speed(dataset(r, ("force", "speed"), {"force": force}))
    assert limit.values[0] == pytest.approx(np.sqrt(2.5), rel=1e-12)
    assert limit.values[1] == np.inf and np.isnan(limit.values[2])
    assert limit.attrs["units"] == "m s-1" and limit.attrs["open_resistance"] == 10.0


def test_speed_limit_map_and_reference_curves():
    coords = {"force": ("force", [1.0, 10.0], {"units": "N", "long_name": "normal force F"}),
              "radius": ("radius", [2.5e-3, 1e-2], {"units": "m", "long_name": "cylinder radius R"})}
    u = np.array(SPEEDS)
    r = np.array([[4 * u**2, 2 * u**2], [np.full(4, 1e-3), u]])
    fig = plotting.render(dataset(r, ("force", "radius", "speed"), coords),
                          {"kind": "speed_limit", "y": "contact_resistance", "x": ["speed"], "map": ["force", "radius"],
                           "units": {"radius": "mm"}}, "map")
    ax = fig.axes[0]
    labels = sorted(t.get_text() for t in ax.texts)
    assert labels == sorted([f"{np.sqrt(2.5):.2g}", f"{np.sqrt(5.0):.2g}", "> 10", "> 10"])  # R = u < 10 up to 10 m/s
    assert [t.get_text() for t in ax.get_yticklabels()] == ["2.5", "10"]

    sigma = {"sigma": ("sigma", [0.5e-6, 1e-6], {"units": "m", "long_name": "sigma"})}
    full = dataset([[2e-4, 2e-4, 3e-4, 1e3], [2e-4, 2e-4, 2e-4, 1e-3]], ("sigma", "speed"), sigma,
                   valid=np.array([[0, 0, 1, 1], [0, 1, 1, 1]], np.int32))
    paper = dataset([[2e-6, 2e-6, 1e-3, 1e66], [2e-6, 2e-6, 2e-6, 1e-4]], ("sigma", "speed"), sigma)
    fig = plotting.render(full, {"y": "contact_resistance", "x": ["speed"]}, reference=paper)
    ax = fig.axes[0]
    bottom, top = ax.get_ylim()
    assert top < 1e5  # the paper's 1e66 ohm does not set the axis
    dashed = [line for line in ax.get_lines() if line.get_linestyle() == "--"]
    assert len(dashed) == 2 and np.nanmax(dashed[0].get_ydata()) == 1e66  # drawn, clipped by the axes
    hollow = [line for line in ax.get_lines() if line.get_markerfacecolor() == "white"]
    assert sum(len(line.get_xdata()) for line in hollow) == 3  # the three valid = 0 points
    assert "paper's model" in " ".join(t.get_text() for t in ax.get_legend().get_texts())


def test_speed_limit_map_marks_cells_with_unconverged_solves_and_names_mu_and_sigma():
    """Issue 29 item 10: a cell whose curve has a solve that did not converge is marked, and
    the title says the lubricant's viscosity, the roughness and the speeds the map covers."""
    coords = {"force": ("force", [1.0, 10.0], {"units": "N", "long_name": "normal force F"}),
              "radius": ("radius", [2.5e-3, 1e-2], {"units": "m", "long_name": "cylinder radius R"})}
    u = np.array(SPEEDS)
    ds = dataset(np.array([[4 * u**2, 2 * u**2], [np.full(4, 1e-3), u]]), ("force", "radius", "speed"), coords)
    ds["converged"][1, 0, 2] = 0  # force 10 N, radius 2.5 mm
    fig = plotting.render(ds, {"kind": "speed_limit", "y": "contact_resistance", "x": ["speed"],
                               "map": ["force", "radius"]}, "map")
    ax = fig.axes[0]
    crosses = [line for line in ax.get_lines() if line.get_marker() == "x"]
    assert len(crosses) == 1 and list(crosses[0].get_xdata()) == [1.35] and list(crosses[0].get_ydata()) == [0.3]
    assert "did not converge" in ax.get_legend().get_texts()[0].get_text()
    assert "μ = 0.1 Pa s, σ = 0.5 µm" in fig.get_suptitle() and f"speeds {min(SPEEDS):g} to {max(SPEEDS):g} m/s" in fig.get_suptitle()


def test_speed_limit_map_reads_for_any_lubricant_as_mu_u():
    """Issue 29 item 10: the steady film depends on mu U alone, so the colour bar's second
    scale is mu U (Pa m) and the title says how to read the map for another viscosity."""
    coords = {"force": ("force", [1.0, 10.0], {"units": "N", "long_name": "normal force F"}),
              "radius": ("radius", [2.5e-3, 1e-2], {"units": "m", "long_name": "cylinder radius R"})}
    u = np.array(SPEEDS)
    ds = dataset(np.array([[4 * u**2, 2 * u**2], [np.full(4, 1e-3), u]]), ("force", "radius", "speed"), coords)
    fig = plotting.render(ds, {"kind": "speed_limit", "y": "contact_resistance", "x": ["speed"],
                               "map": ["force", "radius"]}, "map")
    fig.draw_without_rendering()  # a secondary axis takes its limits when drawn
    bar = fig.axes[1]
    product = [child for child in bar.get_children() if hasattr(child, "get_ylabel") and "μU" in child.get_ylabel()]
    assert len(product) == 1
    low, high = bar.get_ylim()
    assert product[0].get_ylim() == pytest.approx((0.1 * low, 0.1 * high))  # mu = 0.1 Pa s
    assert "another lubricant" in fig.get_suptitle()
    cells = [text.get_text() for text in fig.axes[0].texts]
    assert cells and not any("e+" in cell for cell in cells)  # 140, not 1.4e+02


def test_the_paper_models_resistance_axis_says_spots_only():
    """Issue 29 item 12: Figs. 3-11 model the metal spots alone; their axis must not say 'whole path'."""
    ds = dataset([[2e-4, 2e-4, 3e-4, 1e3]], ("sigma", "speed"),
                 {"sigma": ("sigma", [0.5e-6], {"units": "m", "long_name": "sigma"})})
    ds["contact_resistance"].attrs["long_name"] = "electrical contact resistance of the whole path (spots, film, cluster)"
    label = plotting.render(ds, {"y": "contact_resistance", "x": ["speed"]}).axes[0].get_ylabel()
    assert "metal spots" in label and "whole path" not in label
    full = load_scene({"effects": {"film_conduction": True}}).canonical_yaml()
    ds["scene"][...] = full
    label = plotting.render(ds, {"y": "contact_resistance", "x": ["speed"]}).axes[0].get_ylabel()
    assert "whole path" in label


def test_a_surface_file_is_named_in_the_legend_not_its_path():
    surfaces = {"surface": ("surface", ["../surfaces/ground.asc", "../surfaces/honed.asc"], {"units": "1", "long_name": "surface"})}
    ds = dataset([[2e-4, 2e-4, 3e-4, 1e3], [1e-4, 1e-4, 2e-4, 1e2]], ("surface", "speed"), surfaces)
    fig = plotting.render(ds, {"y": "contact_resistance", "x": ["speed"], "legend": {"label": "{surface}"}})
    assert [t.get_text() for t in fig.axes[0].get_legend().get_texts()][:2] == ["ground.asc", "honed.asc"]


def test_each_kind_of_breach_has_its_own_marker_and_words():
    """Issue 29 item 9: a point's validity flags are drawn each with its own hollow marker,
    and the legend says in words what each means, with its bound."""
    from lubecontact.io.case_schema import VALIDITY_FLAGS

    sigma = {"sigma": ("sigma", [0.5e-6], {"units": "m", "long_name": "sigma"})}
    ds = dataset([[2e-4, 2e-4, 3e-4, 1e3]], ("sigma", "speed"), sigma, valid=np.array([[0, 0, 1, 1]], np.int32))
    gw, bulk = 1 << VALIDITY_FLAGS.index("gw_area"), 1 << VALIDITY_FLAGS.index("bulk_yield")
    ds["validity_flags"] = (("sigma", "speed"), np.array([[gw | bulk, gw, 0, 0]], np.int32), {"units": "1", "long_name": "f"})
    ax = plotting.render(ds, {"y": "contact_resistance", "x": ["speed"]}).axes[0]
    markers = {line.get_marker(): len(line.get_xdata()) for line in ax.get_lines() if line.get_markerfacecolor() == "none"}
    assert markers == {"s": 2, "P": 1}
    legend = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert "A_r/A_n > 0.1: beyond GW's light contact" in legend and "pressure > 1.67 S_y: bulk yield" in legend
    assert "flow factors" not in legend  # only the kinds raised
