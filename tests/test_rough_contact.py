"""Statistical rough contact (paper Eqs. 11-13, 15) against docs/physics.md sections 2 and 9 and
checks #2, #5, #6, #7: McCool statistics, the F_n closed forms, the elastic GW limit, the
Table 1 statistical table, direct adaptive quadrature of Eqs. (11)/(15), and the tails."""

import math
from decimal import Decimal

import numpy as np
import pytest
from scipy.integrate import quad

import lubecontact
from lubecontact.physics.rough_surface import (
    RoughContact,
    gaussian_moment,
    rough_contact,
    summit_height_std,
    summit_offset,
)

pytestmark = pytest.mark.filterwarnings("error")

SIGMA, ETA, R_PEAK, RHO = 0.5e-6, 1.0e9, 1.0e-4, 1.15e-7  # Table 1
E_STAR = 1.0 / (2.0 * (1.0 - 0.36**2) / 41.4e9)


def assert_printed(value, printed: str):
    """value agrees with a number printed in docs/physics.md to half a unit of its last digit."""
    d = Decimal(printed)
    assert abs(value - float(d)) <= 0.5 * 10.0 ** d.as_tuple().exponent * (1 + 1e-9), (value, printed)


def scene(height_std="sigma", hardness="wadwalkar", plasticity=True, alleviation=True):
    return lubecontact.load_scene(
        {
            "roughness": {"height_std": height_std, "hardness_model": hardness},
            "effects": {"plasticity": plasticity, "alleviation": alleviation},
        }
    )


@pytest.fixture(scope="module")
def table9():
    """Section 9 convention: McCool's sigma_s, JG 2005 hardness."""
    return RoughContact.from_scene(scene("mccool", "jg2005"))


@pytest.fixture(scope="module")
def paper():
    """The paper's convention: Gaussian with sigma, Eq. (8) hardness."""
    return RoughContact.from_scene(scene())


# --- McCool statistics (check #2) --------------------------------------------------------


def test_summit_statistics():
    assert_printed(summit_offset(ETA, R_PEAK), "0.45944e-6")
    assert_printed(summit_height_std(SIGMA, ETA, R_PEAK), "0.46134e-6")
    # McCool in terms of the bandwidth alpha: eta = m4/(6 pi sqrt(3) m2), R = 0.375 sqrt(pi/m4),
    # sigma = sqrt(m0), so eta R sigma = 0.375 sqrt(pi)/(6 pi sqrt(3)) sqrt(alpha) = 0.020358 sqrt(alpha)
    alpha = (ETA * R_PEAK * SIGMA / (0.375 * math.sqrt(math.pi) / (6 * math.pi * math.sqrt(3)))) ** 2
    assert_printed(alpha, "6.032")
    assert summit_offset(ETA, R_PEAK) == pytest.approx(4 * SIGMA / math.sqrt(math.pi * alpha), rel=1e-5)
    assert summit_height_std(SIGMA, ETA, R_PEAK) == pytest.approx(SIGMA * math.sqrt(1 - 0.8968 / alpha), rel=1e-5)


def test_mccool_undefined_for_small_bandwidth():
    with pytest.raises(ValueError, match="height_std = 'sigma'"):
        summit_height_std(0.15e-6, ETA, R_PEAK)  # eta R sigma = 0.015 < 0.0193


def test_contact_uses_scene_statistics(table9, paper):
    assert table9.sigma == paper.sigma == SIGMA
    assert table9.y_s == paper.y_s == pytest.approx(0.045944 / (ETA * R_PEAK), rel=1e-15)
    assert paper.height_std == SIGMA
    assert table9.height_std == pytest.approx(math.sqrt(SIGMA**2 - 3.717e-4 / (ETA * R_PEAK) ** 2), rel=1e-15)


# --- F_n closed forms (check #5) ---------------------------------------------------------


@pytest.mark.parametrize("n, t, expected", [(0, 0, "0.5"), (1, 0, "0.398942"), (1.5, 0, "0.430020"),
                                            (2.5, 0, "0.616634"), (1.5, 1, "0.075668"), (1.5, 2, "0.0066482")])
def test_gaussian_moments_published(n, t, expected):
    assert_printed(gaussian_moment(n, t), expected)


@pytest.mark.parametrize("n", [0, 0.5, 1, 1.5])
def test_gaussian_moments_against_quadrature(n):
    for t in (-3.0, -0.7, 0.4, 2.5, 6.0):
        direct = quad(lambda s: (s - t) ** n * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi), t, np.inf,
                      epsabs=0, epsrel=1e-12)[0]
        assert gaussian_moment(n, t) == pytest.approx(direct, rel=1e-10)
    assert gaussian_moment(n, 0) == pytest.approx(2 ** (n / 2 - 1) * math.gamma((n + 1) / 2) / math.sqrt(math.pi))


