"""The scene gallery (config/scenes/*.yaml): every scene loads, solves on a coarse mesh,
converges, and makes physical sense for what it stands for."""

from pathlib import Path

import pytest

import lubecontact as lc
from lubecontact.physics.materials import effective_modulus
from lubecontact.physics.viscosity_temperature import density

SCENES = Path("config/scenes")
GALLERY = sorted(p.stem for p in SCENES.glob("*.yaml") if p.stem != "table1")
COARSE = {"mesh.nx": 41, "mesh.ny": 11}


def ran(ds) -> set:
    return set(ds.attrs["effects_run"].split(","))


@pytest.fixture(scope="module")
def solved():
    cache = {}

    def solve(name):
        if name not in cache:
            scene = lc.load_scene(SCENES / f"{name}.yaml", COARSE)
            cache[name] = (scene, lc.solve(scene))
        return cache[name]

    return solve


def test_the_gallery_has_the_promised_scenes():
    assert {"dry_static", "smooth_full_film", "gold_connector_pao", "gold_connector_pfpe", "auto_effects",
            "measured_ground", "gold_connector_vg32_datasheet"} <= set(GALLERY)


@pytest.mark.parametrize("name", GALLERY)
def test_scene_solves_and_balances_its_load(solved, name):
    scene, ds = solved(name)
    force = scene.operating.force
    assert ds["converged"].item() == 1
    assert abs(ds["force_residual"].item()) <= scene.solver.tolerance * force
    assert ds["contact_force"].item() + ds["fluid_force"].item() == pytest.approx(force, rel=1e-5)
    assert 0.0 <= ds["friction_coefficient"].item() < 1.0
    resistance = ds["contact_resistance"].item()
    assert resistance > 0.0
    assert (resistance > scene.interface.open_resistance) == (ds["open_circuit"].item() == 1)


def test_dry_static_is_carried_by_the_asperities_alone(solved):
    scene, ds = solved("dry_static")
    assert "hydrodynamics" not in ran(ds)
    assert ds["fluid_force"].item() == 0.0
    assert ds["friction_coefficient"].item() == pytest.approx(scene.interface.boundary_friction, rel=1e-5)
    sigma = scene.roughness.sigma  # docs/physics.md section 9: dry Table 1 contact, centre h/sigma ~ -0.66 to -0.69
    assert -1.0 < ds["central_film_thickness"].item() / sigma < -0.4


def test_smooth_full_film_is_an_open_circuit_with_a_martin_like_film(solved):
    scene, ds = solved("smooth_full_film")
    assert ran(ds) == {"hydrodynamics", "cavitation", "elastic_deformation"}
    assert ds["open_circuit"].item() == 1 and ds["contact_force"].item() == 0.0
    s = scene  # Martin (docs/physics.md section 4) bounds a finite, side-leaking cylinder's film from above
    martin = 4.9 * s.lubricant.viscosity * 0.5 * s.operating.speed * s.geometry.radius * s.geometry.length / s.operating.force
    assert 0.3 * martin < ds["min_film_thickness"].item() < martin
    # Couette friction of the full film, 7.283 mu u_m sqrt(2R/h) per length, at the film found
    shear = 7.283 * s.lubricant.viscosity * 0.5 * s.operating.speed * (2 * s.geometry.radius / ds["min_film_thickness"].item()) ** 0.5
    assert ds["friction_coefficient"].item() == pytest.approx(shear * s.geometry.length / s.operating.force, rel=0.5)


def test_gold_connectors_are_gold_and_the_pfpe_film_carries_more(solved):
    pao, ds_pao = solved("gold_connector_pao")
    pfpe, ds_pfpe = solved("gold_connector_pfpe")
    for s in (pao, pfpe):
        assert s.cylinder.resistivity == pytest.approx(2.2e-8)  # CRC Handbook, 20 C
        assert effective_modulus(s) == pytest.approx(79e9 / (2 * (1 - 0.42**2)), rel=1e-12)
        assert 100e6 <= s.cylinder.yield_strength <= 200e6
    assert 0.03 <= pao.lubricant.viscosity <= 0.07 and 0.1 <= pfpe.lubricant.viscosity <= 0.3
    # same contact, only the viscosity differs: the more viscous oil lifts more and conducts less
    assert ds_pfpe["fluid_force"].item() > ds_pao["fluid_force"].item()
    assert ds_pfpe["contact_resistance"].item() > ds_pao["contact_resistance"].item()


def test_datasheet_oil_follows_the_temperature(solved):
    """The VG 32 datasheet scene at 35 C: its kinematic viscosity lies between its 32 mm^2/s at
    40 C and the 68 of the next grade but one; the same contact at a 15 C cold aisle is more
    viscous, lifts more and conducts less."""
    hot, ds_hot = solved("gold_connector_vg32_datasheet")
    assert 32e-6 < hot.lubricant.viscosity / density(870.0, 35.0) < 68e-6
    assert "temperature: 35.0" in ds_hot.attrs["scene"] and "kinematic_viscosity_40: 32.0" in ds_hot.attrs["scene"]
    cold = hot.replace({"operating.temperature": 15})
    ds_cold = lc.solve(cold)
    assert cold.lubricant.viscosity > 2 * hot.lubricant.viscosity
    assert ds_cold["fluid_force"].item() > ds_hot["fluid_force"].item()
    assert ds_cold["contact_resistance"].item() > ds_hot["contact_resistance"].item()


def test_auto_scene_records_its_decisions(solved):
    scene, ds = solved("auto_effects")
    assert scene.effects.auto
    assert "hydrodynamics" not in ran(ds)
    assert "hydrodynamics: off: fluid load share" in ds.attrs["notes"]
    assert "effects: auto" in ds.attrs["scene"]


def test_cli_prints_the_effects_that_ran(tmp_path, capsys):
    from lubecontact.cli.main import main

    out = tmp_path / "case.nc"
    code = main(["solve", str(SCENES / "dry_static.yaml"), "--set", "mesh.nx=41", "--set", "mesh.ny=11", "--out", str(out)])
    assert code == 0 and out.exists()
    assert "effects run: asperity_contact,plasticity,elastic_deformation,alleviation" in capsys.readouterr().out


def test_tin_connector_has_the_whole_path(solved):
    """Table 1 with the full electrical path at 0.1 m/s: cluster term in series, a finite film
    in parallel, ~0.2 mOhm, a closed contact (10 ohm threshold)."""
    scene, ds = solved("tin_connector")
    assert {"macro_constriction", "film_conduction"} <= ran(ds) and "alleviation" not in ran(ds)
    assert 0.0 < float(ds.macro_constriction_resistance) < float(ds.contact_resistance) < 1e-3
    assert 1e9 < float(ds.film_resistance) < 1e14 and int(ds.open_circuit) == 0
