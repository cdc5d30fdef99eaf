"""``--dynamics`` for the studies that run the four-link model only (sensitivity, defect maps;
fragility's stripes): on an arch whose piers rock with it, one degree of freedom cannot follow the arch
and the four-link figures would be unconservative (docs/piers-dynamics.md), so those commands
refuse it unless asked; ``ensemble``, ``curves``, ``assess`` and ``fragility`` (its IDA, issue 31)
run the contact engine there."""

from __future__ import annotations

import sys

from ..errors import ArchInputError


def add_fourlink_dynamics_option(p, help: str | None = None) -> None:
    """--dynamics auto|fourlink and --friction (the routing's friction, as in respond, curves
    and ensemble: the same arch gets the same routing everywhere); ``help``: the command's own
    words for --dynamics (fragility runs the engine where auto chooses it)."""
    from ._friction import add_friction_option

    p.add_argument("--dynamics", choices=("auto", "fourlink"), default="auto",
                   help=help or
                   "auto (default): the four-link model, refused on an arch whose piers "
                   "rock with it or whose joints slide at --friction (one degree of "
                   "freedom cannot follow it: docs/piers-dynamics.md; ensemble and curves "
                   "run the contact engine there); fourlink: the four-link model anyway, "
                   "with a warning")
    add_friction_option(p, "the routing of the dynamics (the joints slide where the four-link "
                           "collapse needs more)")


def check_fourlink(nominal, args, command: str, engine_runs: bool = False):
    """Refuse ``nominal`` where one degree of freedom cannot follow it (``--dynamics auto``),
    unless the command runs the contact engine there (``engine_runs``: the choice is returned
    for it to do so); with ``--dynamics fourlink`` say so on stderr and go on.  Returns the
    DynamicsChoice (its ``to_dict()`` for the command's JSON, under "dynamics")."""
    from ..studies.enginestudy import choose_dynamics
    from .options import friction_mu

    choice = choose_dynamics(nominal, getattr(args, "dynamics", "auto"),
                             friction=friction_mu(args))
    if choice.engine and engine_runs:
        return choice
    if choice.engine:
        raise ArchInputError(
            f"--dynamics: {command} runs the four-link model only, and on this arch "
            f"{choice.reason}; its figures would be unconservative (docs/piers-dynamics.md: on "
            f"heavy piers the first collapse is 3.02 g by the four-link model, 0.71 g by the "
            f"contact engine). Use `archrock ensemble` or `archrock curves`, which run the "
            f"contact engine on this arch, or --dynamics fourlink for the four-link figures "
            f"anyway")
    if "WARNING" in choice.reason:
        print(f"archrock {command}: {choice.reason}", file=sys.stderr)
    return choice
