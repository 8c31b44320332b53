"""Scenes: Table 1 defaults, canonical form and hash, overrides, and every refusal.

The truth for the defaults is the paper's Table 1 typed in here (Jackson & Angadi 2022),
plus the choices docs/DESIGN.md states for what the paper leaves open.
"""

import dataclasses
import math
import pickle
from pathlib import Path

import pytest
import yaml

from lubecontact import load_scene
from lubecontact.scene.scene import Scene, SceneError, parse_override

TABLE1_FILE = Path(__file__).resolve().parents[1] / "config" / "scenes" / "table1.yaml"

TIN = {"youngs_modulus": 41.4e9, "poisson_ratio": 0.36, "yield_strength": 14e6, "resistivity": 1.15e-7}
TABLE1 = {
    "geometry": {"radius": 0.01, "length": 0.001},
    "cylinder": TIN,
    "block": TIN,
    "roughness": {
        "sigma": 0.5e-6,
        "asperity_density": 1e9,
        "asperity_radius": 100e-6,
        "hardness_model": "wadwalkar",
        "height_std": "sigma",
    },
    "lubricant": {"viscosity": 0.1, "resistivity": 1.0e12},
    "interface": {"boundary_friction": 0.1, "barrier_height": 1.4, "open_resistance": 10.0},
    "operating": {"force": 5.0, "speed": 0.1},
    "effects": dict.fromkeys(
        [
            "hydrodynamics",
            "flow_factors",
            "cavitation",
            "asperity_contact",
            "plasticity",
            "elastic_deformation",
            "alleviation",
        ],
        True,
    )
    | dict.fromkeys(["macro_constriction", "film_conduction", "tunnelling"], False),
    "mesh": {"nx": 51, "ny": 51, "x_min": "auto", "x_max": "auto"},
    "solver": {"tolerance": 1e-6, "max_iterations": 200},
}


def _error(source, overrides=None) -> str:
    with pytest.raises(SceneError) as info:
        load_scene(source, overrides)
    return str(info.value)


def test_defaults_are_table1():
    scene = load_scene({})
    assert scene.to_dict() == TABLE1
    assert scene.geometry.radius == 0.01 and scene.block.youngs_modulus == 41.4e9
    assert scene.mesh.x_min is None and scene.mesh.x_max is None
    assert scene.effects.auto is False


def test_table1_file_equals_defaults():
    scene = load_scene(TABLE1_FILE)
    assert scene == load_scene({}) == load_scene(str(TABLE1_FILE))
    assert scene.hash == load_scene({}).hash


def test_partial_scene_is_filled():
    scene = load_scene({"roughness": {"sigma": 1e-6}, "mesh": {"ny": 1}})
    assert scene.roughness.sigma == 1e-6 and scene.mesh.ny == 1
    assert scene.roughness.asperity_density == 1e9 and scene.mesh.nx == 51


@pytest.mark.parametrize("spelling", [1e-6, 0.000001, "1e-6", "1.0E-06", "0.000001"])
def test_hash_stable_across_spellings(spelling):
    reference = load_scene({"roughness": {"sigma": 1.0e-6}})
    scene = load_scene({"roughness": {"sigma": spelling}})
    assert scene == reference
    assert scene.canonical_yaml() == reference.canonical_yaml()
    assert scene.hash == reference.hash and len(scene.hash) == 16


def test_yaml_text_spellings_hash_alike():
    texts = ["roughness: {sigma: 1e-6}", "roughness: {sigma: 0.000001}", "roughness: {sigma: 1.0e-6}"]
    hashes = {load_scene(yaml.safe_load(t)).hash for t in texts}
    assert len(hashes) == 1
    assert isinstance(yaml.safe_load(texts[0])["roughness"]["sigma"], str)  # the PyYAML trap is real


def test_int_and_whole_float_spellings():
    a = load_scene({"operating": {"force": 5}, "mesh": {"nx": 51.0, "ny": "51"}})
    assert a == load_scene({})
    assert isinstance(a.operating.force, float) and isinstance(a.mesh.nx, int)


