"""argparse plumbing: the parser class, the subcommand registry, option types, JSON output and
the error handling of :func:`archrock.cli.main`."""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import warnings
from typing import Callable

from ..errors import OUTCOMES, ArchInputError, ArchrockError
from ..options import OptionError, json_safe  # noqa: F401 (json_safe: re-exported)

PROG = "archrock"
EXIT_USAGE = 2  # bad input: same status as argparse's own errors
EXIT_OUTCOME = 3  # valid input, no answer of the kind asked (archrock.errors.ArchrockError)
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as a shell reports a command stopped by Ctrl-C
_OPTIONAL_MODULES = {"matplotlib", "PIL", "pandas", "pyarrow", "tqdm", "numba", "dask", "distributed",
                     "ezdxf", "SALib"}

#: name -> add_<name>_parser(subparsers), in the order shown by --help (filled by archrock.cli).
SUBCOMMANDS: dict[str, Callable] = {}


#: A command-line problem that is not an arch-input problem (e.g. conflicting options): the
#: option vocabulary's own error, under the command line's name (the same class).
CLIError = OptionError


# A value that starts with '-' and then reads as a number or a list/range of numbers
# ("-5e-1", "-1,2", "-1:0:5"). argparse's own pattern knows only "-5" and "-0.5", so it took
# "--amplitude -5e-1" for an option and said "expected one argument". No archrock option
# starts with '-' followed by a digit or '.', so this cannot hide an option.
_NEGATIVE_VALUE = re.compile(r"^-\.?\d[\d.eE+\-,:]*$")


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors read ``archrock: error: <message>`` (exit status 2), one
    line without the usage block (README), and which takes negative numbers in any spelling
    (``-5e-1``, ``-1,2``) as values."""

    def __init__(self, *args, **kwargs):
        d = kwargs.get("description")
        if d is not None and "%(prog)" not in d:  # formatted only when it names %(prog)
            kwargs["description"] = d.replace("%%", "%")
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_VALUE

    def error(self, message):  # noqa: D401 - argparse API
        msg = " ".join(str(message).split())
        self.exit(EXIT_USAGE, f"{PROG}: error: {msg}\n")

    def add_argument_group(self, title=None, description=None, **kwargs):
        # argparse %-formats an argument's help but not a group's title or description, so a
        # '%%' written there (as the arguments beside it need) showed literally ("5%% damping")
        title, description = (None if t is None else str(t).replace("%%", "%")
                              for t in (title, description))
        return super().add_argument_group(title, description, **kwargs)


def subcommand(name: str):
    """Decorator registering ``add_<name>_parser(subparsers)`` under ``name`` (after the built-in
    subcommands in --help)."""
    def register(add_parser: Callable) -> Callable:
        SUBCOMMANDS[name] = add_parser
        return add_parser
    return register


# ---------------------------------------------------------------------------- argparse types
def interrupted_study(out) -> int:
    """Ctrl-C in a study that keeps its finished responses in ``out`` (None: nothing kept):
    say what was kept on stderr; the exit status."""
    kept = ("nothing was kept (give --out DIR to keep finished responses and resume)"
            if out is None else f"the finished responses are kept in {out}; the same "
                                f"command resumes from them")
    print(f"{PROG}: interrupted; {kept}", file=sys.stderr)
    return EXIT_INTERRUPTED


def parsed(text: str, cast, expected: str):
    """``cast(text)``, or argparse's error 'expected <expected>, got <text>'."""
    try:
        return cast(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {expected}, got {text!r}") from None


def out_of_range(text: str, allowed: str) -> argparse.ArgumentTypeError:
    """argparse's error for a value outside its range, naming what is ``allowed``."""
    return argparse.ArgumentTypeError(f"{text!r} is out of range; allowed {allowed}")


def finite_float(text: str) -> float:
    """argparse type: a finite number (NaN and infinities refused)."""
    v = parsed(text, float, "a number")
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return v


def positive_float(text: str) -> float:
    """argparse type: a finite number > 0."""
    v = finite_float(text)
    if v <= 0:
        raise out_of_range(text, "> 0")
    return v


def non_negative_int(text: str) -> int:
    """argparse type: an integer >= 0 (e.g. a random seed)."""
    v = parsed(text, int, "an integer")
    if v < 0:
        raise out_of_range(text, "an integer >= 0")
    return v


def _int(text: str) -> int:
    """argparse type: an integer, also written as a whole number in float notation ('1e6',
    '2048.0'), so that the option's own range check names what is allowed."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if math.isfinite(v) and v == int(v) and abs(v) < 2.0 ** 53:
        return int(v)
    raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None


def emit_json(obj, out=None) -> None:
    """Print ``obj`` as one JSON document on stdout; NaN/inf are written as null
    (:func:`json_safe`), never as the non-standard ``NaN`` token."""
    out = sys.stdout if out is None else out
    out.write(json.dumps(json_safe(obj), indent=2, allow_nan=False) + "\n")


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    """Library warnings on the command line: ``archrock: warning: <message>``, one line."""
    print(f"{PROG}: warning: {' '.join(str(message).split())}",
          file=sys.stderr if file is None else file)


# ---------------------------------------------------------------------------- top level
def _version() -> str:
    try:
        from importlib.metadata import version

        return version("archrock")
    except Exception:  # not installed (running from a source tree)
        return "unknown"


def new_parser() -> argparse.ArgumentParser:
    """The top-level parser with every subcommand of :data:`SUBCOMMANDS`."""
    parser = _Parser(prog=PROG, description="Seismic rocking assessment of masonry arches: "
                                            "limit analysis, rocking dynamics, ensembles.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", metavar="<command>", parser_class=_Parser)
    sub.required = True
    for add_parser in SUBCOMMANDS.values():
        add_parser(sub)
    return parser


def _progress_line(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def run_command(parser: argparse.ArgumentParser, argv=None) -> int:
    """Parse ``argv`` and run the chosen subcommand; returns the exit status (0 ok, 2 bad input,
    3 a valid input with no answer of the kind asked (archrock.errors.GeometryOutcome: the arch
    cannot stand, no mechanism opens), an impact model that cannot be applied, a fit that cannot
    be identified or a computation limit, 1 missing optional dependency)."""
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse: --help/--version (0) or a usage error (2)
        return int(exc.code) if isinstance(exc.code, int) else (0 if exc.code is None else EXIT_USAGE)
    from ..statics.kinematic import limit_progress

    # long limit analyses (a full enumeration above about 5 s) say how far they are, on stderr,
    # unless the command was asked for no progress
    progress = None if getattr(args, "no_progress", False) else _progress_line
    try:
        with warnings.catch_warnings(), limit_progress(progress):
            warnings.simplefilter("default")  # each distinct warning once, not hidden
            warnings.showwarning = _one_line_warning
            return int(args.func(args) or 0)
    except KeyboardInterrupt:
        # a command with something to say about what was kept catches it itself (ensemble)
        print(f"{PROG}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (ArchInputError, CLIError) as exc:
        # one line, no traceback: the message names the field and the allowed range
        msg = " ".join(str(exc).split())
        print(f"{PROG}: error: {msg}", file=sys.stderr)
        return EXIT_USAGE
    except ArchrockError as exc:
        # a physical outcome or a limit of the method, not a mistake in the input: said as such
        # (on piers too narrow the library's message names them and the width that carries
        # the arch: archrock.statics.buttress.piers_cannot_stand)
        msg = " ".join(str(exc).split())
        kind = "outcome" if isinstance(exc, OUTCOMES) else "error"
        print(f"{PROG}: {kind}: {msg}", file=sys.stderr)
        return EXIT_OUTCOME
    except ImportError as exc:
        # only a missing optional extra is a user-facing condition; anything else is a bug
        root = (getattr(exc, "name", None) or "").split(".")[0]
        if root not in _OPTIONAL_MODULES and "pip install" not in str(exc):
            raise
        print(f"{PROG}: error: {exc} (install the extras: pip install 'archrock[all]')",
              file=sys.stderr)
        return 1
    except BrokenPipeError:  # e.g. `archrock limit --json | head`
        return 0
