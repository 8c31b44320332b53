"""The numbers of issue 10's note: resistance at rest (spots / cluster / total) for Table 1 and
R = 2.5 mm, and the top (10 m/s, the highest speed) of each resistance figure's curves with the
full electrical path, on the figures' 51 x 51 mesh. Usage: PYTHONPATH=src python bench/full_path_numbers.py"""

import lubecontact as lc

FULL = {"effects.macro_constriction": True, "effects.film_conduction": True}
SWEEPS = {"fig04": ("roughness.sigma", [0.25e-6, 0.5e-6, 1.0e-6, 2.0e-6]),
          "fig06": ("geometry.radius", [0.0025, 0.005, 0.01, 0.02]),
          "fig08": ("operating.force", [1.0, 2.0, 5.0, 10.0, 20.0]),
          "fig10": ("lubricant.viscosity", [0.01, 0.03, 0.1, 0.3])}


def parts(ds):
    return " / ".join(f"{float(ds[k]):.3g}" for k in ("spot_resistance", "macro_constriction_resistance",
                                                      "film_resistance", "contact_resistance"))


def main():
    print("at rest: spots / cluster / film / total (ohm); paper model")
    for label, extra in (("Table 1", {}), ("R = 2.5 mm", {"geometry.radius": 0.0025})):
        scene = lc.load_scene("config/scenes/table1.yaml", {"operating.speed": 0.0, **extra})
        full, paper = lc.solve(scene.replace(FULL)), lc.solve(scene)
        print(f"  {label:11s} {parts(full)}   paper {float(paper.contact_resistance):.3g}  "
              f"validity {full.attrs['validity']}")
    print("top of each figure (10 m/s): full path parts; paper model")
    for figure, (key, values) in SWEEPS.items():
        for value in values:
            scene = lc.load_scene("config/scenes/table1.yaml", {key: value, "operating.speed": 10.0})
            full, paper = lc.solve(scene.replace(FULL)), lc.solve(scene)
            print(f"  {figure} {key} = {value:g}: {parts(full)}   paper {float(paper.contact_resistance):.3g}  "
                  f"converged {int(full.converged)}/{int(paper.converged)}  {full.attrs['validity']}")


if __name__ == "__main__":
    main()
