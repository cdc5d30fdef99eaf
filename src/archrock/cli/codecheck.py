"""``archrock codecheck``: the code's kinematic analysis of the arch's collapse mechanisms."""

from __future__ import annotations

import sys

from ._parser import CLIError, _int, emit_json, finite_float, non_negative_int
from .options import add_geometry_options, arch_from_args


def add_spectrum_options(p):
    """The site spectrum: --spectrum FILE (T [s], Se [g]) or the code's parameters."""
    g = p.add_argument_group(
        "site spectrum", "elastic spectrum at 5%% damping: a two-column file or the code's "
                         "parameters (NTC 2018 par. 3.2.3.2.1, or EN 1998-1 with --ec8-type)")
    g.add_argument("--spectrum", metavar="FILE", help="two-column text file: T [s] from 0, Se [g]")
    g.add_argument("--ag", type=finite_float, metavar="G", help="ground acceleration on rock [g]")
    g.add_argument("--f0", type=finite_float, metavar="F0", help="NTC: spectral amplification F0")
    g.add_argument("--tc-star", type=finite_float, metavar="S", help="NTC: period Tc* [s]")
    g.add_argument("--soil", choices=("A", "B", "C", "D", "E"), default="A",
                   help="soil (ground) category (default A)")
    g.add_argument("--topography", default="T1", metavar="T1-T4|S_T",
                   help="NTC topographic category T1-T4 or the factor S_T (default T1)")
    g.add_argument("--ec8-type", type=_int, choices=(1, 2), default=None,
                   help="use the EN 1998-1 spectrum of this type (with --ag, --soil)")
    return p


def spectrum_from_args(args):
    from ..studies.codecheck import SiteSpectrum

    if args.spectrum:
        if args.ag is not None or args.f0 is not None or args.tc_star is not None:
            raise CLIError("--spectrum: cannot be combined with --ag/--f0/--tc-star")
        return SiteSpectrum.from_file(args.spectrum)
    if args.ag is None:
        if args.f0 is not None or args.tc_star is not None or args.ec8_type is not None:
            raise CLIError("--ag: needed with --f0/--tc-star/--ec8-type")
        return None
    if args.ec8_type is not None:
        return SiteSpectrum.ec8(args.ag, args.soil, args.ec8_type)
    if args.f0 is None or args.tc_star is None:
        raise CLIError("--f0 and --tc-star: needed with --ag for the NTC spectrum (or give "
                       "--ec8-type 1|2)")
    topo = args.topography
    if topo not in ("T1", "T2", "T3", "T4"):
        try:
            topo = float(topo)
        except ValueError:
            raise CLIError(f"--topography: {topo!r}; allowed T1-T4 or a number 1 <= S_T <= 1.4") from None
    return SiteSpectrum.ntc(args.ag, args.f0, args.tc_star, args.soil, topo)


def add_codecheck_options(p):
    g = p.add_argument_group("code check")
    # --fc is the masonry's compressive strength (the arch options); the code's confidence
    # factor FC takes its full name
    g.add_argument("--confidence-factor", type=finite_float, default=1.35, metavar="FC",
                   help="confidence factor FC (default 1.35, knowledge level LC1)")
    g.add_argument("--q", type=finite_float, default=2.0, metavar="Q",
                   help="behaviour factor of the linear check (default 2.0)")
    g.add_argument("--control", default="centre", metavar="centre|I",
                   help="control point: mass centre of the moving voussoirs (default) or voussoir I")
    add_spectrum_options(p)
    return p


def codecheck_config_from_args(args):
    from ..studies.codecheck import CodeCheckConfig

    control = args.control
    if control != "centre":
        try:
            control = non_negative_int(control)
        except Exception:
            raise CLIError(f"--control: {args.control!r}; allowed 'centre' or a voussoir index >= 0") from None
    if getattr(args, "fc", None) is not None:
        # until 0.7 --fc was this command's confidence factor: say what it is now, so that an
        # old script's --fc 1.35 does not pass unnoticed as a strength of 1.35 MPa
        print(f"archrock: note: --fc {args.fc:g} is the masonry's compressive strength [MPa]; "
              f"the confidence factor is --confidence-factor (now {args.confidence_factor:g})",
              file=sys.stderr)
    return CodeCheckConfig(fc=args.confidence_factor, q=args.q, control=control, spectrum=spectrum_from_args(args))


def add_codecheck_parser(subparsers):
    p = subparsers.add_parser(
        "codecheck", help="code check: kinematic analysis of local mechanisms (NTC 2018 / Circolare 2019)",
        description="Linear and nonlinear kinematic analysis (NTC 2018 par. 8.7.1, Circolare 2019 "
                    "C8.7.1.2) of the mechanisms limit analysis finds: alpha_0, M*, e*, a_0*, the "
                    "capacity curve, d_u*, T_s and the checks against an elastic site spectrum. "
                    "Formulas and clauses: docs/codecheck.md.")
    add_geometry_options(p)
    add_codecheck_options(p)
    g = p.add_argument_group(
        "mechanism above ground", "the structure the arch stands in (an arch on piers in a "
                                  "church): with a spectrum, adds the checks of a mechanism "
                                  "above ground (docs/piers.md)")
    g.add_argument("--structure-height", type=finite_float, metavar="H",
                   help="height [m] of the structure above its foundation, >= the mechanism's "
                        "centroid")
    g.add_argument("--storeys", type=_int, metavar="N",
                   help="storeys of the structure, 1 to 100 (default 1; gamma = 3N/(2N+1))")
    g.add_argument("--structure-period", type=finite_float, metavar="T1",
                   help="the structure's first period [s] (default 0.05 H^(3/4))")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run_codecheck)
    return p


def _above_ground_from_args(args):
    """The AboveGround of --structure-height/--storeys/--structure-period, or None."""
    from ..errors import ArchInputError
    from ..studies.codecheck import AboveGround

    h = getattr(args, "structure_height", None)
    n = getattr(args, "storeys", None)
    t1 = getattr(args, "structure_period", None)
    if h is None:
        if n is not None or t1 is not None:
            raise CLIError("--structure-height: needed with --storeys/--structure-period")
        return None
    try:
        return AboveGround(h, 1 if n is None else n, t1)
    except ArchInputError as exc:
        msg = str(exc)
        for field, flag in (("height:", "--structure-height:"), ("storeys:", "--storeys:"),
                            ("period:", "--structure-period:")):
            if msg.startswith(field):
                raise ArchInputError(flag + msg[len(field):]) from None
        raise


def run_codecheck(args) -> int:
    from ..studies.codecheck import code_check
    from ..reports.codecheck import format_codecheck

    cfg = codecheck_config_from_args(args)
    above = _above_ground_from_args(args)
    arch = arch_from_args(args)
    from ..errors import ArchInputError

    try:
        res = code_check(arch, config=cfg, above_ground=above)
    except ArchInputError as exc:
        if above is not None and str(exc).startswith("height:"):  # the structure's height
            raise ArchInputError("--structure-height:" + str(exc)[len("height:"):]) from None
        raise
    if args.json:
        emit_json(res.to_dict())
    else:
        print(format_codecheck(res))
    return 0
