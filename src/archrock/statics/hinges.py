"""Hinges and four-hinge mechanisms of a voussoir arch, and the one enumeration of candidates.

Joints are numbered 0..n from the left springing (joint 0 the left springing, n the right).  A
hinge sits at the intrados or the extrados end of a joint's contact segment (``EDGES``, edge
index 0 and 1).  Direction 'l' means horizontal loads toward +x (mechanism M_l), 'r' toward -x
(M_r).  A :class:`Mechanism` carries its multiplier: the horizontal load, per unit weight, that
activates it (kinematic theorem).

Four-hinge candidates: every quadruple of joints a < b < c < d in lexicographic order, with the
16 edge patterns of each (pattern bits: joint a's edge is bit 3, ..., joint d's bit 0); a
candidate's index is rank(quadruple) * 16 + pattern.  :func:`four_hinge_sets` lists the
quadruples (the one enumeration of them: statics, the least-loss law and the pier diagnostics
start from it; a search that keeps only some joints takes the same order from
:func:`quadruples`), :func:`four_hinge_candidates` the mechanisms, :func:`_candidates` the
index arrays,
:func:`candidate_hinges` and :func:`_candidate_index` convert between an index and its hinges
without the list; every search in :mod:`archrock.statics` uses this order (ties resolve to the
first candidate in it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from itertools import chain, combinations

import numpy as np

__all__ = ["Hinge", "Mechanism", "HINGE_LABELS", "EDGES", "DIRECTIONS", "candidate_hinges",
           "four_hinge_sets", "four_hinge_candidates", "quadruples"]


EDGES = ("intrados", "extrados")
DIRECTIONS = ("l", "r")
# Sign s_e such that a hinge at edge e opens when s_e * (omega_right - omega_left) > 0.
_EDGE_SIGN = np.array([-1.0, 1.0])
_ADMISSIBLE_TOL = 1e-9
#: The 16 edge patterns of a quadruple (0 intrados, 1 extrados; joint a's edge is bit 3).
_PATTERNS = np.array([[(p >> k) & 1 for k in (3, 2, 1, 0)] for p in range(16)], dtype=np.int64)


@dataclass(frozen=True)
class Hinge:
    """A hinge at the intrados or extrados end of joint ``joint`` (0 = left springing)."""

    joint: int
    edge: str

    def to_dict(self) -> dict:
        return {"joint": int(self.joint), "edge": self.edge}


#: Hinge labels from the leading side of a mechanism (docs/method.md, Four-link equation).
HINGE_LABELS = ("A", "B", "C", "D")


@dataclass(frozen=True)
class Mechanism:
    """A collapse mechanism; hinges ordered from the left springing.

    direction: 'l' (loads toward +x, M_l) or 'r' (loads toward -x, M_r).
    multiplier: the horizontal load multiplier lambda that activates it (kinematic theorem).
    hinges: the joints that rotate about one end of their contact segment.
    lift_off: the joints that open at both ends (the parts separate across them, with no
    sliding); empty for the four-hinge rocking chain of Oppenheim's model.  A mechanism with
    lift-off has fewer than four hinges (kind 'lift-off'); the four-link model does not
    describe it (docs/method.md, The Heyman optimum).
    """

    direction: str
    hinges: tuple[Hinge, ...]
    multiplier: float
    lift_off: tuple[int, ...] = ()
    #: joints crushed through at collapse (finite f_c: the stress block fills the joint, which
    #: shortens as it turns); empty under Heyman's hypotheses
    crushed: tuple[int, ...] = ()

    @property
    def kind(self) -> str:
        """'four-hinge' (a rocking chain of three links), 'lift-off', 'crushing' (a joint
        crushed through), or 'three-hinge' (three hinges on one line: a degenerate chain the
        dual can give, no four-link model either)."""
        if self.crushed:
            return "crushing"
        if self.lift_off:
            return "lift-off"
        return "four-hinge" if len(self.hinges) == 4 else f"{len(self.hinges)}-hinge".replace(
            "3-", "three-")

    @property
    def is_four_hinge(self) -> bool:
        return not self.lift_off and not self.crushed and len(self.hinges) == 4

    @property
    def joints(self) -> tuple[int, ...]:
        return tuple(h.joint for h in self.hinges)

    @property
    def label(self) -> str:
        """Compact hinge label, joints from the left springing with their edge (i = intrados,
        e = extrados, s = separates: lift-off), e.g. '0i-3e-5i-7e' or '0s-4i-7e'."""
        parts = [(h.joint, f"{h.joint}{h.edge[0]}") for h in self.hinges]
        parts += [(j, f"{j}s") for j in self.lift_off]
        parts += [(j, f"{j}c") for j in self.crushed]
        return "-".join(p for _, p in sorted(parts))

    def describe(self) -> str:
        """One line for people: the kind, the hinges and the joints that lift off."""
        if self.crushed:
            joints = ", ".join(str(j) for j in self.crushed)
            return (f"mechanism with joint{'s' if len(self.crushed) > 1 else ''} {joints} "
                    f"crushed through ({self.label})")
        if not self.lift_off:
            return f"{self.kind} mechanism {self.label}"
        lifts = ", ".join(str(j) for j in self.lift_off)
        return (f"mechanism with lift-off at joint{'s' if len(self.lift_off) > 1 else ''} "
                f"{lifts} ({self.label})")

    def labelled(self) -> list[tuple[str, Hinge]]:
        """(label, hinge) pairs: A..D from the mechanism's leading side (docs/method.md, Four-link equation): for
        M_l, A is the leftmost hinge; for M_r, A is the rightmost."""
        hinges = list(self.hinges)
        if self.direction == "r":
            hinges = hinges[::-1]
        return list(zip(HINGE_LABELS, hinges))

    def mirrored(self, n: int) -> "Mechanism":
        """The same mechanism on the mirror image of an n-voussoir arch."""
        hinges = tuple(Hinge(n - h.joint, h.edge) for h in reversed(self.hinges))
        return Mechanism("r" if self.direction == "l" else "l", hinges, self.multiplier,
                         tuple(sorted(n - j for j in self.lift_off)),
                         tuple(sorted(n - j for j in self.crushed)))

    def to_dict(self) -> dict:
        out = {"direction": self.direction, "multiplier": self.multiplier,
               "hinges": [h.to_dict() for h in self.hinges], "kind": self.kind,
               "lift_off": [int(j) for j in self.lift_off], "label": self.label}
        if self.crushed:  # only with finite f_c: Heyman's dicts stay as they were
            out["crushed"] = [int(j) for j in self.crushed]
        return out


def quadruples(items) -> np.ndarray:
    """Every four of ``items`` (increasing integers: joints, or joint-end rows) as rows
    a < b < c < d of a (K, 4) int64 array, in lexicographic order; on joints, the order of
    :func:`four_hinge_sets` restricted to them."""
    items = [int(i) for i in items]
    k = math.comb(len(items), 4)
    flat = np.fromiter(chain.from_iterable(combinations(items, 4)), dtype=np.int64, count=4 * k)
    return flat.reshape(k, 4)


@lru_cache(maxsize=64)
def four_hinge_sets(n: int) -> np.ndarray:
    """The joint quadruples a < b < c < d of an n-voussoir arch (joints 0..n), in lexicographic
    order: (C(n+1, 4), 4) int64, read-only.  The one enumeration of four-hinge sets; a
    candidate's rank is its row here."""
    quads = quadruples(range(n + 1))
    quads.setflags(write=False)
    return quads


