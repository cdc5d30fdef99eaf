"""Command-line interface: ``archrock <subcommand> ...`` (argparse, stdlib only).

The CLI is thin: it turns options into configuration objects (:mod:`.options`), calls the
library and prints what :mod:`archrock.reports` makes of the results.

Adding a subcommand: in a module ``cli/<name>.py`` write ``add_<name>_parser(subparsers)``, which
creates the parser with ``subparsers.add_parser(...)``, adds its options (the groups of
:mod:`.options`, and :func:`finite_float` / :func:`positive_float` as argparse ``type=`` to refuse
NaN/inf), sets ``parser.set_defaults(func=run_<name>)`` and returns the parser; then list it in
:data:`SUBCOMMANDS` below.  ``run_<name>(args) -> int`` does the work; raising
:class:`~archrock.errors.ArchInputError` (or :class:`CLIError`) gives the one-line
``archrock: error: ...`` message and exit status 2.
"""

from __future__ import annotations

from . import (app, arcade, assess, codecheck, curves, defects, dem, ensemble, fragility, importdxf,
               limit, paper, records, respond, select, sensitivity, verify)
from ._parser import (SUBCOMMANDS, CLIError, emit_json, finite_float, new_parser,
                      non_negative_int, positive_float, run_command, subcommand)
from .options import (GEOMETRY_DEFAULTS, add_geometry_options, add_impact_options,
                      add_motion_options, add_spread_options, arch_from_args, model_from_args,
                      motion_from_args)

__all__ = [
    "main", "build_parser", "subcommand", "SUBCOMMANDS", "CLIError",
    "add_geometry_options", "arch_from_args", "finite_float", "positive_float",
    "non_negative_int", "emit_json", "GEOMETRY_DEFAULTS",
    "add_motion_options", "motion_from_args", "add_impact_options", "model_from_args",
    "add_spread_options",
]

# In the order shown by --help.
SUBCOMMANDS.update({
    "limit": limit.add_limit_parser,
    "random-arch": limit.add_random_arch_parser,
    "plot-limit": limit.add_plot_limit_parser,
    "respond": respond.add_respond_parser,
    "curves": curves.add_curves_parser,
    "fragility": fragility.add_fragility_parser,
    "ensemble": ensemble.add_ensemble_parser,
    "paper": paper.add_paper_parser,
    "import-dxf": importdxf.add_import_dxf_parser,
    "codecheck": codecheck.add_codecheck_parser,
    "select": select.add_select_parser,
    "assess": assess.add_assess_parser,
    "defects": defects.add_defects_parser,
    "sensitivity": sensitivity.add_sensitivity_parser,
    "dem": dem.add_dem_parser,
    "arcade": arcade.add_arcade_parser,
    "verify": verify.add_verify_parser,
    "records": records.add_records_parser,
    "app": app.add_app_parser,
})


def build_parser():
    """The top-level parser with every registered subcommand."""
    return new_parser()


def main(argv=None) -> int:
    """Run the CLI; returns the exit status (0 ok, 2 bad input, 1 missing optional dependency)."""
    return run_command(build_parser(), argv)

