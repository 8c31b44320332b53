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
    default run, planned as the Snakefile plans them, resistances and load fractions of a few
    cheap solves (within 1 %), and of the long runs' blocks the cheap results, a line
    contact's reconnect time (within 2 %), between markers that scripts/doc_numbers.py writes."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "doc_numbers.py"), "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


# README.md's sections whose results and times scripts/doc_numbers.py writes (between its
# markers). What they may still spell out by hand: names, the fixed inputs of their scenes,
# exit codes, the formulas and the tolerances the tests hold.
GENERATED_SECTIONS = ("What accuracy costs, and how fast it is", "Time: how long a contact stays open after it stops")
FIXED = ("Table 1", "Figs. 3–11", "51×51", "51 × 51", "1 m/s", "(1 − cos 2πft)", "t = 0", "(default 2)",
         "default 10⁻³", "10 Ω by default", "exits 3", "exit 2", "BDF2", "BDF1", "docs/physics.md section 14", "docs/physics.md section 17",
         "h₀^(−1/2) = h_i^(−1/2) + w′t/(6√2 πμR^(3/2))", "√(2R h_M)", "within 1 %", "to 10⁻⁵", "order ≈ 2", "10⁻¹²", "(2 Hz)")


def typed_numbers(text: str) -> list[str]:
    """The lines of ``text`` that hold a digit outside the generated blocks and markers, code
    and the FIXED phrases: a number typed by hand."""
    text = re.sub(r"<!-- run:(\w+) -->\n.*?\n<!-- /run -->", "", text, flags=re.S)
    text = re.sub(r"<!-- (\w+):(\w+) -->.*?<!-- /\1 -->", "", text, flags=re.S)
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    for phrase in FIXED:
        text = text.replace(phrase, "")
    return [line for line in text.splitlines() if re.search(r"\d", line)]


def section(text: str, heading: str) -> str:
    start = text.index(f"\n## {heading}")
    end = text.find("\n## ", start + 1)
    return text[start:] if end < 0 else text[start:end]


@pytest.mark.parametrize("heading", GENERATED_SECTIONS)
def test_the_generated_sections_type_no_number(heading):
    """Every result and time in these sections comes from a run (scripts/doc_numbers.py
    --runs); a number typed into their prose is found here."""
    assert typed_numbers(section((ROOT / "README.md").read_text(), heading)) == []


def test_a_typed_number_is_found_and_a_generated_one_is_not():
    assert typed_numbers("takes **4.7 s at 51²** to reconnect") == ["takes **4.7 s at 51²** to reconnect"]
    assert typed_numbers("the <!-- planned:cases -->1174<!-- /planned --> cases at 1 m/s") == []
    assert typed_numbers("<!-- run:speed -->\ntakes 4.7 s (3 steps)\n<!-- /run -->\nafter `motion.ramp=1e-3`") == []
