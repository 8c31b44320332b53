"""Roughness from measured surfaces (lubecontact.surfaces; docs/physics.md section 18).

Independent truths: the analytic profile moments of a Gaussian-correlated surface
(ACF sigma^2 exp(-r^2/l^2): m2 = 2 sigma^2/l^2, m4 = 12 sigma^2/l^4, so alpha = 3) and of a
rolled power-law spectrum (by quadrature of its areal spectrum); a sine's moments
(A^2/2, A^2 k^2/2, A^2 k^4/2); the scaling law of heights (m_n * c^2: eta and alpha
unchanged, R_peak / c); the moments of the summed height map for the composite; unit
conversion (the same map in um and in m).
"""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from lubecontact.cli.main import main
from lubecontact.surfaces import (
    SurfaceError,
    composite,
    parameters,
    read_surface,
    spectral_moments,
)
from lubecontact.surfaces.moments import hann_window, tukey_window
from lubecontact.surfaces.reading import from_array
from lubecontact.surfaces.synthetic import isotropic_surface, rolled_power_law


def mccool_expected(m0, m2, m4):
    """McCool (1986) from the moments, written out here (sigma, eta, R_peak, alpha)."""
    return math.sqrt(m0), m4 / (6 * math.pi * math.sqrt(3) * m2), 0.375 * math.sqrt(math.pi / m4), m0 * m4 / m2**2


def profile_moments(spectrum, q_max):
    """Profile moments of an isotropic surface from its areal spectrum C(q), by quadrature."""
    integral = lambda n: quad(lambda q: spectrum(q) * q ** (n + 1), 0, q_max, limit=200, points=[q_max / 8])[0]  # noqa: E731
    return 2 * math.pi * integral(0), math.pi * integral(2), 0.75 * math.pi * integral(4)


def assert_params(p, expected, rel):
    got = (p.sigma, p.asperity_density, p.asperity_radius, p.alpha)
    for name, g, e in zip(("sigma", "eta", "R_peak", "alpha"), got, expected):
        assert g == pytest.approx(e, rel=rel), f"{name}: {g:.5g} vs {e:.5g}"


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("periodic", [True, False])
def test_gaussian_correlated_surface_matches_mccool_of_analytic_moments(seed, periodic):
    """Periodic: the moments are sums over the modes (exact up to the sum-vs-integral error);
    measured (not periodic, tilted): a windowed estimate, statistical within a few %."""
    n, dx, corr, rms = 256, 1e-6, 6e-6, 0.4e-6
    spectrum = lambda q: rms**2 * corr**2 / (4 * math.pi) * np.exp(-(q**2) * corr**2 / 4)  # noqa: E731
    z = isotropic_surface(spectrum, n, n * dx, seed)
    if not periodic:
        z = z + 1e-3 * dx * np.arange(n)  # a tilt of 1 mrad, which the detrending removes
    p = parameters(spectral_moments(from_array(z, (n * dx, n * dx), periodic=periodic)))
    expected = mccool_expected(rms**2, 2 * rms**2 / corr**2, 12 * rms**2 / corr**4)
    assert expected[3] == pytest.approx(3.0)
    assert_params(p, expected[:3], rel=0.01 if periodic else 0.03)
    assert p.alpha == pytest.approx(3.0, rel=0.01 if periodic else 0.05)
    assert p.isotropic


def test_rolled_power_law_surface_matches_quadrature_of_its_spectrum():
    n, side, hurst = 256, 256e-6, 0.8
    q_r, q_s = 2 * math.pi / 40e-6, 2 * math.pi / 5e-6
    spectrum = lambda q: 1e-30 * rolled_power_law(q, q_r, q_s, hurst)  # noqa: E731
    z = isotropic_surface(spectrum, n, side, seed=7)
    p = parameters(spectral_moments(from_array(z, (side, side), periodic=True), cutoff=4e-6))
    expected = mccool_expected(*profile_moments(spectrum, q_s))
    assert expected[3] > 4  # a broader band than the Gaussian's alpha = 3
    assert_params(p, expected, rel=0.03)