# --- elastic GW limit (check #6) ---------------------------------------------------------


@pytest.mark.parametrize("height_std", ["sigma", "mccool"])
def test_elastic_limit_is_greenwood_williamson(height_std):
    """plasticity off: p_c = (4/3) eta E* R^1/2 s^3/2 F_3/2(d/s), A_r/A_n = pi eta R s F_1(d/s),
    g = eta (2/rho) (R s)^1/2 F_1/2(d/s)."""
    contact = RoughContact.from_scene(scene(height_std, plasticity=False))
    s = contact.height_std
    h = SIGMA * np.linspace(-3.0, 8.0, 23)
    t = (h - contact.y_s) / s
    np.testing.assert_allclose(
        contact.pressure(h), 4 / 3 * ETA * E_STAR * math.sqrt(R_PEAK) * s**1.5 * gaussian_moment(1.5, t), rtol=1e-5
    )
    np.testing.assert_allclose(contact.area_fraction(h), math.pi * ETA * R_PEAK * s * gaussian_moment(1, t), rtol=1e-5)
    np.testing.assert_allclose(
        contact.log_conductance(h), np.log(ETA * 2 / RHO * math.sqrt(R_PEAK * s) * gaussian_moment(0.5, t)), atol=1e-5
    )


# --- Section 9 table (check #7) ----------------------------------------------------------

TABLE9 = [  # h/sigma, p_c (Pa), A_r/A_n, sum 2a/rho (S/m^2), Psi
    (0.5, "9.419e6", "0.26696", "1.2052e11", "0.33601"),
    (1.0, "5.0118e6", "0.13869", "7.1044e10", "0.49717"),
    (2.0, "0.82082e6", "0.021909", "1.4099e10", "0.78641"),
    (3.0, "0.056332e6", "1.4682e-3", "1.1413e9", "0.94308"),
]


@pytest.mark.parametrize("h_over_sigma, p_c, area, conductance, psi", TABLE9)
def test_statistical_table_section9(table9, h_over_sigma, p_c, area, conductance, psi):
    h = h_over_sigma * SIGMA
    af = table9.area_fraction(h)
    for value, printed in [(table9.pressure(h), p_c), (af, area), (math.exp(table9.log_conductance(h)), conductance),
                           ((1 - math.sqrt(af)) ** 1.5, psi)]:
        assert value == pytest.approx(float(printed), rel=1e-4)
    assert table9.conductance(h) == pytest.approx(float(conductance), rel=1e-4)


def test_gaussian_with_sigma_section9():
    contact = RoughContact.from_scene(scene("sigma", "jg2005"))
    assert_printed(contact.pressure(SIGMA), "5.4895e6")


# --- table against direct adaptive quadrature of Eqs. (11) and (15) -----------------------


def direct_eq11(contact, h):
    """(p_c, A_r/A_n, g) by scipy quad of eta int_d^inf f(z - d) G(z) dz, G with std s."""
    asperity, s = contact.asperity, contact.height_std
    d = h - contact.y_s
    lower = max(d, -14 * s)  # G(z) below -14 s is below 1e-42 of its peak
    upper = max(d, 0.0) + 14 * s
    points = sorted({lower + min(s, s * s / abs(d)) if d else lower + s,
                     *(d + b for b in asperity.breakpoints if lower < d + b < upper)})

    def integral(f):
        def integrand(z):
            return float(f(z - d)) * math.exp(-0.5 * (z / s) ** 2) / (math.sqrt(2 * math.pi) * s)

        return ETA * quad(integrand, lower, upper, points=points, limit=400, epsabs=0, epsrel=1e-11)[0]

    return (integral(asperity.load), integral(asperity.contact_area),
            integral(lambda w: 2 / RHO * asperity.contact_radius(w)))


@pytest.mark.parametrize("which", ["table9", "paper"])
def test_table_against_direct_quadrature(which, request):
    contact = request.getfixturevalue(which)
    s, y_s = contact.height_std, contact.y_s
    h_over_sigma = np.linspace(-2.0, 8.0, 13) + 0.0123  # off the table nodes
    deep = y_s + s * np.array([-11.97, -12.04, -19.97, -20.04, -150.3, -3.3e4])  # quadrature/grid seams
    for h in np.concatenate([h_over_sigma * SIGMA, deep]):
        p, a, g = direct_eq11(contact, h)
        assert contact.pressure(h) == pytest.approx(p, rel=1e-6, abs=0.0)
        assert contact.area_fraction(h) == pytest.approx(a, rel=1e-6, abs=0.0)
        assert contact.log_conductance(h) == pytest.approx(math.log(g), abs=1e-6)