@pytest.mark.parametrize(
    "override",
    [
        {"roughness.sigma": 0.6e-6},
        {"operating.speed": 0.0},
        {"effects.flow_factors": False},
        {"mesh.x_min": -1e-3},
        {"mesh.ny": 1},
        {"block.resistivity": 2e-7},
        {"roughness.hardness_model": "jg2005"},
    ],
)
def test_hash_changes_with_any_value(override):
    base = load_scene({})
    changed = base.replace(override)
    assert changed != base and changed.hash != base.hash


def test_dotted_overrides():
    scene = load_scene(
        TABLE1_FILE,
        {"roughness.sigma": "1e-6", "effects.hydrodynamics": "false", "mesh.nx": "101", "operating.speed": 2},
    )
    assert scene.roughness.sigma == 1e-6
    assert scene.effects.hydrodynamics is False and scene.effects.cavitation == "reynolds"
    assert scene.mesh.nx == 101 and scene.operating.speed == 2.0
    assert scene.geometry.radius == 0.01  # untouched keys keep their values


def test_replace_validates_and_keeps_original():
    base = load_scene({})
    assert base.replace({"lubricant.viscosity": "0.2"}).lubricant.viscosity == 0.2
    assert base.lubricant.viscosity == 0.1
    with pytest.raises(SceneError, match="lubricant.viscosity"):
        base.replace({"lubricant.viscosity": -1})


def test_section_override_merges_mapping():
    scene = load_scene({"mesh": {"nx": 81}}, {"mesh": {"ny": 1}})
    assert (scene.mesh.nx, scene.mesh.ny) == (81, 1)


@pytest.mark.parametrize(
    "source",
    [
        {},
        {"effects": "auto"},
        {"effects": {"cavitation": False}, "mesh": {"x_min": -1e-3, "x_max": 5e-4, "ny": 1}},
        {"roughness": {"height_std": "mccool", "sigma": "2e-6"}, "operating": {"speed": 0}},
    ],
)
def test_round_trip(source):
    scene = load_scene(source)
    text = scene.canonical_yaml()
    assert load_scene(yaml.safe_load(text)) == scene
    assert load_scene(yaml.safe_load(text)).canonical_yaml() == text


def test_canonical_yaml_sorted_and_complete():
    data = yaml.safe_load(load_scene({}).canonical_yaml())
    assert list(data) == sorted(TABLE1)
    assert all(list(section) == sorted(section) for section in data.values())
    assert data == TABLE1


def test_effects_auto():
    scene = load_scene({"effects": "auto"})
    assert scene.effects.auto is True
    flags = {k: getattr(scene.effects, k) for k in TABLE1["effects"]}
    # the paper's effects on (cavitation as its option name), the electrical path's beyond it off
    assert flags == {**TABLE1["effects"], "cavitation": "reynolds"}
    assert "effects: auto" in scene.canonical_yaml()
    assert scene.hash != load_scene({}).hash  # auto is a distinct case
    assert load_scene({}, {"effects": "auto"}) == scene


def test_effects_flag_override_ends_auto():
    scene = load_scene({"effects": "auto"}, {"effects.hydrodynamics": "false"})
    assert scene.effects.auto is False and scene.effects.hydrodynamics is False
    expected = {**TABLE1["effects"], "cavitation": "reynolds"}  # the option name of `true`
    assert all(getattr(scene.effects, k) == v for k, v in expected.items() if k != "hydrodynamics")


def test_frozen():
    scene = load_scene({})
    with pytest.raises(dataclasses.FrozenInstanceError):
        scene.roughness.sigma = 1e-6
    with pytest.raises(dataclasses.FrozenInstanceError):
        scene.roughness = None
    assert hash(scene) == hash(load_scene({}))  # usable as a dict key