def test_sine_profile_moments_exact_when_periodic():
    amplitude, periods, n, length = 0.3e-6, 5, 256, 1e-3
    x = np.arange(n) * length / n
    k = 2 * math.pi * periods / length
    m = spectral_moments(from_array(amplitude * np.sin(k * x), (length,), periodic=True), cutoff=length / 10)
    assert m.m0 == pytest.approx(amplitude**2 / 2, rel=1e-12, abs=0.0)
    assert m.m2[0] == pytest.approx(amplitude**2 * k**2 / 2, rel=1e-12)
    assert m.m4[0] == pytest.approx(amplitude**2 * k**4 / 2, rel=1e-12)
    assert m.gamma is None
    # Hann window: the line spreads over three bins (power 1/6, 2/3, 1/6), m2 off by 1/(3 j^2);
    # a cosine over whole periods is orthogonal to the line the detrending removes
    hann = spectral_moments(from_array(amplitude * np.cos(k * x), (length,)), cutoff=length / 10, window="hann")
    assert hann.m2[0] == pytest.approx(amplitude**2 * k**2 / 2 * (1 + 1 / (3 * periods**2)), rel=2e-3)


@pytest.mark.parametrize("n", [1, 2, 3, 7, 64, 128, 255, 512])
@pytest.mark.parametrize("taper", [0.0, 0.1, 0.5, 0.9, 1.0, 1.5])
def test_windows_are_scipys_to_the_bit(n, taper):
    """The numpy Tukey and Hann windows (the two profile_power uses) equal scipy.signal's
    exactly: a measured surface's parameters, and so its cases' ids, must not move."""
    from scipy.signal import windows

    np.testing.assert_array_equal(tukey_window(n, taper), windows.tukey(n, taper))
    np.testing.assert_array_equal(hann_window(n), windows.hann(n, sym=True))
    assert np.allclose(hann_window(n), np.hanning(n), rtol=0, atol=1e-15)  # the textbook form


def test_cutoff_excludes_shorter_waves():
    """Two sines; the shorter one lies beyond lambda_c and must not reach m2."""
    n, length = 512, 1e-3
    x = np.arange(n) * length / n
    k1, k2 = 2 * math.pi * 4 / length, 2 * math.pi * 100 / length
    z = 1e-6 * np.sin(k1 * x) + 1e-7 * np.sin(k2 * x)
    m = spectral_moments(from_array(z, (length,), periodic=True), cutoff=length / 50)
    assert m.m2[0] == pytest.approx(1e-12 * k1**2 / 2, rel=1e-12)
    assert m.cutoff == length / 50


def test_height_scaling_law():
    """z -> c z: m0, m2, m4 * c^2, so eta and alpha unchanged and R_peak / c."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=3)
    base = parameters(spectral_moments(from_array(z, (64e-6, 64e-6))))
    scaled = parameters(spectral_moments(from_array(3.0 * z, (64e-6, 64e-6))))
    assert scaled.sigma == pytest.approx(3 * base.sigma, rel=1e-12, abs=0.0)
    assert scaled.asperity_density == pytest.approx(base.asperity_density, rel=1e-12)
    assert scaled.alpha == pytest.approx(base.alpha, rel=1e-12)
    assert scaled.asperity_radius == pytest.approx(base.asperity_radius / 3, rel=1e-12, abs=0.0)


def test_composite_equals_summed_height_map():
    size = (256e-6, 256e-6)
    a = isotropic_surface(lambda q: rolled_power_law(q, 1e5, 1.2e6, 0.8), 256, size[0], seed=11, rms=0.3e-6)
    b = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.2e6, 0.5), 256, size[0], seed=12, rms=0.6e-6)
    ma, mb = (spectral_moments(from_array(z, size, periodic=True)) for z in (a, b))
    both, split = composite(ma, mb)
    summed = parameters(spectral_moments(from_array(a + b, size, periodic=True)))
    assert both.sigma == pytest.approx(math.hypot(0.3e-6, 0.6e-6), rel=0.02)
    assert_params(both, (summed.sigma, summed.asperity_density, summed.asperity_radius, summed.alpha), rel=0.03)
    assert split[0] == pytest.approx(0.2, rel=0.02) and sum(split) == pytest.approx(1.0)


def test_anisotropic_surface_reported():
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 128, 128e-6, seed=5)
    stretched = np.repeat(z[:, :64], 2, axis=1)  # every x wavelength doubled: gamma = 2
    p = parameters(spectral_moments(from_array(stretched, (128e-6, 128e-6))))
    assert p.gamma == pytest.approx(2.0, rel=0.15)
    assert not p.isotropic and any("anisotropic" in n for n in p.notes())


def test_a_surface_steeper_than_45_degrees_is_noted_and_its_units_questioned():
    """The RMS slope sqrt(m2) scales with the heights (test above): the same map read in um
    where its heights are in mm is 1000 times as steep. The note names the keys to check; the
    surface as measured has no such note."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=3, rms=0.5e-6)
    gentle = parameters(spectral_moments(from_array(z, (64e-6, 64e-6))))
    steep = parameters(spectral_moments(from_array(1e3 * z, (64e-6, 64e-6))))
    assert math.sqrt(gentle.moments.m2_mean) < 1.0 < math.sqrt(steep.moments.m2_mean)
    assert not any("RMS slope" in n for n in gentle.notes())
    assert any(n.startswith("RMS slope") and "--unit" in n for n in steep.notes())


