"""Checks for tests/cluster/run_slurm.sh: compare two results/ trees by value, not by bytes.

    check_results.py compare REF CAND     every file of REF is in CAND and vice versa; netCDF
                                          values agree (xarray.testing), figures are real PNG/PDF
    check_results.py partial REF CAND     after a killed run: every case file CAND has is
                                          complete and equals REF's; prints "present missing leftovers"
    check_results.py submissions WORKDIR PREFIX
                                          reads `snakemake --dry-run` output on stdin, prints how
                                          many sbatch calls it means (a group job counts once,
                                          rules in `localrules:` of WORKDIR's Snakefile and
                                          workflow/rules/*.smk not at all) and how many of its
                                          jobs are of rules named PREFIX*

Exit status 1 with a message on the first mismatch.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import xarray as xr

# Wall-clock measurements (every variable in seconds: solve_time, the accuracy study's
# *_solve_time) differ between any two runs; everything else must agree.
TIME_UNITS = "s"
# Same code and scenes on both sides: the numbers agree to round-off (in practice bit for
# bit). rtol is far below the solver tolerance, so a case solved from another scene,
# another start or another code version shows.
RTOL = 1e-9
MAGIC = {".png": b"\x89PNG\r\n\x1a\n", ".pdf": b"%PDF-"}


def fail(message: str) -> None:
    sys.exit(f"check_results: {message}")


def files(root: Path) -> set[str]:
    """Relative paths of the visible files under ``root`` (hidden names = temp files, logs)."""
    return {
        str(p.relative_to(root))
        for p in root.rglob("*")
        if p.is_file() and not any(part.startswith(".") for part in p.relative_to(root).parts)
    }


def open_values(path: Path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        timings = [name for name, var in ds.variables.items() if var.attrs.get("units") == TIME_UNITS]
        return ds.drop_vars(timings).load()


def same_values(ref: Path, cand: Path) -> None:
    try:
        xr.testing.assert_allclose(open_values(ref), open_values(cand), rtol=RTOL, atol=0.0)
    except AssertionError as err:
        fail(f"{cand} differs from the local run's {ref}:\n{err}")


def real_figure(path: Path) -> None:
    magic = MAGIC[path.suffix]
    with path.open("rb") as fh:
        head = fh.read(len(magic))
    if head != magic or path.stat().st_size < 1000:
        fail(f"{path} is not a complete {path.suffix[1:].upper()} file")


def compare(ref_root: Path, cand_root: Path) -> None:
    ref, cand = files(ref_root), files(cand_root)
    if not any(f.endswith(".nc") for f in ref) or not any(f.endswith(".png") for f in ref):
        fail(f"the local run's {ref_root} has no netCDF or no PNG file: nothing to compare")
    if ref != cand:
        fail(
            f"file sets differ: only in the local run {sorted(ref - cand)}, "
            f"only in the cluster run {sorted(cand - ref)}"
        )
    counts = {"nc": 0, "figures": 0, "other": 0}
    for rel in sorted(ref):
        suffix = Path(rel).suffix
        if suffix == ".nc":
            same_values(ref_root / rel, cand_root / rel)
            counts["nc"] += 1
        elif suffix in MAGIC:
            real_figure(cand_root / rel)
            counts["figures"] += 1
        else:
            if (cand_root / rel).stat().st_size == 0 and (ref_root / rel).stat().st_size > 0:
                fail(f"{cand_root / rel} is empty")
            counts["other"] += 1
    print(f"{counts['nc']} netCDF files equal in value, {counts['figures']} figures, {counts['other']} other files")


def partial(ref_root: Path, cand_root: Path) -> None:
    """Cases left by an interrupted run must each be complete; temp files are counted."""
    ref_cases = {f for f in files(ref_root) if f.endswith(".nc") and f.split("/")[0] == "cases"}
    if not ref_cases:
        fail(f"no case files under {ref_root}/cases in the local run")
    present = {f for f in files(cand_root) if f.endswith(".nc") and f.split("/")[0] == "cases"}
    strangers = present - ref_cases
    if strangers:
        fail(f"case files the local run does not have: {sorted(strangers)}")
    for rel in sorted(present):
        try:
            same_values(ref_root / rel, cand_root / rel)
        except (OSError, ValueError) as err:  # truncated/unreadable netCDF: not complete
            fail(f"{cand_root / rel} looks like a case file but does not open: {err}")
    leftovers = [p for p in (cand_root / "cases").rglob(".*.tmp")] if (cand_root / "cases").is_dir() else []
    print(len(present), len(ref_cases - present), len(leftovers))


def local_rules(workdir: Path) -> set[str]:
    """Rule names declared with ``localrules:`` in the Snakefile and workflow/rules/*.smk."""
    names: set[str] = set()
    for source in [workdir / "Snakefile", *sorted((workdir / "workflow" / "rules").glob("*.smk"))]:
        if source.is_file():
            for match in re.finditer(r"^localrules:([^\n]*(?:\n[ \t]+[^\n]*)*)", source.read_text(), flags=re.M):
                names.update(re.findall(r"\w+", match.group(1)))
    return names


def submissions(dry_run: str, local: set[str], prefix: str) -> tuple[int, int]:
    """(sbatch calls, jobs of rules named prefix*) of a dry run."""
    groups = len(re.findall(r"^\S.*\bGroup job \S+", dry_run, flags=re.M))
    # ungrouped jobs print "rule NAME:" at the start of a line, grouped ones indented
    singles = [name for name in re.findall(r"^rule (\w+):", dry_run, flags=re.M) if name not in local]
    matching = re.findall(rf"^\s*rule {re.escape(prefix)}\w*:", dry_run, flags=re.M)
    return groups + len(singles), len(matching)


def main(argv: list[str]) -> None:
    if argv[:1] == ["submissions"] and len(argv) == 3:
        print(*submissions(sys.stdin.read(), local_rules(Path(argv[1])), argv[2]))
    elif len(argv) == 3 and argv[0] in ("compare", "partial"):
        ref, cand = Path(argv[1]), Path(argv[2])
        for root in (ref, cand):
            if not root.is_dir():
                fail(f"{root} is not a directory")
        (compare if argv[0] == "compare" else partial)(ref, cand)
    else:
        fail(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
