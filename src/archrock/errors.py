"""Errors raised for bad input: each message names the field and the allowed range."""


class ArchInputError(ValueError):
    """Invalid user input (geometry, ground motion, options). The message names the field."""


class EnergyGainError(ArchInputError):
    """An impact model would create kinetic energy on this geometry."""
