"""Readable reports and JSON-ready summaries of results, one module per result kind.

The command line prints what these return; the same text and objects are available to scripts.
"""

from .curves import curves_summary, format_curves
from .defects import defects_summary, format_defects
from .ensemble import format_ensemble
from .fragility import format_fragility, fragility_summary
from .limit import format_limit_table, limit_summary
from .response import format_response

__all__ = ["limit_summary", "format_limit_table", "format_response", "curves_summary",
           "format_curves", "fragility_summary", "format_fragility", "format_ensemble",
           "defects_summary", "format_defects"]