# Each bad input: (scene mapping, text the message must contain: key, and what is allowed).
BAD = [
    ({"roughness": {"sigma": -1e-6}}, ["roughness.sigma", "-1e-06", ">= 1e-10 (m) (at least an atom"]),
    ({"roughness": {"sigma": 0}}, ["roughness.sigma", ">= 1e-10"]),
    ({"roughness": {"sigma": float("nan")}}, ["roughness.sigma", "not finite"]),
    ({"lubricant": {"viscosity": float("inf")}}, ["lubricant.viscosity", "not finite"]),
    ({"lubricant": {"viscosity": ".inf"}}, ["lubricant.viscosity", "not a number"]),
    ({"lubricant": {"viscosity": "thick"}}, ["lubricant.viscosity", "'thick'", "a finite number"]),
    ({"lubricant": {"viscosity": None}}, ["lubricant.viscosity", "a finite number"]),
    ({"operating": {"force": True}}, ["operating.force", "boolean"]),
    ({"operating": {"force": 0}}, ["operating.force", "> 0"]),
    ({"operating": {"speed": -0.1}}, ["operating.speed", ">= 0"]),
    ({"interface": {"boundary_friction": -0.1}}, ["interface.boundary_friction", ">= 0"]),
    ({"geometry": {"radius": 0}}, ["geometry.radius", "in [1e-10, 1000] (m) (from an atom"]),
    ({"geometry": {"length": -1e-3}}, ["geometry.length", "in [1e-10, 1000]"]),
    ({"cylinder": {"youngs_modulus": 0}}, ["cylinder.youngs_modulus", ">= 1000 (Pa) (at least a gel"]),
    ({"block": {"yield_strength": -14e6}}, ["block.yield_strength", ">= 1000 (Pa)"]),
    ({"block": {"resistivity": 0}}, ["block.resistivity", "> 0"]),
    ({"roughness": {"asperity_density": 0}}, ["roughness.asperity_density", "in [1, 1e+20] (1/m^2)"]),
    ({"roughness": {"asperity_radius": -1e-4}}, ["roughness.asperity_radius", "in [1e-10, 1000]"]),
    ({"cylinder": {"poisson_ratio": 0.5}}, ["cylinder.poisson_ratio", "(-1, 0.5)"]),
    ({"block": {"poisson_ratio": -1}}, ["block.poisson_ratio", "(-1, 0.5)"]),
    ({"roughness": {"sigma": 2e-4}}, ["roughness.sigma", "geometry.radius/100"]),
    ({"roughness": {"height_std": "mccool", "sigma": 1e-7}}, ["roughness.height_std", "mccool", "sigma"]),
    ({"roughness": {"height_std": "gauss"}}, ["roughness.height_std", "'sigma'", "'mccool'"]),
    ({"roughness": {"hardness_model": "wadwalker"}}, ["roughness.hardness_model", "did you mean 'wadwalkar'"]),
    ({"mesh": {"nx": 2}}, ["mesh.nx", ">= 3"]),
    ({"mesh": {"nx": 51.5}}, ["mesh.nx", "51.5", "whole"]),
    ({"mesh": {"nx": "many"}}, ["mesh.nx", "an integer"]),
    ({"mesh": {"ny": 2}}, ["mesh.ny", "equal to 1 or >= 3"]),
    ({"mesh": {"ny": 0}}, ["mesh.ny", "equal to 1 or >= 3"]),
    ({"mesh": {"x_min": "left"}}, ["mesh.x_min", "'auto' or a finite number"]),
    ({"mesh": {"x_max": float("nan")}}, ["mesh.x_max", "not finite"]),
    ({"solver": {"tolerance": 0}}, ["solver.tolerance", "(0, 0.1)"]),
    ({"solver": {"tolerance": 0.5}}, ["solver.tolerance", "(0, 0.1)"]),
    ({"solver": {"max_iterations": 0}}, ["solver.max_iterations", ">= 1"]),
    ({"solver": {"max_iterations": 10.5}}, ["solver.max_iterations", "whole"]),
    ({"effects": {"hydrodynamics": 1}}, ["effects.hydrodynamics", "true or false"]),
    ({"effects": {"plasticity": "yes"}}, ["effects.plasticity", "true or false"]),
    ({"effects": "some"}, ["effects", "'auto'"]),
    ({"geometry": 0.01}, ["geometry", "not a mapping"]),
    ({"roughness": {"sigam": 1e-6}}, ["roughness.sigam: unknown key; did you mean roughness.sigma?"]),
    ({"geometry": {"sigma": 1e-6}}, ["geometry.sigma: unknown key", "roughness.sigma"]),
    ({"roughnes": {"sigma": 1e-6}}, ["roughnes: unknown key", "did you mean roughness?"]),
    ({"effects": {"auto": True}}, ["effects.auto", "effects: auto"]),
    (
        {"effects": {"asperity_contact": False, "hydrodynamics": False}},
        ["nothing carries the load", "effects.hydrodynamics"],
    ),
    (
        {"effects": {"asperity_contact": False}, "operating": {"speed": 0}},
        ["nothing carries the load", "operating.speed"],
    ),
    ({"mesh": {"nx": 5}}, ["mesh.nx", "too coarse"]),
    ({"mesh": {"x_min": 1e-3, "x_max": -1e-3}}, ["mesh.x_max", "greater than mesh.x_min"]),
    ({"mesh": {"x_min": -0.02}}, ["mesh domain", "radius"]),
]


