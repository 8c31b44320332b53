"""Start-up cost guards (issue 14): what `import lubecontact`, `load_scene` and the first solve load.

A fresh interpreter is started for each check, since the test process has imported everything.
"""

import json
import subprocess
import sys
from importlib.metadata import PackageNotFoundError, version

import numpy as np
import pytest

from lubecontact.physics import rough_surface

HEAVY = ("numba", "llvmlite", "scipy", "xarray", "pandas", "importlib.metadata")
# planning needs importlib.metadata where a scene has a measured surface (the cache key
# holds the surface reader's version: lubecontact.surfaces.measured)
SOLVER_AND_DATA = ("numba", "llvmlite", "scipy", "xarray", "pandas")


def _fresh(code: str) -> dict:
    """Run ``code`` in a new interpreter; it prints one JSON object as its last line."""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_and_load_scene_stay_light():
    loaded = _fresh(
        "import json, sys\n"
        "import lubecontact\n"
        "first = sorted(m for m in " + repr(HEAVY) + " if m in sys.modules)\n"
        "lubecontact.load_scene('config/scenes/table1.yaml', {'mesh.nx': 11, 'mesh.ny': 11})\n"
        "second = sorted(m for m in " + repr(HEAVY) + " if m in sys.modules)\n"
        "print(json.dumps({'import': first, 'load_scene': second}))\n"
    )
    assert loaded == {"import": [], "load_scene": []}


def test_planning_the_workflow_stays_light():
    """What the Snakefile runs at parse time (every snakemake call, and every job on a
    cluster) to plan the figures, the transient cases and the accuracy study: no solver,
    no xarray (they cost ~0.4 s a parse when the unsteady package and the study loaded them).
    The measured surfaces of config/test.yaml are analysed first, here: a cold surface cache
    needs scipy, a warm one (the session's, which the fresh process shares) does not."""
    import yaml

    from lubecontact.studies import figure_grids as grid

    with open("config/test.yaml") as file:
        config = yaml.safe_load(file)
    specs = {f: grid.figure_spec(f, "config/figures", config["figures"]) for f in config["figures"]}
    grid.expand_all(specs)
    loaded = _fresh(
        "import json, sys, yaml\n"
        "from lubecontact.studies import accuracy_plan as convergence, figure_grids as grid, transient_cases as study\n"
        "config = yaml.safe_load(open('config/test.yaml'))\n"
        "specs = {f: grid.figure_spec(f, 'config/figures', config['figures']) for f in config['figures']}\n"
        "grid.expand_all(specs)\n"
        "study.figure_cases(study.study_spec('config/transient.yaml', config.get('transient')))\n"
        "convergence.study_points(convergence.study_spec('config/accuracy.yaml', config.get('accuracy')))\n"
        "print(json.dumps(sorted(m for m in " + repr(SOLVER_AND_DATA) + " if m in sys.modules)))\n"
    )
    assert loaded == []


def test_solve_does_not_load_numba():
    loaded = _fresh(
        "import json, sys\n"
        "import lubecontact\n"
        "ds = lubecontact.solve(lubecontact.load_scene('config/scenes/table1.yaml', {'mesh.nx': 11, 'mesh.ny': 11}))\n"
        "print(json.dumps({'numba': 'numba' in sys.modules, 'version': ds.attrs['lubecontact_version']}))\n"
    )
    assert loaded["numba"] is False
    assert loaded["version"] == _installed_version()


def _installed_version() -> str:
    try:
        return version("lubecontact")
    except PackageNotFoundError:
        return "0+unknown"


def test_version_is_resolved_lazily():
    import lubecontact

    assert lubecontact.__version__ == _installed_version()
    from lubecontact import __version__

    assert __version__ == lubecontact.__version__


@pytest.fixture(scope="module")
def table():
    import lubecontact

    return rough_surface.RoughContact.from_scene(lubecontact.load_scene("config/scenes/table1.yaml"))