def test_units_of_a_raw_matrix(tmp_path):
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    np.savetxt(tmp_path / "um.txt", z * 1e6)
    np.save(tmp_path / "m.npy", z)
    in_um = read_surface(tmp_path / "um.txt", size=(64.0, 64.0), unit="um")
    in_m = read_surface(tmp_path / "m.npy", size=(64e-6, 64e-6), unit="m")
    assert in_um.dx == pytest.approx(1e-6) and in_um.size == pytest.approx((64e-6, 64e-6))
    pu, pm = (parameters(spectral_moments(s)) for s in (in_um, in_m))
    assert np.allclose(in_um.heights, z, rtol=1e-15, atol=1e-21)
    for name in ("sigma", "asperity_density", "asperity_radius", "alpha"):
        assert getattr(pu, name) == pytest.approx(getattr(pm, name), rel=1e-9)


def test_instrument_header_gives_size_and_unit(tmp_path):
    """Gwyddion-style plain text, read by SurfaceTopography: size in um, heights in nm."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9)
    path = tmp_path / "map.asc"
    with path.open("w") as out:
        out.write("# Channel: Height\n# Width: 64 \u00b5m\n# Height: 32 \u00b5m\n# Value units: nm\n")
        np.savetxt(out, z[:32] * 1e9)
    s = read_surface(path)
    assert s.heights.shape == (32, 64) and s.dx == pytest.approx(1e-6) and s.dy == pytest.approx(1e-6)
    assert np.allclose(s.heights, z[:32], rtol=1e-12, atol=1e-20)


def test_binary_instrument_format(tmp_path):
    """SurfaceTopography's NetCDF container (x along the first axis there), size in um."""
    from SurfaceTopography import Topography

    z = np.random.default_rng(1).normal(size=(32, 16))  # [x, y], heights in um
    Topography(z, (64.0, 32.0), unit="\u00b5m").to_netcdf(str(tmp_path / "t.nc"))
    s = read_surface(tmp_path / "t.nc")
    assert s.heights.shape == (16, 32) and s.dx == pytest.approx(2e-6) and s.dy == pytest.approx(2e-6)
    assert np.allclose(s.heights, z.T * 1e-6, rtol=1e-12, atol=0)


@pytest.mark.parametrize(
    "content, reason",
    [
        ("# Width: 10 \u00b5m\n# Height: 10 \u00b5m\n# Value units: m\n" + "\n".join(
            " ".join("nan" if (i, j) == (3, 4) else f"{(i * j) % 7}e-7" for j in range(10)) for i in range(10)),
         "undefined"),
        ("\n".join(f"{x:.6f} {math.sin(40 * x) * 1e-6:.6e}" for x in np.sort(np.random.default_rng(0).random(40))),
         "non-uniform"),
    ],
    ids=["nan_gap", "nonuniform"],
)
def test_gaps_and_nonuniform_grids_refused(tmp_path, content, reason):
    path = tmp_path / "bad.asc"
    path.write_text(content + "\n")
    with pytest.raises(SurfaceError, match=reason):
        read_surface(path)


def test_nan_in_raw_matrix_refused(tmp_path):
    z = np.ones((16, 16)) * np.arange(16)
    z[2, 2] = np.nan
    np.save(tmp_path / "gap.npy", z)
    with pytest.raises(SurfaceError, match="1 undefined"):
        read_surface(tmp_path / "gap.npy", size=(1, 1), unit="um")


