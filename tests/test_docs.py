"""Every citation in the code resolves inside the repository: docs/physics.md sections by
number, docs/DESIGN.md sections by heading, and no comment cites a file the repository does
not carry or a benchmark log as its authority."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CODE = sorted(
    p for folder in ("src", "workflow", "scripts", "bench") for p in (ROOT / folder).rglob("*")
    if p.suffix in (".py", ".smk", ".yaml", ".rst", ".sh") and "__pycache__" not in p.parts
)


def headings(path: Path) -> list[str]:
    return [line.lstrip("#").strip() for line in path.read_text().splitlines() if line.startswith("#")]


def cited_sections(text: str) -> set[int]:
    """Section numbers cited as 'docs/physics.md section 4', 'sections 2 and 18', 'sections 12-13'."""
    numbers = set()
    for match in re.finditer(r"docs/physics\.md,? sections? (\d+(?:\s*(?:-|,|and)\s*\d+)*)", text):
        for a, b in re.findall(r"(\d+)(?:\s*-\s*(\d+))?", match.group(1)):
            numbers.update(range(int(a), int(b or a) + 1))
    return numbers


def test_physics_sections_cited_in_the_code_exist():
    numbered = {int(m.group(1)) for h in headings(ROOT / "docs" / "physics.md") if (m := re.match(r"(\d+)\.", h))}
    missing = {}
    for path in CODE:
        absent = cited_sections(path.read_text()) - numbered
        if absent:
            missing[str(path.relative_to(ROOT))] = sorted(absent)
    assert missing == {}


def test_design_sections_cited_in_the_code_exist():
    titles = headings(ROOT / "docs" / "DESIGN.md")
    missing = set()
    for path in CODE:
        for name in re.findall(r'docs/DESIGN\.md,? "([^"]+)"', path.read_text()):
            if not any(name in title for title in titles):
                missing.add((str(path.relative_to(ROOT)), name))
    assert missing == set()


@pytest.mark.parametrize("pattern, why", [
    (r"(?<![\w/])physics\.md", "cite docs/physics.md"),
    (r"(?<![\w/])DESIGN\.md", "cite docs/DESIGN.md"),
    (r"RESULTS\w*\.md|HISTORY\.md", "a benchmark log is no authority: state the measurement"),
    (r"\bshared/|reference/physics", "a file outside the repository"),
])
def test_no_citation_leaves_the_repository(pattern, why):
    code = [p for p in CODE if p.parts[len(ROOT.parts)] in ("src", "workflow")]  # bench/ writes the logs
    found = [f"{path.relative_to(ROOT)}:{n}" for path in code
             for n, line in enumerate(path.read_text().splitlines(), 1) if re.search(pattern, line)]
    assert found == [], why


def test_the_citation_parser_reads_what_the_code_writes():
    assert cited_sections("see docs/physics.md sections 12-13 and docs/physics.md section 4") == {4, 12, 13}
    assert cited_sections("(docs/physics.md sections 2 and 18)") == {2, 18}


def test_the_scene_keys_table_in_config_readme_is_current():
    """config/README.md's table of scene keys is written from the schema; a key added,
    renamed or given another default without rewriting it fails here."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "scene_keys.py"), "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_the_numbers_the_docs_quote_about_the_default_run_are_current():
    """README.md and results/README.md quote cases, chunks, figures and submissions of the
    default run, planned as the Snakefile plans them, and resistances of a few 51 x 51 solves
    (the solved ones within 1 %), between markers that scripts/doc_numbers.py writes."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "doc_numbers.py"), "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
