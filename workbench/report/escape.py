"""HTML text for the report: one escaping rule for every section.

:func:`esc` escapes HTML and defuses URLs (the report page must contain no ``http(s)://``
reference: it is one self-contained file).  Checked by ``tests/report/`` (the browser test finds
no external reference; the page tests read escaped text).
"""

from __future__ import annotations

import html
from typing import Any

__all__ = ["esc"]


def esc(text: Any) -> str:
    """HTML-escape ``text`` and defuse URLs (a zero-width space after ``:``, so ``://`` never appears)."""
    return html.escape(str(text)).replace("://", ":&#8203;//")
