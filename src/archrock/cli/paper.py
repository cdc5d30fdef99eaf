"""``archrock paper``: reproduce the paper's results into a folder."""

from __future__ import annotations


def add_paper_parser(subparsers):
    p = subparsers.add_parser(
        "paper", help="reproduce the paper's results into a folder (figures + summary.json)")
    p.add_argument("--out", metavar="DIR", default="paper-out",
                   help="output folder (default paper-out)")
    p.set_defaults(func=run_paper)
    return p


def run_paper(args) -> int:
    from ..reports.plots import PAPER_FIGURES
    from ..studies.paper import run_paper_study
    from .options import folder_arg
    from .runsettings import run_settings

    # the paper's lines (and its table) are the command's output: on stdout
    run_paper_study(figures=PAPER_FIGURES,
                    settings=run_settings(args, out=folder_arg(args.out), sink=print))
    return 0
