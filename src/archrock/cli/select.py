"""``archrock select``: records chosen and scaled for a site spectrum, by the codes' rules for
time-history analysis (NTC 2018 par. 3.2.3.6, EN 1998-1 par. 3.2.3.1.2)."""

from __future__ import annotations

from pathlib import Path

from ._parser import CLIError, _int, emit_json, finite_float
from .codecheck import add_spectrum_options, spectrum_from_args
from .options import RECORDS_HELP, RECORDS_METAVAR, folder_arg, say_written

#: the suite --records stands for when it is not given (with the 'records' extra)
DEFAULT_SUITE = "p695-far-field"


def add_select_parser(subparsers):
    p = subparsers.add_parser(
        "select", help="records chosen and scaled for a site spectrum (NTC 2018 / EN 1998-1)",
        description="Choose --count records (default 7) and scale them so that the mean of "
                    "their 5%% spectra is nowhere below 90%% of the site spectrum over the "
                    "period range (default 0.15-2.0 s, NTC 2018 par. 3.2.3.6), every factor "
                    "within --scale-bounds and the mean PGA of the scaled set at least the "
                    "site's a_g S (EN 1998-1 par. 3.2.3.1.2); at most one component per FEMA "
                    "P695 record (station). Records by spectral shape, then the least common "
                    "adjustment. "
                    "Method: docs/curves.md, Records for a site spectrum.")
    p.add_argument("--records", nargs="+", default=None, metavar=RECORDS_METAVAR,
                   help=f"candidate {RECORDS_HELP}; default {DEFAULT_SUITE} with the 'records' "
                        f"extra")
    p.add_argument("--units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of two-column records (default g)")
    add_spectrum_options(p)
    add_selection_options(p)
    p.add_argument("--out", metavar="DIR",
                   help="write selection.json, selection.csv and spectra.png (the figure needs "
                        "matplotlib) to DIR")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run_select)
    return p


def add_selection_options(p):
    """--count, --period-range, --scale-bounds, --both-components: the selection's options,
    here and in ``archrock assess`` (read by :func:`selection_config_from_args`)."""
    g = p.add_argument_group("selection")
    g.add_argument("--count", type=_int, default=7, metavar="N",
                   help="records to choose (default 7, the codes' least for the mean rule)")
    g.add_argument("--period-range", nargs=2, type=finite_float, default=(0.15, 2.0),
                   metavar=("LO", "HI"), help="periods [s] where the mean must reach 90%% of "
                                              "the target (default 0.15 2.0)")
    g.add_argument("--scale-bounds", nargs=2, type=finite_float, default=(0.5, 4.0),
                   metavar=("LO", "HI"), help="least and largest scale factor (default 0.5 4)")
    g.add_argument("--both-components", action="store_true",
                   help="allow both components of one P695 record, a station (default: one per station)")


def _records(args):
    """The candidate records: --records, or the default suite with the extra."""
    from ..groundmotion.p695 import EXTRA_HINT, extra_available
    from ..groundmotion.suite import read_records

    items = args.records
    if items is None:
        if not extra_available():
            raise CLIError(f"--records: needed (the default {DEFAULT_SUITE} needs the FEMA "
                           f"P695 sets: {EXTRA_HINT})")
        items = [DEFAULT_SUITE]
    return list(read_records(items, units=args.units).records)


#: the selection's fields that are options here, as the messages name them
_FIELDS = ("count", "period_range", "scale_bounds")


def _as_option(exc):
    """An ArchInputError about a selection field, said with the option's name."""
    field, _, rest = str(exc).partition(":")
    if field in _FIELDS:
        return CLIError(f"--{field.replace('_', '-')}:{rest}")
    return exc


def selection_config_from_args(args):
    """The SelectionConfig of :func:`add_selection_options`' options."""
    from ..errors import ArchInputError
    from ..studies.selection import SelectionConfig

    try:
        return SelectionConfig(count=args.count, period_range=tuple(args.period_range),
                               scale_bounds=tuple(args.scale_bounds),
                               one_per_station=not args.both_components)
    except ArchInputError as exc:
        raise _as_option(exc) from None


def _write(out: Path, selection, records, spectrum) -> list:
    """selection.json, selection.csv and (with matplotlib) spectra.png in ``out``."""
    import json

    from ..options import json_safe
    from ..reports.selection import selection_csv, selection_figure, selection_json

    out.mkdir(parents=True, exist_ok=True)
    (out / "selection.json").write_text(json.dumps(json_safe(selection_json(selection)),
                                                   indent=2, allow_nan=False) + "\n")
    (out / "selection.csv").write_text(selection_csv(selection))
    written = [out / "selection.json", out / "selection.csv"]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("figure skipped: matplotlib is not installed (pip install 'archrock[plot]')")
        return written
    selection_figure(selection, out / "spectra.png", motions=records, spectrum=spectrum)
    return written + [out / "spectra.png"]


def run_select(args) -> int:
    from ..reports.selection import format_selection, selection_json
    from ..studies.selection import select_for_site

    spectrum = spectrum_from_args(args)
    if spectrum is None:
        raise CLIError("--ag or --spectrum: a site spectrum is needed (the target of the "
                       "selection)")
    config = selection_config_from_args(args)
    out = folder_arg(args.out)
    records = _records(args)
    from ..errors import ArchInputError

    try:
        selection = select_for_site(spectrum, records, config)
    except ArchInputError as exc:
        raise _as_option(exc) from None
    written = _write(Path(out), selection, records, spectrum) if out else []
    if args.json:
        emit_json(selection_json(selection))
    else:
        print(format_selection(selection))
        say_written(*written)
    return 0
