"""Write the table of every scene key (section, key, unit, default, allowed, meaning) into
config/README.md between its markers, from the schema itself (lubecontact.scene), so the
table can never drift from the code. ``--check`` only says whether the file is current
(exit 1 if not); tests/test_docs.py runs it.

    .venv/bin/python scripts/scene_keys.py           # rewrite the table
    .venv/bin/python scripts/scene_keys.py --check   # is it current?
"""

import argparse
import sys
from dataclasses import MISSING, fields
from pathlib import Path

from lubecontact.scene import SECTIONS

README = Path(__file__).resolve().parents[1] / "config" / "README.md"
BEGIN = "<!-- scene keys: begin (written by scripts/scene_keys.py; do not edit by hand) -->"
END = "<!-- scene keys: end -->"


def _default(field) -> str:
    value = field.default if field.default is not MISSING else field.default_factory()
    if value is None:
        return "auto" if "auto" in str(getattr(field.metadata["rule"], "allowed", "")) else "none"
    if isinstance(value, bool):
        return "true" if value else "false"
    return f"{value:g}" if isinstance(value, float) else str(value)


def table() -> str:
    """The markdown table of every key a scene may set."""
    rows = ["| key | unit | default | allowed | meaning |", "|---|---|---|---|---|"]
    for section, cls in SECTIONS.items():
        user_keys = set(cls.keys())
        for field in fields(cls):
            if field.name not in user_keys:
                continue
            rule = field.metadata["rule"]
            unit = getattr(rule, "unit", None) or ""
            allowed = str(getattr(rule, "allowed", "")).replace("|", "/")
            meaning = str(field.metadata.get("doc", "")).replace("|", "/")
            rows.append(f"| `{section}.{field.name}` | {unit} | {_default(field)} | {allowed} | {meaning} |")
    return "\n".join(rows)


def current_text(text: str) -> str:
    """``text`` with the block between the markers replaced by the table."""
    head, _, rest = text.partition(BEGIN)
    _, _, tail = rest.partition(END)
    return f"{head}{BEGIN}\n{table()}\n{END}{tail}"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if config/README.md is not current")
    args = parser.parse_args(argv)
    text = README.read_text()
    if BEGIN not in text or END not in text:
        print(f"{README}: markers missing", file=sys.stderr)
        return 1
    wanted = current_text(text)
    if args.check:
        if wanted != text:
            print(f"{README} is not current: run python scripts/scene_keys.py", file=sys.stderr)
            return 1
        return 0
    README.write_text(wanted)
    return 0


if __name__ == "__main__":
    sys.exit(main())
