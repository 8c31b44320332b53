# One netCDF per figure: its cases along the swept parameters and speed, CF attributes
# (lubecontact.studies.collect). The layout is a JSON plan (plans/collect/<figure>.json): a
# changed grid layout re-collects, and so does a change of the code that collects (its inputs
# `code`). A case file that does not read names itself in the log.


rule collect:
    input:
        cases=lambda w: [case_path(i) for i in GRIDS[w.figure].unique_cases()],
        plan=lambda w: plan_path(f"collect/{w.figure}", GRIDS[w.figure].layout()),
        # the code that reads the cases and writes the dataset (its layout, its CF attributes)
        code=["src/lubecontact/studies/collect.py", "src/lubecontact/io/case_files.py",
              "src/lubecontact/io/case_schema.py"],
    output:
        f"{RESULTS}/data/{{figure}}.nc",
    log:
        f"{RESULTS}/logs/collect/{{figure}}.log",
    conda:
        "../envs/lubecontact.yaml"
    script:
        "../scripts/collect.py"
