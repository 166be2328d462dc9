"""axe-core in the page: the WCAG 2.1 A and AA rules, every impact, as the accessibility tests run them.

axe-playwright-python (requirements-test.txt) carries axe-core itself (its wheel's axe.min.js), so
the check runs with no network, on the local page, the offline page from file:// and the notebook.
"""
from __future__ import annotations

import pytest

TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
# A rule that cannot apply, turned off by name with the reason. None so far: every rule of the
# four tags runs, and the canvases get text alternatives rather than an exemption.
RULES_OFF: dict[str, str] = {}


def violations(page, context=None) -> list[str]:
    """Each WCAG 2.1 A/AA violation axe-core finds on the page (or in `context`), one line each."""
    axe = pytest.importorskip("axe_playwright_python.sync_playwright",
                              reason="axe-playwright-python is not installed (pip install -r requirements-test.txt)")
    options = {"runOnly": {"type": "tag", "values": TAGS}, "resultTypes": ["violations"],
               "rules": {rule: {"enabled": False} for rule in RULES_OFF}}
    found = axe.Axe().run(page, context=context, options=options).response["violations"]
    return [f"{v['id']} ({v['impact']}): {v['help']} at {', '.join(str(n['target']) for n in v['nodes'][:5])}"
            f" ({len(v['nodes'])} nodes) {v['nodes'][0].get('failureSummary', '')[:200]!r}" for v in found]