def test_slope_is_derivative_of_pressure(paper):
    h = SIGMA * np.array([-30.0, -2.0, -0.5, 0.3, 1.0, 2.5, 6.0, 20.0])
    p, slope = paper.pressure_and_slope(h)
    np.testing.assert_array_equal(p, paper.pressure(h))
    dh = 1e-5 * SIGMA
    fd = (paper.pressure(h + dh) - paper.pressure(h - dh)) / (2 * dh)
    np.testing.assert_allclose(slope, fd, rtol=1e-6)


# --- tails: finite, continuous, monotone, never NaN ---------------------------------------


@pytest.mark.parametrize("which", ["table9", "paper"])
def test_tails_finite_monotone(which, request):
    contact = request.getfixturevalue(which)
    h = SIGMA * np.concatenate([-np.geomspace(1e8, 50.1, 400), np.linspace(-50, 1e3, 60001)])
    p, slope = contact.pressure_and_slope(h)
    area = contact.area_fraction(h)
    log_g = contact.log_conductance(h)
    for values in (p, slope, area, log_g):
        assert np.all(np.isfinite(values))
    assert np.all(np.diff(log_g) < 0)  # strictly decreasing, representable everywhere
    assert np.all(np.diff(p) <= 0) and np.all(np.diff(area) <= 0) and np.all(slope <= 0)
    assert np.all(np.diff(p)[h[1:] < 30 * SIGMA] < 0)  # strictly where p_c is representable
    assert p[-1] == 0.0 and p[0] > 1e9  # far tail underflows; 1e8 sigma deep is a big pressure
    # continuity where the table hands over to its extensions (t = 48 and t = -1e6)
    for t_seam in (48.0, -1.0e6 - 0.35e6):
        pair = contact.y_s + contact.height_std * t_seam * np.array([1 - 1e-9, 1 + 1e-9])
        assert abs(np.diff(contact.log_conductance(pair))[0]) < 1e-6 * abs(t_seam)


def test_infinite_separations_are_limits(paper):
    h = np.array([-np.inf, np.inf, -1e300, 1e300])
    p, slope = paper.pressure_and_slope(h)
    assert p[1] == 0.0 and p[3] == 0.0 and p[0] == np.inf and p[2] > 0
    assert not np.isnan(slope).any()
    with pytest.raises(ValueError, match="NaN"):
        paper.pressure(np.array([0.0, np.nan]))


def test_shapes_preserved(paper):
    h = SIGMA * np.arange(6.0).reshape(2, 3)
    assert paper.pressure(h).shape == (2, 3)
    assert paper.pressure_and_slope(h)[1].shape == (2, 3)
    assert paper.log_conductance(h).shape == (2, 3)
    assert np.ndim(paper.area_fraction(SIGMA)) == 0


# --- public Dataset ----------------------------------------------------------------------


@pytest.mark.parametrize("alleviation", [True, False])
def test_rough_contact_dataset(alleviation):
    sc = scene("mccool", "jg2005", alleviation=alleviation)
    h = SIGMA * np.array([0.5, 1.0, 2.0, 3.0])
    ds = rough_contact(sc, h)
    assert ds.pressure.dims == ("separation",)
    np.testing.assert_array_equal(ds.separation.values, h)
    for name in ("pressure", "area_fraction", "conductance", "separation"):
        assert {"units", "long_name"} <= set(ds[name].attrs)
    assert ds.pressure.attrs["units"] == "Pa" and ds.conductance.attrs["units"] == "S m-2"
    assert ds.attrs["scene_hash"] == sc.hash
    psi = np.array([float(row[4]) for row in TABLE9])
    g = np.array([float(row[3]) for row in TABLE9])
    np.testing.assert_allclose(ds.conductance.values, g / psi if alleviation else g, rtol=1e-4)
    np.testing.assert_allclose(ds.pressure.values, [float(row[1]) for row in TABLE9], rtol=1e-4)


def test_public_name_is_the_function():
    import lubecontact.model.solve  # noqa: F401  (imports the rough-surface module)

    assert callable(lubecontact.rough_contact)
    assert callable(lubecontact.sweep)
