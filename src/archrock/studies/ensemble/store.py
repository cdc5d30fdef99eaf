"""An ensemble's output folder: now :mod:`archrock.studies.store`, the one store of the studies
(this name is that very module, kept for 0.6's import path)."""

import sys

from .. import store as _store

sys.modules[__name__] = _store
