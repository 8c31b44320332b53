# Measured surfaces (lubecontact.surfaces): the profile spectra of config["surfaces"] with
# the cut-off of the moments marked and McCool's parameters in the legend. Their resistance
# curves are ordinary grids (config/figures/fig04_measured.yaml, roughness.surface).

SURFACE_FILES = list(config.get("surfaces") or [])
# the figure and the surface analysis it draws (reading, moments, McCool)
SURFACE_CODE = [str(p) for p in lcgrid.solver_sources("src/lubecontact", ("plotting.surfaces",))]


rule surfaces_psd:
    input:
        surfaces=SURFACE_FILES,
        code=SURFACE_CODE,
    output:
        png=report(
            f"{RESULTS}/figures/surfaces_psd.png",
            caption="../scripts/surfaces_psd_caption.rst",
            category="Measured surfaces",
        ),
        pdf=f"{RESULTS}/figures/surfaces_psd.pdf",
    log:
        f"{RESULTS}/logs/plot/surfaces_psd.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/surfaces_psd.py"