def four_hinge_candidates(n: int, direction: str):
    """Every four-hinge mechanism of an n-voussoir arch that can open toward ``direction``, in
    the candidate order (quadruples of :func:`four_hinge_sets`, then edge patterns), without the
    two patterns that never open (four intrados or four extrados hinges: the relative rotations
    add up to zero).  Yields :class:`Mechanism` with a NaN multiplier (not yet computed)."""
    for joints in four_hinge_sets(n).tolist():
        for pattern in _PATTERNS[1:15].tolist():
            yield Mechanism(direction, tuple(Hinge(j, EDGES[e]) for j, e in zip(joints, pattern)),
                            float("nan"))


@lru_cache(maxsize=64)
def _candidates(n: int):
    """All (joint quadruple, edge pattern) candidates for n voussoirs, as index arrays."""
    quads = four_hinge_sets(n)
    jq = np.repeat(quads, 16, axis=0)
    eq = np.tile(_PATTERNS, (len(quads), 1))
    return jq, eq


@lru_cache(maxsize=64)
def _active_candidates(n: int):
    """Indices (into :func:`_candidates`) of the candidates that can ever be admissible, with
    precomputed gather indices.

    The four relative hinge rotations q = (w1, w2 - w1, w3 - w2, -w3) add up to zero, so they
    cannot all open a hinge at the same edge: the patterns with four intrados or four extrados
    hinges are never admissible and are dropped (2 of the 16 patterns).  The remaining order is
    the original one, so ties resolve to the same candidate as a full scan.
    Returns (idx, point index per hinge (4, K'), segment-pair index per link (3, K')) with point
    index = 2*joint + edge into the flattened (n+1, 2) point arrays and pair index = i*(n+1) + j
    into the flattened (n+1, n+1) table of prefix-sum differences.
    """
    jq, eq = _candidates(n)
    keep = ~(np.all(eq == 0, axis=1) | np.all(eq == 1, axis=1))
    idx = np.flatnonzero(keep)
    j, e = jq[idx], eq[idx]
    pt = (2 * j + e).T.copy()
    m = n + 1
    pair = np.stack([j[:, 0] * m + j[:, 1], j[:, 1] * m + j[:, 2], j[:, 2] * m + j[:, 3]])
    sign = _EDGE_SIGN[e].T.copy()
    for arr in (idx, pt, pair, sign):
        arr.setflags(write=False)
    return idx, pt, pair, sign