def _reference(t, q, dq, k_lo, j_hi, k_hi, take_exp):
    """The former per-element kernel (plain Python): the Hermite basis form at each t."""
    r = rough_surface
    value, slope = np.empty_like(t), np.empty_like(t)
    n = q.size
    for i, x in enumerate(t):
        if x <= r._T_LO:
            val, der = q[0] + k_lo * np.log(x / r._T_LO), k_lo / x
        elif x >= r._T_HI:
            val = j_hi + k_hi * np.log(x / r._T_HI) - 0.5 * x * x - r._LOG_SQRT_2PI
            der = k_hi / x - x
        else:
            if x >= r.T_UNIFORM:
                c, dc_dt = x / r.T_STEP, 1.0 / r.T_STEP
            else:
                y = (x - r.T_UNIFORM) / r.T_SCALE
                c = r._C_UNIFORM + np.arcsinh(y) / r._DU
                dc_dt = 1.0 / (r.T_STEP * np.sqrt(1.0 + y * y))
            u = c - r._C_MIN
            k = min(int(u), n - 2)
            s = u - k
            q0, q1, m0, m1 = q[k], q[k + 1], dq[k], dq[k + 1]
            val = (2 * s**3 - 3 * s**2 + 1) * q0 + (s**3 - 2 * s**2 + s) * m0 + (3 * s**2 - 2 * s**3) * q1 + (s**3 - s**2) * m1
            der = dc_dt * ((6 * s**2 - 6 * s) * (q0 - q1) + (3 * s**2 - 4 * s + 1) * m0 + (3 * s**2 - 2 * s) * m1)
        if take_exp:
            val = np.exp(val)
            der = val * der if val > 0.0 and der != 0.0 else 0.0
        value[i], slope[i] = val, der
    return value, slope


@pytest.mark.parametrize("take_exp", [True, False])
@pytest.mark.parametrize("row", [rough_surface.PRESSURE, rough_surface.AREA, rough_surface.CONDUCTANCE])
def test_vectorised_kernel_matches_the_elementwise_one(table, row, take_exp):
    r = rough_surface
    t = np.concatenate([
        np.linspace(-30.0, 50.0, 1601),  # both node spacings, T_UNIFORM, _T_HI
        -np.logspace(1.5, 7.0, 200),  # deep interference, across _T_LO
        [r._T_LO, np.nextafter(r._T_LO, 0.0), r._T_HI, np.nextafter(r._T_HI, 0.0), r.T_UNIFORM, 0.0],
    ])
    args = (table._k_lo[row], table._j_hi[row], table._k_hi[row], take_exp)
    value, slope = r._evaluate(t, table._nodes[row], *args)
    with np.errstate(under="ignore"):
        ref_value, ref_slope = _reference(t, table._q[row], table._dq[row], *args)
    # the same formula, vectorised: equal to rounding (|Q| up to ~1e3 in the far tail)
    if take_exp:
        np.testing.assert_allclose(value, ref_value, rtol=1e-11, atol=0.0)
        np.testing.assert_allclose(slope, ref_slope, rtol=1e-11, atol=0.0)
    else:
        np.testing.assert_allclose(value, ref_value, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(slope, ref_slope, rtol=1e-11, atol=1e-12)


def test_kernel_limits(table):
    r = rough_surface
    t = np.array([-np.inf, np.inf, -1e300, 1e300])
    value, slope = r._evaluate(t, table._nodes[r.PRESSURE], table._k_lo[0], table._j_hi[0], table._k_hi[0], True)
    assert value[0] == np.inf and value[1] == 0.0 and value[3] == 0.0 and np.isfinite(value[2])
    assert slope[0] == 0.0 and slope[1] == 0.0 and slope[3] == 0.0 and not np.signbit(slope[[0, 1, 3]]).any()
    value, slope = r._evaluate(t, table._nodes[r.PRESSURE], table._k_lo[0], table._j_hi[0], table._k_hi[0], False)
    assert value[0] == np.inf and value[1] == -np.inf and np.isfinite(value[2])