@pytest.mark.parametrize("source, expected", BAD, ids=[str(s) for s, _ in BAD])
def test_bad_input_names_key_and_allowed(source, expected):
    message = _error(source)
    for text in expected:
        assert text in message


def test_mccool_limit_matches_physics_md():
    # docs/physics.md section 9: sigma_s = 0.46134 um for Table 1; the bound is sqrt(3.717e-4)/(eta R).
    sigma_min = math.sqrt(3.717e-4) / (1e9 * 1e-4)
    assert math.sqrt(0.5e-6**2 - sigma_min**2) == pytest.approx(0.46134e-6, rel=1e-4)
    load_scene({"roughness": {"height_std": "mccool", "sigma": 1.01 * sigma_min}})
    with pytest.raises(SceneError, match="roughness.height_std"):
        load_scene({"roughness": {"height_std": "mccool", "sigma": 0.99 * sigma_min}})


def test_all_problems_in_one_error():
    message = _error({"geometry": {"radius": -1}, "lubricant": {"viscosity": "x"}, "mesh": {"ny": 2}, "oops": 1})
    lines = message.splitlines()[1:]
    assert len(lines) == 4
    for key in ["geometry.radius", "lubricant.viscosity", "mesh.ny", "oops"]:
        assert sum(key in line for line in lines) == 1


def test_override_errors_are_reported():
    message = _error({}, {"roughness.sigam": "1e-6", "mesh.nx": "[1,", "operating.force": "-5"})
    assert "did you mean roughness.sigma?" in message
    assert "mesh.nx" in message and "operating.force" in message


def test_bad_override_string_bool():
    assert "effects.cavitation" in _error({}, {"effects.cavitation": "1"})


def test_files(tmp_path):
    missing = tmp_path / "nope.yaml"
    assert str(missing) in _error(missing)
    broken = tmp_path / "broken.yaml"
    broken.write_text("roughness: {sigma: [1e-6\n")
    message = _error(broken)
    assert str(broken) in message and "invalid YAML" in message
    twice = tmp_path / "twice.yaml"
    twice.write_text("roughness:\n  sigma: 1e-6\n  sigma: 2e-6\n")
    assert "sigma given twice" in _error(twice)
    empty = tmp_path / "empty.yaml"
    empty.write_text("# only a comment\n")
    assert "empty" in _error(empty) and "{}" in _error(empty)  # issue 13: Table 1 is asked for explicitly
    empty.write_text("{}  # Table 1\n")
    assert load_scene(empty) == load_scene({})
    listing = tmp_path / "list.yaml"
    listing.write_text("- 1\n- 2\n")
    assert "mapping" in _error(listing)
    latin = tmp_path / "latin1.yaml"  # a hostile run's (thirtieth session): the codec's words alone, no file
    latin.write_bytes("operating:\n  speed: 0.1  # 20 \u00b0C\n".encode("latin-1"))
    assert str(latin) in _error(latin) and "byte 0xb0 on line 2" in _error(latin) and "save the scene as UTF-8" in _error(latin)