@pytest.mark.parametrize(
    "setup, args, reason",
    [
        (None, ["missing.asc"], "cannot read (No such file"),
        ("junk", ["junk.xyz"], "cannot read"),
        ("one_point", ["one.npy", "--size", "1", "--unit", "um"], "at least"),
        ("flat", ["flat.npy", "--size", "16", "16", "--unit", "um"], "sigma = 0"),
        ("constant", ["constant.npy", "--size", "16", "16", "--unit", "um"], "sigma = 0"),
        ("flat", ["flat.npy"], "needs its size"),
        ("raw_text", ["raw.txt"], "no physical size"),
        ("flat", ["flat.npy", "--size", "16", "--unit", "um"], "two lengths"),
    ],
    ids=["unreadable", "unknown_format", "one_point", "all_equal", "constant", "npy_without_size", "text_without_size",
         "size_count"],
)
def test_cli_bad_input_exit_2_nothing_written(tmp_path, monkeypatch, capsys, setup, args, reason):
    monkeypatch.chdir(tmp_path)
    if setup == "junk":
        (tmp_path / "junk.xyz").write_bytes(b"\x00\x01\x02 not a surface \xff" * 20)
    elif setup == "one_point":
        np.save(tmp_path / "one.npy", np.array([1.0]))
    elif setup == "flat":
        np.save(tmp_path / "flat.npy", np.full((16, 16), 2.0) + np.arange(16))  # a tilted plane
    elif setup == "constant":  # every height equal (issue 29 item 6: it passed as sigma = 2e-21 m)
        np.save(tmp_path / "constant.npy", np.full((16, 16), 2.0))
    elif setup == "raw_text":
        np.savetxt(tmp_path / "raw.txt", np.random.default_rng(0).random((16, 16)))
    assert main(["roughness", *args, "--out", "r.yaml"]) == 2
    assert reason in capsys.readouterr().err
    assert not (tmp_path / "r.yaml").exists()


