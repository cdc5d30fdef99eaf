"""``archrock import-dxf``: a surveyed arch from a drawing (one closed polyline per voussoir)
written as a polygon geometry file."""

from __future__ import annotations

import sys
from pathlib import Path

from ._parser import CLIError, emit_json, positive_float
from .options import GEOMETRY_DEFAULTS, folder_arg

UNIT_CHOICES = ("m", "cm", "mm")  # archrock.geometry.dxf.UNITS, spelled out so that --help needs no numpy


def add_import_dxf_parser(subparsers):
    p = subparsers.add_parser(
        "import-dxf", help="read a surveyed arch from a DXF drawing; write its geometry file",
        description="Each closed polyline (LWPOLYLINE or POLYLINE) of the layer is one voussoir; "
                    "the voussoirs are ordered along the chain of shared faces from the left "
                    "springing, and each one's intrados, extrados and faces are found from the "
                    "contacts with its neighbours (docs/geometry.md). Needs ezdxf "
                    "(pip install 'archrock[dxf]').")
    p.add_argument("drawing", metavar="DRAWING.dxf", help="the DXF drawing")
    p.add_argument("--layer", metavar="L",
                   help="layer of the voussoirs (default: every layer); names compare "
                        "case-insensitively")
    p.add_argument("--units", choices=UNIT_CHOICES, default="m",
                   help="drawing units (default m)")
    p.add_argument("--density", type=positive_float, metavar="RHO",
                   default=GEOMETRY_DEFAULTS["density"],
                   help=f"density [kg/m^3] (default {GEOMETRY_DEFAULTS['density']:g})")
    p.add_argument("--out", metavar="FILE", help="geometry file to write (default: stdout)")
    p.set_defaults(func=run_import_dxf)
    return p


def run_import_dxf(args) -> int:
    from ..geometry.dxf import read_dxf

    out = folder_arg(args.out, "--out", "a file name (omit --out for stdout)")
    arch, handles = read_dxf(args.drawing, args.layer, args.units, density=args.density,
                             name=Path(args.out).stem if out else None)
    meta = {"generator": "archrock import-dxf", "drawing": str(args.drawing),
            "layer": args.layer, "units": args.units, "handles": list(handles)}
    if out:
        from ..geometry.files import write_arch

        try:
            Path(out).parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise CLIError(f"--out: cannot create the folder of {out!r} ({exc.strerror})") from None
        write_arch(arch, out, metadata=meta)
        print(f"{arch.n} voussoirs (DXF handles {', '.join(handles)} from the left springing); "
              f"wrote {out}", file=sys.stderr)
    else:
        emit_json({**arch.to_dict(), "metadata": meta})
    return 0