def test_parse_override():
    assert parse_override("roughness.sigma=1e-6") == ("roughness.sigma", 1e-6)  # decimal numbers as YAML 1.2 reads them
    assert parse_override(" effects.cavitation = false") == ("effects.cavitation", False)
    assert parse_override("mesh.x_min=-1.0e-3") == ("mesh.x_min", -1e-3)
    assert parse_override("effects=auto") == ("effects", "auto")
    key, value = parse_override("roughness.sigma=1e-6")
    assert load_scene({}, {key: value}).roughness.sigma == 1e-6
    for text in ["roughness.sigma", "=1", "mesh.nx=[1,"]:
        with pytest.raises(SceneError, match="key=value|not a valid YAML"):
            parse_override(text)


def test_scene_is_a_scene():
    assert isinstance(load_scene({}), Scene)
    assert load_scene(load_scene({}), {"mesh.ny": 1}).mesh.ny == 1


def test_pickles_for_worker_processes():
    scene = load_scene({}, {"mesh.ny": 1})
    assert pickle.loads(pickle.dumps(scene)) == scene
    with pytest.raises(SceneError) as info:
        load_scene({"mesh": {"ny": 2}})
    again = pickle.loads(pickle.dumps(info.value))
    assert again.problems == info.value.problems and str(again) == str(info.value)


# --- a grease (docs/physics.md section 21) ---------------------------------------------------

TABLE1_HASH = "8faf877ec8828574"  # config/scenes/table1.yaml before the rheology keys existed


def test_rheology_keys_at_their_defaults_leave_the_hash_alone():
    scene = load_scene(TABLE1_FILE, {"lubricant.rheology": "newtonian", "lubricant.creep_viscosity": 1e4})
    assert scene.hash == load_scene(TABLE1_FILE).hash == TABLE1_HASH
    assert "rheology" not in scene.canonical_yaml()
    grease = load_scene(TABLE1_FILE, {"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0})
    assert grease.hash != TABLE1_HASH and "yield_stress: 300.0" in grease.canonical_yaml()
    assert load_scene(grease.to_dict()) == grease  # the canonical form loads back


@pytest.mark.parametrize("overrides, words", [
    ({"lubricant.yield_stress": 300.0}, ["lubricant.yield_stress = 300.0", "'newtonian'"]),
    ({"lubricant.flow_index": 0.8}, ["lubricant.flow_index = 0.8", "herschel_bulkley"]),
    ({"lubricant.creep_viscosity": 1e5}, ["lubricant.creep_viscosity", "rheology"]),
    ({"lubricant.rheology": "bingham"}, ["lubricant.yield_stress = 0.0", "> 0 Pa"]),
    ({"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0, "lubricant.flow_index": 0.8},
     ["lubricant.flow_index = 0.8", "herschel_bulkley"]),
    ({"lubricant.rheology": "bingham", "lubricant.yield_stress": 300.0, "lubricant.creep_viscosity": 0.05},
     ["lubricant.creep_viscosity = 0.05", "> lubricant.viscosity"]),
    ({"lubricant.rheology": "herschel_bulkley", "lubricant.yield_stress": 300.0, "effects.cavitation": "jfo"},
     ["effects.cavitation = 'jfo'", "'reynolds' or 'none'"]),
    ({"lubricant.rheology": "grease"}, ["lubricant.rheology", "'grease'", "herschel_bulkley"]),
    ({"lubricant.rheology": "bingham", "lubricant.yield_stress": -1.0}, ["lubricant.yield_stress", "-1.0"]),
])
def test_a_grease_that_does_not_fit_together_is_refused_by_name(overrides, words):
    with pytest.raises(SceneError) as err:
        load_scene(TABLE1_FILE, overrides)
    for word in words:
        assert word in str(err.value)
