"""The option vocabulary of the command line and the web app: option values (argparse's
Namespace, or the one the app fills from a request's fields) -> the library's specs and arches.

One layer above the studies and below both ``cli/`` and ``app/``, so that a request is checked
as a command is without the app importing the command line (docs/architecture.md).  Needs no
numpy to import: the library is imported inside the builders.
"""

from __future__ import annotations

from .arch import (GEOMETRY_DEFAULTS, JOINTS, SHAPES, arch_from_args, fc_from_args,
                   piers_from_args, supports_from_args, undamaged_arch_from_args)
from .errors import OptionError
from .jsonsafe import json_safe
from .specs import (impact_spec_from_args, model_from_args, motion_from_args,
                    motion_spec_from_args, spreads)

__all__ = [
    "OptionError", "json_safe", "GEOMETRY_DEFAULTS", "SHAPES", "JOINTS", "arch_from_args",
    "fc_from_args", "undamaged_arch_from_args", "piers_from_args", "supports_from_args", "spreads",
    "motion_spec_from_args", "motion_from_args", "impact_spec_from_args", "model_from_args",
]
