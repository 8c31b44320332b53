"""The IOOS compliance checker (pip compliance-checker) as a test helper: CF-1.10 findings."""

import json
import tempfile
from pathlib import Path


def cf_findings(path) -> list[str]:
    """Every error (high priority) and warning (medium) of the cf:1.10 check of ``path``."""
    from compliance_checker.runner import CheckSuite, ComplianceChecker

    CheckSuite.load_all_available_checkers()
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "report.json"
        ComplianceChecker.run_checker(str(path), ["cf:1.10"], 0, "normal", output_filename=str(report), output_format="json")
        result = json.loads(report.read_text())["cf:1.10"]
    return [
        f"{Path(path).name}: {level.split('_')[0]}: {item['name']}: {msg}"
        for level in ("high_priorities", "medium_priorities")
        for item in result[level]
        for msg in item["msgs"]
    ]
