"""Result records are frozen: their arrays are read-only views, so a caller cannot change a result
after the fact (the caller's own arrays stay writable)."""

from __future__ import annotations

import dataclasses

import numpy as np


def readonly_arrays(record) -> None:
    """Replace every ndarray field of a frozen dataclass ``record`` by a read-only view of it."""
    for f in dataclasses.fields(record):
        value = getattr(record, f.name)
        if isinstance(value, np.ndarray) and value.flags.writeable:
            view = value.view()
            view.flags.writeable = False
            object.__setattr__(record, f.name, view)


class EngineRecord:
    """Base of the contact engine's run records (frozen dataclasses with a ``status`` field):
    read-only arrays, and ``collapsed`` read from the status."""

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def collapsed(self) -> bool:
        return self.status == "collapsed"
