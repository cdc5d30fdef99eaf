"""The error of an option that cannot be taken as given (a conflict, a missing partner)."""

from __future__ import annotations


class OptionError(Exception):
    """Options that conflict or lack a partner (``--cv`` with ``--impact``, ``--span`` without
    ``--rise``): not an arch-input problem (:class:`archrock.errors.ArchInputError`), but the
    same exit status 2 on the command line and status 400 in the app.  The command line knows
    it as ``archrock.cli.CLIError`` (the same class)."""
