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


DOCS = [ROOT / "README.md", ROOT / "config" / "README.md", ROOT / "bench" / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def test_every_import_the_docs_show_resolves():
    # found by a hostile run (thirtieth session): the README showed `from lubecontact.solver
    # import solve_case`, a module that no longer exists. Checked: `from lubecontact... import
    # name` and `lc.name(` after `import lubecontact as lc`
    shown = []
    for doc in DOCS:
        text = doc.read_text()
        shown += re.findall(r"from\s+(lubecontact[\w.]*)\s+import\s+(\w+)", text)
        shown += [("lubecontact", name) for name in re.findall(r"\blc\.(\w+)\(", text)]
    assert len(shown) >= 5
    code = "; ".join(f"import {module}; getattr({module}, {name!r})" for module, name in sorted(set(shown)))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_the_scene_keys_table_in_config_readme_is_current():
    """config/README.md's table of scene keys is written from the schema; a key added,
    renamed or given another default without rewriting it fails here."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "scene_keys.py"), "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_the_numbers_the_docs_quote_about_the_default_run_are_current():
    """README.md and results/README.md quote cases, chunks, figures and submissions of the
    default run, planned as the Snakefile plans them, resistances and load fractions of a few
    cheap solves and the results of cheap analyses and of the code's constants (within 1 %),
    and of the long runs' blocks the cheap results, a line
    contact's reconnect time (within 2 %), between markers that scripts/doc_numbers.py writes."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "doc_numbers.py"), "--check"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


# README.md's sections whose results and times scripts/doc_numbers.py writes (between its
# markers). What they may still spell out by hand (FIXED): names, the fixed inputs of their
# scenes and meshes, exit codes, standards and publications, the formulas and their
# constants, and the tolerances the tests hold.
GENERATED_SECTIONS = ("One operating point from the command line", "Scenes",
                      "Measured surfaces: from a profilometer file to a resistance curve", "The electrical path",
                      "What accuracy costs, and how fast it is",
                      "Time: how long a contact stays open after it stops", "Physics conventions and where the paper is silent",
                      "Flow near contact")
FIXED = (
    # scene inputs, meshes and speeds
    "Table 1", "Figs. 3–11", "Figures 3–11", "Figs. 4, 6, 8, 10", "51×51", "51 × 51", "51²", "101²", "201²", "501²",
    "2000²", "128²", "256²", "31 × 15 mesh", "1 m/s", "10 m/s", "0.01 m/s", "10⁻⁴ m/s", "0.0158 m/s", "0.5 mm/s",
    "0.01 to 1000 m/s", "speed 0", "F = 5 N", "F = 1 N", "1 N", "1000 N", "R = 2.5 mm", "R = 20 mm", "σ = 0.5 µm",
    "σ = 0.25 µm", "σ = 2 µm", "σ = 0.02 µm", "σ = 0.25, 0.5, 1, 2 µm", "2 µm / 25 µm", "σ R_peak = 0.5 µm × 100 µm",
    "η = 1e9", "R_peak = 100 µm", "μ = 0.3 Pa s", "μ = 0.1 Pa s", "0.05 Pa s", "0.2 Pa s", "0.087 Pa s", "10 Pa s",
    "100 Pa s", "100 Pa m", "ISO VG 100", "40 °C", "10 Ω", "(split = 1)", "split = 0.5", "(0–1, default 0.5)",
    "from 0.5", "128 × 128 points", "512 µm", "8 seeds", "(default 2)", "default 10⁻³", "1e12 Ω·m", "1.4 eV",
    "φ = 1 eV, s = 1 nm", "10⁶ Pa s", "10²⁰⁰",
    # codes, standards, publications
    "| 0 |", "| 1 |", "| 2 |", "| 3 |", "| 130 |", "exits 2", "exits 3", "exit 2", "CF-1.10", "YAML 1.1", "as 16",
    "as 8", "as 80", "ASTM D341", "ASTM\nD1250", "section 19", "section 20", "section 21", "section 22", "EIA-364-28", "EIA-364-27",
    "docs/physics.md section 14",
    "docs/physics.md section 17", "Wear 107, 1986", "Greenwood 1966", "Simmons 1963", "(1979)", "1979, γ = 1",
    "1.42 eV", "Phys. Rev. B 68 (2003) 035416", "0.4–2.1 pS/m", "~1000×", "~1e-4–1e-3 Ω", "some 40 formats",
    "X3P", "BDF2", "BDF1", "JG 2005", "\"87 MPa\"",
    # the paper's equations and the formulas with their constants
    "Eqs. 1–5", "Eq. 2", "Eqs. 6–13", "Eq. (16)", "Eqs. 15–17", "Eq. 19", "Eq. (8)", "m0", "m2", "m4", "m_n",
    "6π√3", "0.375", "0.02036 √α", "0.020358√α", "α ≈ 2", "α < 2", "α = 3 exactly", "1/1.25 ≤ γ ≤ 1.25",
    "γ = 1", "σ1² + σ2²", "0 < q ≤ 2π/λ_c", "4 sampling", "4 sampling intervals", "fewer than 8 points",
    "(σ = 0)", "2w′/(πE*)", "(2·split − 1)", "(1 − 2·split)", "(U/2)", "U/2", "ρ/(2Σa)", "a_i = ρ g_i dA_i/2",
    "(ρ1 + ρ2)/2", "1/r", "1/(ρ_f t)", "(2s/(3√(2mφ)))", "(4πs/h)", "(1 − cos 2πft)",
    "t = 0", "h₀^(−1/2) = h_i^(−1/2) + w′t/(6√2 πμR^(3/2))", "√(2R h_M)", "20 √(2 R h_Martin)", "√(20 R σ)",
    "max(2 b_Hertz", "[-3.5 s, 1.5 s]", "0.9 R", "≈ 2.5/X²", "(h/2)", "a/R = 1", "h = 0", "h ≤ 0", "h = −3σ",
    "h/σ = 0.5", "h/σ < 0.5", "k(0.5σ)", "exponent 1", "10⁻³ k(0.5σ)", "(h_a + h_b)/2", "k/2 to 0", "h_T(0)",
    "p ≥ 0", "θ ≤ 1", "p(1−θ) = 0", "φ = 1", "A_r/A_n > 0.1", "A_r/A_n > 1", "1.67 S_y", "≥ 1 %", "(Ctrl-C)",
    "≥ 0 m/s", "STOP > 0", "N ≥ 1", "3D", "2D", "Fig. 4", "Fig. 4/5", "Figs. 4, 6,\n8, 10", "× 51 nodes",
    "× 51 instead", "ny = 1", "m2²", "(1/m²)", "1/c", "m2_y/m2_x", "√(2mφ)", "x_min/√(2Rh)", "20 √(2R h_M)",
    "1/[(1−ν1²)/E1 + (1−ν2²)/E2]", "E/(1−ν²)",
    # tolerances the tests hold
    "within 1 %", "within 3 %", "within 5 %", "and 3 %", "1e-12", "to 10⁻⁵", "to 10⁻¹²", "order ≈ 2", "10⁻¹²",
    "(2 Hz)",
)


def without_fixed(text: str) -> str:
    """``text`` without the FIXED phrases, each matched whole: "1 m/s" leaves "0.01 m/s" alone."""
    for phrase in sorted(FIXED, key=len, reverse=True):
        before = r"(?<![\w.])" if phrase[0].isalnum() else ""
        after = r"(?!\w)" if phrase[-1].isalnum() else ""
        text = re.sub(before + r"\s+".join(map(re.escape, phrase.split("\n"))) + after, "", text)
    return text


def typed_numbers(text: str) -> list[str]:
    """The lines of ``text`` that hold a digit outside the generated blocks and markers, code
    and the FIXED phrases: a number typed by hand."""
    text = re.sub(r"<!-- run:(\w+) -->\n.*?\n<!-- /run -->", "", text, flags=re.S)
    text = re.sub(r"<!-- (\w+):(\w+) -->.*?<!-- /\1 -->", "", text, flags=re.S)
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    return [line for line in without_fixed(text).splitlines() if re.search(r"\d", line)]


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
    assert typed_numbers("takes **4.7 s at 31²** to reconnect") == ["takes **4.7 s at 31²** to reconnect"]
    assert typed_numbers("stopped from 1 m/s (Table 1)") == []
    assert typed_numbers("stopped from 0.1 m/s") == ["stopped from 0.1 m/s"]  # a fixed phrase is matched whole
    assert typed_numbers("the <!-- planned:cases -->1174<!-- /planned --> cases at 1 m/s") == []
    assert typed_numbers("<!-- run:speed -->\ntakes 4.7 s (3 steps)\n<!-- /run -->\nafter `motion.ramp=1e-3`") == []
