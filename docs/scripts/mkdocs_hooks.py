"""MkDocs hooks of the documentation site (mkdocs.yml ``hooks``).

A docstring that writes an index or a unit next to another bracket (``intrados[i][0]``,
``H [N/m][m]``) reads to Markdown as a reference link, and mkdocs-autorefs warns that it finds
no such target, which ``mkdocs build --strict`` turns into a failure.  Those are text, not
links: this hook lowers that one warning to INFO when it comes from a docstring under src/, so
that a broken cross-reference in the pages of docs/ still fails the build.
"""

from __future__ import annotations

import logging

_LOGGERS = ("mkdocs.plugins.mkdocs_autorefs._internal.plugin",   # mkdocs-autorefs >= 1.3
            "mkdocs.plugins.mkdocs_autorefs.plugin", "mkdocs.plugins.mkdocs_autorefs")


class _DocstringBrackets(logging.Filter):
    def filter(self, record: logging.LogRecord) -> bool:
        msg = record.getMessage()
        if (record.levelno == logging.WARNING and "Could not find cross-reference target" in msg
                and "/src/archrock/" in msg):
            record.levelno, record.levelname = logging.INFO, "INFO"
        return True


def on_startup(command, dirty):
    for name in _LOGGERS:
        logger = logging.getLogger(name)
        if not any(isinstance(f, _DocstringBrackets) for f in logger.filters):
            logger.addFilter(_DocstringBrackets())
