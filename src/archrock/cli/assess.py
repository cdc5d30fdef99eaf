"""``archrock assess``: one self-contained HTML report of an arch (and its JSON, and a PDF)."""

from __future__ import annotations

import sys
import time

from ._friction import add_friction_option, resolve_friction
from ._parser import CLIError, _int, non_negative_int
from .codecheck import add_codecheck_options, codecheck_config_from_args
from .select import DEFAULT_SUITE, add_selection_options, selection_config_from_args
from .options import (RECORDS_HELP, RECORDS_METAVAR, add_geometry_options, add_impact_options,
                      add_random_arches_options, arch_from_args, impact_spec_from_args,
                      spreads_for)


def add_assess_parser(subparsers):
    p = subparsers.add_parser(
        "assess", help="one self-contained HTML report of an arch: every analysis, with figures",
        description="Geometry, limit analysis (both directions, Fig. 3), impact coefficients, "
                    "the response to the paper's pulse, the collapse-acceleration curve with its "
                    "band over irregular arches, fragility curves (with --records), the code "
                    "check, the time-history verification under records scaled to the site "
                    "spectrum (with a spectrum and records), and every assumption with references; written as one HTML file "
                    "(figures embedded, no network needed) and the JSON behind it.")
    add_geometry_options(p)
    p.add_argument("--out", metavar="REPORT.html", default="assessment.html",
                   help="HTML report to write (default assessment.html); the JSON goes beside "
                        "it with the suffix .json")
    p.add_argument("--pdf", action="store_true",
                   help="also print the report to PDF with headless Chromium (must be on PATH)")
    p.add_argument("--durations", default="0.1,0.2,0.3,0.5,0.7,1.0", metavar="LO:HI:N|A,B,...",
                   help="pulse durations of the collapse-acceleration curve [s] "
                        "(default 0.1,0.2,0.3,0.5,0.7,1.0)")
    p.add_argument("--n-scan", type=_int, default=60, metavar="N",
                   help="amplitude grid of the curve (default 60)")
    add_random_arches_options(p, "random arches of the band and the fragility (default 12; 0: "
                                 "the nominal arch only)")
    p.set_defaults(samples=12)
    p.add_argument("--records", nargs="+", metavar=RECORDS_METAVAR, default=None,
                   help=RECORDS_HELP + "; for the time-history verification and the fragility "
                        "section (default with a site spectrum: p695-far-field where the "
                        "'records' extra is installed)")
    p.add_argument("--record-units", choices=("g", "m/s2", "cm/s2"), default=None,
                   help="units of two-column records (default g)")
    p.add_argument("--scales", default="0.2:3:15", metavar="LO:HI:N|A,B,...",
                   help="IDA scale factors (default 0.2:3:15)")
    p.add_argument("--bootstrap", type=non_negative_int, default=0, metavar="N",
                   help="fragility bootstrap resamples (0 = none, default)")
    add_impact_options(p)
    add_friction_option(p, "the whole report: the friction analysis, the governing answer, the "
                           "routing of the dynamics and the contact engine")
    add_codecheck_options(p)
    add_selection_options(p)  # the time-history verification's records, as `archrock select`
    p.add_argument("--no-progress", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=run_assess)
    return p


def run_assess(args) -> int:
    from ..groundmotion.suite import record_paths
    from ..studies.assessment import AssessConfig, assess
    from ..studies.curves import parse_range
    from ..reports.html import write_pdf, write_report

    from ..reports.drawing import _require_matplotlib

    _require_matplotlib()  # the figures need it: say so before minutes of work, not after
    if not args.out.lower().endswith((".html", ".htm")):
        raise CLIError(f"--out: {args.out!r}; allowed a file name ending in .html")
    say = (lambda msg: None) if args.no_progress else (lambda msg: print(msg, file=sys.stderr,
                                                                          flush=True))
    t0 = time.perf_counter()
    arch = arch_from_args(args)
    mu, stated = resolve_friction(args.friction)
    codecheck = codecheck_config_from_args(args)
    records = _records_or_default(args.records, codecheck.spectrum, say)
    cfg = AssessConfig(
        impact=impact_spec_from_args(args), durations=tuple(parse_range(args.durations, "durations")),
        n_scan=args.n_scan, samples=args.samples, seed=args.seed,
        spreads=spreads_for(args, arch),
        records=record_paths(records), record_units=args.record_units,
        scales=tuple(parse_range(args.scales, "scales")), bootstrap=args.bootstrap,
        codecheck=codecheck, friction=mu, selection=selection_config_from_args(args))
    from ..geometry.blocks import describe_blocks

    say(f"archrock assess: {arch.name}, {describe_blocks(arch)}; friction {stated}")
    from ..studies.runner import RunSettings

    result = assess(arch, cfg, settings=RunSettings(progress=say))
    say("rendering the report ...")
    html_path, json_path = write_report(result, args.out, progress=say)
    print(f"wrote {html_path}")
    print(f"wrote {json_path}")
    line = _timehistory_line(result)
    if line:
        print(line)
    if args.pdf:
        pdf = write_pdf(html_path, html_path.with_suffix(".pdf"))
        print(f"wrote {pdf}")
    say(f"done in {time.perf_counter() - t0:.1f} s")
    return 0


def _records_or_default(records, spectrum, say):
    """The --records given, or with a site spectrum and none given the default suite where the
    'records' extra is installed (without it the report's section says how to get it)."""
    if records or spectrum is None:
        return records
    from ..groundmotion.p695 import extra_available

    if not extra_available():
        return records
    say(f"records: {DEFAULT_SUITE} (the default with a site spectrum; --records to choose)")
    return [DEFAULT_SUITE]


def _timehistory_line(result) -> str:
    """The report's verdict against the site spectrum in one line: the time history's where it
    governs (its records meet the selection rules), the simplified kinematic check's named as
    not governing; else the kinematic check's."""
    sec = {s.key: s for s in result.sections}.get("timehistory")
    if sec is None or "rule" not in sec.data:
        return ""
    rule, kin = sec.data["rule"], sec.data["kinematic"]
    e = "inf" if rule["unbounded"] else f"{rule['value']:.3g}"
    th = f"E = {e} ({rule['rule']} of {rule['n']} records)"
    kc = "-" if kin["passed"] is None else ("pass" if kin["passed"] else "FAIL")
    if sec.data.get("governs"):
        return (f"verdict: {'pass' if rule['passed'] else 'FAIL'} by time history, {th}; the "
                f"simplified kinematic check, not governing: {kc}")
    return (f"verdict: {kc} by the kinematic check; the time history, not governing (its records "
            f"break a selection rule): {'pass' if rule['passed'] else 'FAIL'}, {th}")
