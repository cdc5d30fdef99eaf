"""Blocks by kind: an arch's voussoirs, pier courses and buttress blocks counted and named apart
(an arch of 9 voussoirs on two piers is not "an arch of 11 voussoirs"), for every text, figure
title and JSON that gives a count (docs/piers.md)."""

from __future__ import annotations

from .piers import _pier_runs

__all__ = ["block_counts", "describe_blocks", "arch_phrase", "article", "block_kind",
           "block_name", "block_names", "arcade_counts", "describe_arcade"]


def _plural_word(word: str) -> str:
    return word + ("es" if word.endswith("s") else "s")  # buttress -> buttresses


def _plural(count: int, word: str) -> str:
    """'1 block', '3 courses', '2 buttresses'."""
    return f"{count} {word if count == 1 else _plural_word(word)}"


def _courses_text(runs) -> str:
    """'1 block each', '3 courses each', '3 and 2 courses' for two pier runs ``runs``."""
    a, b = (len(r) for r in runs)
    unit = "block" if max(a, b) == 1 else "course"
    return f"{_plural(a, unit)} each" if a == b else f"{a} and {_plural(b, unit)}"


def block_counts(arch) -> dict:
    """The blocks of ``arch`` counted by kind (docs/piers.md): ``voussoirs``, ``pier_blocks``
    (courses of rectangular piers), ``buttress_blocks`` (of battered or stepped piers), ``piers``
    (how many piers or buttresses it stands on: 0, 1 or 2) and ``blocks`` (all of them).  An
    arch without piers has only voussoirs."""
    kinds = tuple(getattr(arch, "block_kinds", ()) or ("voussoir",) * arch.n)
    left, right = _pier_runs(kinds)
    return {"voussoirs": kinds.count("voussoir"), "pier_blocks": kinds.count("pier"),
            "buttress_blocks": kinds.count("buttress"),
            "piers": int(bool(left)) + int(bool(right)), "blocks": len(kinds)}


def describe_blocks(arch) -> str:
    """The blocks of ``arch`` in words, each kind apart: "7 voussoirs", "9 voussoirs on two
    piers (1 block each)", "9 voussoirs on two buttresses (3 courses each)", "9 voussoirs on a
    pier (left, 2 courses) and a buttress (right, 1 block)"."""
    kinds = tuple(getattr(arch, "block_kinds", ()) or ("voussoir",) * arch.n)
    nv = _plural(kinds.count("voussoir"), "voussoir")
    runs = [r for r in _pier_runs(kinds) if r]
    if not runs:
        return nv
    names = [kinds[r[0]] for r in runs]
    if len(runs) == 2 and names[0] == names[1]:
        return f"{nv} on two {_plural_word(names[0])} ({_courses_text(runs)})"
    sides = ("left", "right") if len(runs) == 2 else \
        (("left",) if kinds[0] != "voussoir" else ("right",))
    parts = [f"a {k} ({s}, {_plural(len(r), 'block' if len(r) == 1 else 'course')})"
             for k, r, s in zip(names, runs, sides)]
    return f"{nv} on " + " and ".join(parts)


def article(word: str) -> str:
    """'a' or 'an' before ``word`` (by its first letter: 'an arch', 'a circular arch')."""
    return "an" if word[:1].lower() in "aeiou" else "a"


def arch_phrase(arch, adjective: str = "") -> str:
    """"an arch of 9 voussoirs on two piers (1 block each)", "a circular arch of 7 voussoirs"
    (``adjective`` before "arch"), articles right."""
    noun = f"{adjective} arch" if adjective else "arch"
    return f"{article(noun)} {noun} of {describe_blocks(arch)}"


def block_kind(arch, i: int) -> str:
    """"voussoir", "pier" or "buttress": the kind of block ``i`` (chain order) of ``arch``."""
    kinds = getattr(arch, "block_kinds", ()) or ()
    return kinds[int(i)] if kinds else "voussoir"


def block_name(arch, i: int) -> str:
    """Block ``i`` (chain order) in the words of the drawing: "voussoir 3" (the arch's own
    numbering, 0 at its left springing), "left pier" (a monolithic pier), "right buttress
    course 2" (courses counted from the foot up); "voussoir i" on an arch without piers."""
    i = int(i)
    kinds = tuple(getattr(arch, "block_kinds", ()) or ())
    if not kinds:
        return f"voussoir {i}"
    left, right = _pier_runs(kinds)
    if i in left or i in right:
        side, run = ("left", left) if i in left else ("right", right)
        course = i + 1 if side == "left" else len(kinds) - i  # from the foot up, both sides
        return f"{side} {kinds[i]}" + (f" course {course}" if len(run) > 1 else "")
    return f"voussoir {i - len(left)}"


def block_names(arch) -> tuple:
    """:func:`block_name` of every block of ``arch``, in chain order."""
    return tuple(block_name(arch, i) for i in range(arch.n))


def arcade_counts(arc) -> dict:
    """The blocks of an :class:`~archrock.geometry.arcade.Arcade` by kind: ``voussoirs``,
    ``pier_blocks``, ``buttress_blocks``, ``beams``, ``blocks`` and ``piers`` (how many piers
    its ``piers`` lists; None where it lists none, e.g. an arcade read from a file without
    them)."""
    kinds = tuple(arc.kinds)
    piers = tuple(getattr(arc, "piers", ()) or ())
    return {"voussoirs": kinds.count("voussoir"), "pier_blocks": kinds.count("pier"),
            "buttress_blocks": kinds.count("buttress"), "beams": kinds.count("beam"),
            "piers": len(piers) or None, "blocks": len(kinds)}


def describe_arcade(arc) -> str:
    """An arcade's blocks in words, each kind apart: "18 voussoirs, 3 piers in 6 courses",
    "18 voussoirs, 4 pier blocks" (piers not numbered by their labels)."""
    c = arcade_counts(arc)
    parts = [_plural(c["voussoirs"], "voussoir")] if c["voussoirs"] else []
    walls = c["pier_blocks"] + c["buttress_blocks"]
    if walls:
        what = ("pier" if not c["buttress_blocks"] else "buttress" if not c["pier_blocks"]
                else "pier or buttress")
        if c["piers"]:
            word = "buttress" if what == "buttress" else "pier"
            per = "" if walls == c["piers"] else f" in {_plural(walls, 'course')}"
            parts.append(_plural(c["piers"], word) + per)
        else:
            parts.append(_plural(walls, f"{what} block"))
    if c["beams"]:
        parts.append(_plural(c["beams"], "beam"))
    return ", ".join(parts)