def test_cli_writes_a_scene_section(tmp_path, capsys):
    from lubecontact.scene.scene import load_scene

    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    np.save(tmp_path / "s.npy", z * 1e6)
    out = tmp_path / "r.yaml"
    assert main(["roughness", str(tmp_path / "s.npy"), "--size", "64", "64", "--unit", "um", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    for unit_text in ("sigma          = ", " m (", "1/m^2", "lambda_c", "alpha"):
        assert unit_text in printed
    scene = load_scene(out)
    direct = parameters(spectral_moments(from_array(z, (64e-6, 64e-6))))
    assert scene.roughness.sigma == pytest.approx(direct.sigma, rel=1e-9)
    assert scene.roughness.asperity_radius == pytest.approx(direct.asperity_radius, rel=1e-9)


# --- a scene's roughness.surface ----------------------------------------------------------------


def write_asc(path, z, side_um=64):
    with path.open("w") as out:
        out.write(f"# Width: {side_um} \u00b5m\n# Height: {side_um} \u00b5m\n# Value units: m\n")
        np.savetxt(out, z, fmt="%.8e")


@pytest.fixture
def scene_dir(tmp_path):
    """scenes/s.yaml naming ../maps/a.asc (relative to the scene file), and maps/b.asc."""
    (tmp_path / "scenes").mkdir()
    (tmp_path / "maps").mkdir()
    for name, seed in (("a", 21), ("b", 22)):
        z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=seed, rms=0.5e-6)
        write_asc(tmp_path / "maps" / f"{name}.asc", z)
    (tmp_path / "scenes" / "s.yaml").write_text("roughness:\n  surface: ../maps/a.asc\nmesh: {nx: 15, ny: 1}\n")
    return tmp_path


def test_scene_takes_roughness_from_the_file(scene_dir, monkeypatch):
    from lubecontact.scene.scene import load_scene

    monkeypatch.chdir(scene_dir / "maps")  # the path is relative to the scene file, not to here
    scene = load_scene(scene_dir / "scenes" / "s.yaml")
    direct = parameters(spectral_moments(read_surface(scene_dir / "maps" / "a.asc")))
    assert scene.roughness.sigma == direct.sigma
    assert scene.roughness.asperity_density == direct.asperity_density
    assert scene.roughness.asperity_radius == direct.asperity_radius
    # rebuilt from the Scene (as grids do): same surface, same case
    assert scene.replace({}).hash == scene.hash
    moved = scene.replace({"operating.speed": 1.0})
    assert moved.roughness.sigma == direct.sigma and moved.hash != scene.hash
    # another surface through an override, relative to the scene file too
    other = scene.replace({"roughness.surface": "../maps/b.asc"})
    assert other.roughness.sigma != direct.sigma and other.hash != scene.hash


def test_analysed_surface_is_kept_on_disk_by_content(scene_dir, tmp_path, monkeypatch):
    """A new process (the memory cache cleared) takes a surface's parameters from the disk
    cache without reading the file; an edited file or an unreadable cache entry is analysed
    again, and what comes back is the direct analysis."""
    from lubecontact.surfaces import measured

    monkeypatch.setenv("LUBECONTACT_CACHE", str(tmp_path / "cache"))
    surface = scene_dir / "maps" / "a.asc"
    direct = parameters(spectral_moments(read_surface(surface)))
    measured._cached.cache_clear()
    first, digest = measured.scene_roughness(surface)
    assert first == direct and len(list((tmp_path / "cache").glob("*.json"))) == 1

    def no_reading(*args, **kwargs):
        raise AssertionError("read the file instead of the cache")

    measured._cached.cache_clear()
    with monkeypatch.context() as m:
        m.setattr(measured, "read_surface", no_reading)
        assert measured.scene_roughness(surface) == (direct, digest)
        text = surface.read_text().splitlines()
        text[3] = text[3].replace("e", "1e", 1)  # one height edited
        surface.write_text("\n".join(text) + "\n")
        measured._cached.cache_clear()
        with pytest.raises(AssertionError, match="instead of the cache"):
            measured.scene_roughness(surface)
    for stored in (tmp_path / "cache").glob("*.json"):
        stored.write_text("{not json")
    measured._cached.cache_clear()
    edited = parameters(spectral_moments(read_surface(surface)))
    assert measured.scene_roughness(surface)[0] == edited != direct
    measured._cached.cache_clear()


def test_case_hash_sees_the_content_not_the_name(scene_dir):
    from lubecontact.scene.scene import load_scene

    path = scene_dir / "scenes" / "s.yaml"
    first = load_scene(path)
    (scene_dir / "maps" / "copy.asc").write_bytes((scene_dir / "maps" / "a.asc").read_bytes())
    renamed = load_scene(path, {"roughness.surface": "../maps/copy.asc"})
    assert renamed.hash == first.hash and "copy" not in renamed.canonical_yaml()
    text = (scene_dir / "maps" / "a.asc").read_text().splitlines()
    text[3] = text[3].replace("e", "1e", 1)  # one height edited
    (scene_dir / "maps" / "a.asc").write_text("\n".join(text) + "\n")
    assert load_scene(path).hash != first.hash
    # a cut-off is part of the case too
    assert load_scene(path, {"roughness.surface_cutoff": 8e-6}).hash != load_scene(path).hash


def test_scene_without_surface_keeps_its_canonical_form():
    from lubecontact.scene.scene import load_scene

    text = load_scene({}).canonical_yaml()
    assert "surface" not in text


@pytest.mark.parametrize(
    "overrides, reason",
    [
        ({"roughness.sigma": 1e-6}, "roughness.sigma = 1e-06: set by roughness.surface"),
        ({"roughness.surface": "../maps/none.asc"}, "roughness.surface = '../maps/none.asc': "),
        # a scene has no --size: it is pointed to the section `lubecontact roughness` writes (a
        # hostile run's finding, thirtieth session: it was told to "pass --size")
        ({"roughness.surface": "../maps/raw.npy"}, "needs its size (--size LX [LY]) and unit (--unit), and a scene "
                                                   "cannot give a file its size or unit; allowed: an instrument file, "
                                                   "or for a raw height matrix the roughness section that `lubecontact "
                                                   "roughness FILE --size LX [LY] --unit U --out section.yaml` writes"),
        ({"roughness.surface_cutoff": 1e-6}, "shorter than the Nyquist"),
    ],
    ids=["sigma_too", "missing_file", "raw_matrix", "cutoff_below_nyquist"],
)
def test_scene_surface_refusals(scene_dir, overrides, reason):
    from lubecontact.scene.scene import SceneError, load_scene

    np.save(scene_dir / "maps" / "raw.npy", np.zeros((16, 16)))
    with pytest.raises(SceneError) as err:
        load_scene(scene_dir / "scenes" / "s.yaml", overrides)
    assert reason in str(err.value)


def test_surface_override_on_a_scene_without_one(scene_dir):
    """A grid sweeps roughness.surface over a Table 1-like scene: the override replaces
    sigma, eta, R_peak and its path starts at the scene file's directory."""
    from lubecontact.scene.scene import SceneError, load_scene

    (scene_dir / "scenes" / "plain.yaml").write_text("roughness: {sigma: 1.0e-6, asperity_radius: 2.0e-4}\n")
    base = load_scene(scene_dir / "scenes" / "plain.yaml")
    swept = base.replace({"roughness.surface": "../maps/a.asc"})
    assert swept.roughness.sigma == load_scene(scene_dir / "scenes" / "s.yaml").roughness.sigma
    with pytest.raises(SceneError, match="roughness.surface_cutoff = 1e-05: no roughness.surface"):
        base.replace({"roughness.surface_cutoff": 1e-5})


def test_cli_profile_and_composite(tmp_path, capsys):
    """A 1-D profile in nm over 2 mm (the sine's moments are known) and a composite of two."""
    amplitude_nm, periods, n, length_um = 300.0, 8, 512, 2000.0
    x = np.arange(n) / n
    np.save(tmp_path / "p.npy", amplitude_nm * np.cos(2 * math.pi * periods * x))
    args = ["roughness", str(tmp_path / "p.npy"), "--size", str(length_um), "--unit", "nm", "--periodic"]
    assert main(args) == 0
    out = capsys.readouterr().out
    k = 2 * math.pi * periods / (length_um * 1e-9)  # --size is in --unit too: 2000 nm
    assert f"m0             = {(amplitude_nm * 1e-9) ** 2 / 2:.6g} m^2" in out
    assert f"{(amplitude_nm * 1e-9) ** 2 * k**2 / 2:.6g} (x)" in out and "n/a (profile)" in out
    assert main(args[:2] + args[1:2] + args[2:]) == 0  # the same profile twice
    out = capsys.readouterr().out
    assert "composite" in out and "V_r1 0.5, V_r2 0.5" in out
    assert main(["roughness", "a", "b", "c"]) == 2
    assert main(args + ["--out", str(tmp_path / "no" / "such" / "dir.yaml")]) == 2
    assert "cannot write" in capsys.readouterr().err


def test_fig04_alpha_holds_mccool_bandwidth_and_fig04_does_not():
    """The captions' claims from the grids themselves: alpha = (eta R sigma / 0.02036)^2."""
    from pathlib import Path

    from lubecontact.studies import figure_grids as grid

    root = Path(__file__).resolve().parents[1]

    def alphas(figure):
        g = grid.expand(figure, grid.figure_spec(figure, root / "config" / "figures"), root)
        scenes = [g.base.replace(c.set) for c in g.cases[:, 0]]
        return [(s.roughness.asperity_density * s.roughness.asperity_radius * s.roughness.sigma / 0.020358) ** 2 for s in scenes]

    assert alphas("fig04_alpha") == pytest.approx([6.03] * 4, rel=1e-3)
    paper = alphas("fig04")
    assert paper[0] == pytest.approx(1.51, rel=1e-2) and paper[-1] == pytest.approx(96.5, rel=1e-2)


def test_a_constant_surface_is_refused_in_a_scene(scene_dir):
    """Every height equal: no roughness, refused with the reason (it was taken for sigma =
    2e-21 m, R_peak 5e10 m, and solved as converged with R = inf; issue 29 item 6)."""
    write_asc(scene_dir / "maps" / "flat.asc", np.full((32, 32), 1.3e-6))
    from lubecontact.scene import SceneError, load_scene

    with pytest.raises(SceneError, match="sigma = 0"):
        load_scene(str(scene_dir / "scenes" / "s.yaml"), {"roughness.surface": "../maps/flat.asc"})


# --- input handling of `lubecontact roughness` (a hostile tester's findings) --------------------


@pytest.mark.parametrize("options", [["--size", "1", "1", "--unit", "mm"], ["--size", "1", "1"]],
                         ids=["size_and_unit", "size_only"])
def test_cli_refuses_size_for_a_file_whose_header_gives_it(tmp_path, capsys, options):
    """--size (with or without --unit) on an instrument file used to bypass its header (the
    matrix read raw, sigma 1000 times off, exit 0); refused instead."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    write_asc(tmp_path / "map.asc", z)
    assert main(["roughness", str(tmp_path / "map.asc"), *options]) == 2
    captured = capsys.readouterr()
    assert "header already gives its size and units" in captured.err and "drop --size/--unit" in captured.err
    assert captured.out == ""


def test_a_raw_matrix_with_a_plain_comment_header_still_takes_size(tmp_path):
    """np.savetxt's own '#' header names no size: the matrix is still raw, --size its size."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    np.savetxt(tmp_path / "map.txt", z * 1e6, header="heights in um, rows along y")
    surface = read_surface(tmp_path / "map.txt", size=(64.0, 64.0), unit="um")
    assert surface.dx == pytest.approx(1e-6) and np.allclose(surface.heights, z, rtol=1e-15, atol=1e-21)


@pytest.mark.parametrize("content", ["", "   \n\n\t\n", "# heights in um\n# none yet\n"], ids=["zero_bytes", "blank", "comments"])
@pytest.mark.parametrize("size", [["100"], ["100", "100"]], ids=["profile_size", "map_size"])
def test_cli_refuses_an_empty_matrix_file(tmp_path, capsys, content, size):
    """An empty file ended in a ZeroDivisionError (exit 1), or with two lengths in "a
    profile needs one length"; now it is refused as empty."""
    (tmp_path / "empty.txt").write_text(content)
    assert main(["roughness", str(tmp_path / "empty.txt"), "--size", *size, "--unit", "um"]) == 2
    assert "empty (holds no heights)" in capsys.readouterr().err


def test_an_empty_matrix_is_refused_without_a_warning(tmp_path):
    """The refusal is the only message: numpy's "input contained no data" is not shown too."""
    (tmp_path / "empty.txt").write_text("")
    np.save(tmp_path / "empty.npy", np.zeros((0, 16)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for name in ("empty.txt", "empty.npy"):
            with pytest.raises(SurfaceError, match=r"empty \(holds no heights\)"):
                read_surface(tmp_path / name, size=(100.0,), unit="um")
    with pytest.raises(SurfaceError, match=r"empty \(holds no heights\)"):
        from_array(np.zeros((0,)), (1.0,))


def test_periodic_map_reports_its_mean_removed_not_a_plane(tmp_path, capsys):
    """A periodic map loses only its mean (a plane does not wrap around): the printed
    cut-off line and the --out section's comment say so; a measured map's say plane."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    np.save(tmp_path / "s.npy", z * 1e6)
    args = ["roughness", str(tmp_path / "s.npy"), "--size", "64", "64", "--unit", "um"]
    assert main([*args, "--periodic", "--out", str(tmp_path / "periodic.yaml")]) == 0
    printed = capsys.readouterr().out
    assert "window none, mean removed)" in printed and "plane" not in printed
    assert "mean removed" in (tmp_path / "periodic.yaml").read_text()
    assert main([*args, "--out", str(tmp_path / "measured.yaml")]) == 0
    assert "window tukey, plane detrended)" in capsys.readouterr().out
    assert "plane detrended" in (tmp_path / "measured.yaml").read_text()
    assert spectral_moments(from_array(z[0], (64e-6,))).detrending == "line detrended"


@pytest.mark.parametrize("cutoff", ["0", "-1e-5", "nan", "inf"])
def test_cli_refuses_a_cutoff_that_is_not_a_positive_length(tmp_path, capsys, cutoff):
    """--cutoff 0 silently meant the automatic cut-off, while a scene's surface_cutoff: 0 is
    refused; refused here too, naming --cutoff and how to get the automatic one."""
    z = isotropic_surface(lambda q: rolled_power_law(q, 2e5, 1.5e6, 0.7), 64, 64e-6, seed=9, rms=0.5e-6)
    write_asc(tmp_path / "map.asc", z)
    assert main(["roughness", str(tmp_path / "map.asc"), f"--cutoff={cutoff}"]) == 2
    err = capsys.readouterr().err
    assert f"--cutoff {float(cutoff):g}" in err and "omit --cutoff for the automatic" in err