def _candidate_index(n: int, joints, edges) -> np.ndarray:
    """Indices in the order of :func:`_candidates` of candidates given by their joints (K, 4),
    increasing, and edges (K, 4): the inverse of :func:`candidate_hinges`, vectorised."""
    j = np.asarray(joints, dtype=np.int64)
    e = np.asarray(edges, dtype=np.int64)
    m = n + 1
    x = m - 1 - j  # combinations after a quadruple, counted by its complement (combinadic)
    after = (x[:, 0] * (x[:, 0] - 1) * (x[:, 0] - 2) * (x[:, 0] - 3) // 24
             + x[:, 1] * (x[:, 1] - 1) * (x[:, 1] - 2) // 6
             + x[:, 2] * (x[:, 2] - 1) // 2 + x[:, 3])
    rank = math.comb(m, 4) - 1 - after
    return rank * 16 + (e[:, 0] << 3 | e[:, 1] << 2 | e[:, 2] << 1 | e[:, 3])


def candidate_hinges(n: int, idx: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(joints, edges) of candidate ``idx`` in the order of :func:`_candidates` (quadruples
    a < b < c < d in lexicographic order, 16 edge patterns each), without building the list."""
    rank, pattern = divmod(int(idx), 16)
    m = n + 1
    joints = []
    x = 0
    for slot in range(4):
        left = 3 - slot
        while True:
            count = math.comb(m - x - 1, left)  # combinations whose slot-th joint is x
            if rank < count:
                joints.append(x)
                x += 1
                break
            rank -= count
            x += 1
    edges = tuple((pattern >> k) & 1 for k in (3, 2, 1, 0))
    return tuple(joints), edges


def _mechanism_from_candidate(n: int, idx: int, direction: str, k: float) -> Mechanism:
    joints, edges = candidate_hinges(n, idx)
    hinges = tuple(Hinge(j, EDGES[e]) for j, e in zip(joints, edges))
    return Mechanism(direction, hinges, float(k))
