# One netCDF per figure: its cases along the swept parameters and speed, CF attributes
# (lubecontact.grid.collect). Plain-Python params: a changed grid layout re-collects.


rule collect:
    input:
        lambda w: [case_path(i) for i in GRIDS[w.figure].unique_cases()],
    output:
        "results/data/{figure}.nc",
    params:
        layout=lambda w: GRIDS[w.figure].layout(),
    log:
        "results/logs/collect/{figure}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/collect.py"
