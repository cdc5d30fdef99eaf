"""``archrock records``: the built-in FEMA P695 record sets, or one suite's records."""

from __future__ import annotations

from ._parser import CLIError, emit_json


def add_records_parser(subparsers):
    p = subparsers.add_parser(
        "records", help="list the built-in FEMA P695 record sets, or one set's records",
        description="Without a name: the built-in suites (FEMA P695 far-field, near-field with "
                    "and without velocity pulses; optional extra 'records'). With a suite "
                    "name: each record (id, event, year, station, magnitude, distance, PGA, "
                    "PGV, DT, duration). A suite name works wherever --records takes files, "
                    "and SUITE/ID (p695-far-field/1a: record 1, component a) wherever --record "
                    "takes a file; NAME-normalized gives the set's normalised accelerations.")
    p.add_argument("suite", nargs="?", default=None, metavar="SUITE",
                   help="p695-far-field, p695-near-field-pulse or p695-near-field-no-pulse "
                        "(each also NAME-normalized)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run_records)
    return p


def run_records(args) -> int:
    from ..groundmotion.p695 import (EXTRA_HINT, SUITES, extra_available, is_suite,
                                     suite_records)

    if args.suite is None:
        have = extra_available()
        if args.json:
            emit_json({"suites": [{"name": k, "description": v[1]} for k, v in SUITES.items()],
                       "installed": have, "install": None if have else EXTRA_HINT})
            return 0
        for name, (_, what) in SUITES.items():
            print(f"{name:26s} {what}")
        print("each also as NAME-normalized (the set's normalised accelerations)")
        if not have:
            print(f"not installed: {EXTRA_HINT}")
        return 0
    if not is_suite(args.suite):
        raise CLIError(f"suite: {args.suite!r}; allowed {', '.join(SUITES)} (each also "
                       f"NAME-normalized)")
    rows = suite_records(args.suite)  # without the extra: one line saying how to get it
    if args.json:
        emit_json({"suite": args.suite, "records": [r.to_dict() for r in rows]})
        return 0
    print(format_suite(args.suite, rows))
    return 0


def format_suite(name: str, rows) -> str:
    """The table of a suite's records, one line each."""
    head = (f"{'id':>4} {'event':22s} {'year':>4} {'station':24s} {'M':>4} {'R km':>5} "
            f"{'PGA g':>6} {'PGV cm/s':>8} {'DT s':>6} {'dur s':>6}")
    lines = [f"{name}: {len(rows)} records", head]
    for r in rows:
        lines.append(f"{r.record:>3}{r.component} {r.event[:22]:22s} {r.year:>4} "
                     f"{r.station[:24]:24s} {r.magnitude:4.1f} {r.distance_km:5.1f} "
                     f"{r.pga_g:6.3f} {r.pgv_max_cm_s:8.1f} {r.dt:6.4f} {r.duration:6.2f}")
    lines.append("PGA: the component's own; PGV: the record's (the set's metadata); R: closest "
                 "distance to the rupture plane")
    return "\n".join(lines)
