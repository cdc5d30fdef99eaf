"""The contact engine: the arch as rigid voussoirs with contact and Coulomb friction (pymunk), a
check of the four-link model's idealisations (one mechanism, no sliding).

* :mod:`.engine` -- :class:`ContactArch`, the arch in a pymunk space (exact mass properties,
  convex pieces of each outline, static abutments, ground motion as the ground frame's body
  force);
* :mod:`.ramp` -- :func:`ramp`, the activation multiplier and hinges in each direction;
* :mod:`.motion` -- :func:`engine_respond`, the response to a pulse or record, with the
  equivalent four-link rotation;
* :mod:`.push` -- :func:`push_support`, a support spread, closed or settled slowly (a kinematic
  abutment): the thrust, the hinges and the displacement capacity;
* :mod:`.settings` -- :class:`EngineSettings` and :func:`engine_scales` (the settings in metres
  and seconds for an arch); :mod:`.convex` -- outline simplification within a tolerance and
  exact convex decomposition.

pymunk is optional (``pip install "archrock[dem]"``): it is imported when an engine is built.
"""

from .convex import convex_pieces, outline_deviation, simplify_outline
from .motion import ContactResponse, engine_respond, equivalent_rotation
from .push import PushResult, push_support
from .ramp import RampDirection, RampResult, ramp, ramp_direction, ramp_range
from .settings import (DEFAULT_FRICTION, DEFAULT_OUTLINE_TOL, FINE_CUT, EngineScales,
                       EngineSettings, engine_scales)
from .engine import ContactArch, import_pymunk
from .blocksystem import BlockSystem, block_on_ground, blocks_of_arcade, blocks_of_arch
from .rigid import (RigidArcade, RigidArch, RigidBlocks, engine_arcade, engine_arch,
                    require_engine)

__all__ = ["ContactArch", "EngineSettings", "DEFAULT_FRICTION", "RampDirection", "RampResult",
           "ramp", "ramp_direction", "ramp_range", "ContactResponse", "engine_respond", "equivalent_rotation",
           "convex_pieces", "simplify_outline", "outline_deviation", "import_pymunk",
           "DEFAULT_OUTLINE_TOL", "FINE_CUT", "EngineScales", "engine_scales", "PushResult",
           "push_support", "BlockSystem", "block_on_ground", "blocks_of_arch",
           "blocks_of_arcade", "RigidBlocks", "RigidArch", "RigidArcade", "engine_arch",
           "engine_arcade", "require_engine"]
