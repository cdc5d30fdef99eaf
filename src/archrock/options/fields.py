"""One table from the command line's flags to the specs' fields.

Each spec that a command builds from its flags has one row per field: the flag that sets it, or
None with the reason in :data:`DERIVED`.  The builders of :mod:`archrock.options` read the option
values through it (:func:`values`), and word a library message about a field with the flag
(:func:`flag_message`); ``tests/cli/test_flag_table.py`` holds it against the specs' fields and the
parser's options.  A flag's value is found under its argparse ``dest`` (:func:`dest`).
"""

from __future__ import annotations

__all__ = ["FLAGS", "DERIVED", "dest", "values", "flag_message"]

#: spec -> {field: flag (None: set by no flag, see DERIVED)}; "with_piers" is the keyword
#: arguments of archrock.geometry.with_piers (the arch on piers has no spec of its own)
FLAGS: dict[str, dict[str, str | None]] = {
    "Spreads": {"span": "--spread-span", "thickness": "--spread-thickness",
                "radius": "--spread-radius", "tilt": "--spread-tilt",
                "pier_lean": "--spread-pier-lean", "pier_width": "--spread-pier-width",
                "pier_height": "--spread-pier-height", "pier_course": "--spread-pier-course",
                "fc": "--spread-fc"},
    "PulseSpec": {"kind": "--pulse", "amplitude_g": "--amplitude", "duration": "--pulse-duration"},
    "RecordSpec": {"path": "--record", "units": "--units", "scale": "--scale", "sha256": None},
    "ImpactSpec": {"model": "--impact", "cv": "--cv", "literal": "--literal-cv",
                   "on": "--impact-on", "fallback": None, "note": None},
    "SupportMovement": {"spread": "--spread", "settlement": "--settlement",
                        "side": "--support-side", "rotation": "--rotation",
                        "pivot_depth": "--pivot-depth"},
    "with_piers": {"height": "--pier-height", "width": "--pier-width",
                   "courses": "--pier-courses", "batter": "--pier-batter",
                   "height_right": "--right-pier-height", "width_right": "--right-pier-width",
                   "courses_right": "--right-pier-courses",
                   "batter_right": "--right-pier-batter", "steps": "--pier-steps",
                   "steps_right": "--right-pier-steps", "name": None},
}

#: (spec, field) set by no flag -> why
DERIVED = {
    ("RecordSpec", "sha256"): "the digest of the file, computed when --record is read",
    ("ImpactSpec", "fallback"): "implied by the model and where it is evaluated (--impact-on)",
    ("ImpactSpec", "note"): "written when a model is resolved on the nominal arch",
    ("with_piers", "name"): "the arch's own name",
}


def dest(flag: str) -> str:
    """argparse's attribute of ``flag``: '--spread-span' -> 'spread_span'."""
    return flag[2:].replace("-", "_")


def values(args, spec: str, defaults: dict | None = None) -> dict:
    """{field: the value of its flag in ``args``} for the fields of ``spec`` that a flag sets;
    a flag that the command does not have, or that was not given (None), takes
    ``defaults[field]`` when there is one and is left out otherwise."""
    defaults = defaults or {}
    out = {}
    for field, flag in FLAGS[spec].items():
        if flag is None:
            continue
        v = getattr(args, dest(flag), None)
        if v is None and field in defaults:
            v = defaults[field]
        if v is not None:
            out[field] = v
    return out


def flag_message(message: str, spec: str) -> str | None:
    """A library message that starts with a field of ``spec`` ('height: ...'), worded with its
    flag instead ('--pier-height: ...'); None when it names no such field."""
    for field, flag in sorted(FLAGS[spec].items(), key=lambda kv: -len(kv[0])):
        if flag is not None and message.startswith(field + ":"):
            return flag + message[len(field):]
    return None
