"""Why the static program of an arcade has no answer, in words that name a block or a contact
(docs/arcades.md, When the program has no answer).

Called after HiGHS reports the program infeasible (no contact forces hold the blocks) or
unbounded (no mechanism), so a working arcade pays nothing.  The causes looked for, in order:

* a block given twice, or two blocks that overlap (:mod:`archrock.geometry.overlap`);
* a load far from the block that carries it (farther than the block's own size): a typing slip
  in a coordinate, which moves the block's mass centre off its contacts;
* every contact on the ground (a = -1): no block rests on another;
* a block that its own contacts cannot hold at any horizontal load (each contact's far side
  taken as fixed): its weight's line falls outside them; or two blocks that each hold only
  under horizontal loads the other cannot take (their ranges of the load factor do not
  meet).  Found by two three-row programs per block (the least and greatest load factor), in
  reading order, at most :data:`MAX_BLOCKS` blocks.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linprog

from ..geometry.arcade import GROUND

__all__ = ["diagnose", "input_mistake", "MAX_BLOCKS"]

#: Blocks checked one by one at most (each a three-row program; about a millisecond each).
MAX_BLOCKS = 5000


def _name(arc, k: int) -> str:
    lab = arc.blocks[k].label
    return f"block {k} ({lab})" if lab else f"block {k}"


def input_mistake(arc) -> str | None:
    """A mistake in the arcade itself that explains a program with no answer: overlapping or
    duplicated blocks, or a load far from its block (one line naming them), else None."""
    from ..geometry.overlap import find_overlap, overlap_message
    from ..geometry.polygon import FACE_TOLERANCE

    for k, b in enumerate(arc.blocks):
        out = np.asarray(b.outline, float)
        size = float(np.max(np.ptp(out, axis=0)))
        lo, hi = out.min(axis=0), out.max(axis=0)
        for i, (m, at) in enumerate(b.loads):
            off = float(np.hypot(*np.maximum(0.0, np.maximum(lo - at, at - hi))))
            if off > size:
                return (f"blocks[{k}].loads[{i}]: {m:g} kg/m at ({at[0]:g}, {at[1]:g}) m, "
                        f"{off:.4g} m outside {_name(arc, k)}, which is {size:.4g} m across; "
                        f"allowed a load on or near its block")
    hit = find_overlap([b.outline for b in arc.blocks],
                       FACE_TOLERANCE * min(1.0, 0.1 * arc.extent))
    return None if hit is None else overlap_message(arc, hit)


def _k_range(prog, k: int, contacts: list[int]):
    """(least, greatest) horizontal load factor at which some forces at ``contacts`` (their far
    sides fixed) hold block ``k`` (the block's three rows of the full program, alone; -inf/inf
    where unbounded), or None where none does."""
    cols = [3 * c + e for c in contacts for e in (0, 1, 2)] + [prog.A_eq.shape[1] - 1]
    A = prog.A_eq[3 * k:3 * k + 3][:, cols]
    b = prog.b_eq[3 * k:3 * k + 3]
    bounds = [prog.bounds[j] for j in cols]
    A_ub = b_ub = None
    rows, rhs = [], []
    for i, c in enumerate(contacts):
        if not np.isfinite(prog.mu[c]):  # no sliding there
            continue
        for s in (1.0, -1.0):
            row = np.zeros(len(cols))
            row[3 * i + 2] = s
            row[3 * i] = row[3 * i + 1] = -prog.mu[c]
            rows.append(row)
            rhs.append(prog.coh[c])
    if rows:
        A_ub, b_ub = np.array(rows), np.array(rhs)
    out = []
    for sign in (1.0, -1.0):  # least, then greatest k
        c = np.zeros(len(cols))
        c[-1] = sign
        res = linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A, b_eq=b, bounds=bounds, method="highs")
        if res.status == 2:
            return None
        out.append(-sign * np.inf if res.status == 3 else float(res.x[-1]))
    return out[0], out[1]


def _unheld_block(prog) -> str | None:
    """The first block its own contacts cannot hold at any horizontal load, or the two blocks
    whose ranges of load do not meet (module docstring), in words."""
    arc = prog.arc
    touching = [[] for _ in range(arc.n_blocks)]
    for c, ct in enumerate(arc.contacts):
        for side in (ct.a, ct.b):
            if side != GROUND:
                touching[side].append(c)
    lo, hi = (-np.inf, None), (np.inf, None)
    for k in range(min(arc.n_blocks, MAX_BLOCKS)):
        rng = _k_range(prog, k, touching[k])
        if rng is None:
            labels = [arc.contacts[c].label or f"contact {c}" for c in touching[k]]
            return (f"{_name(arc, k)} cannot be held by its contacts "
                    f"({'; '.join(labels)}) at any horizontal load: its weight's line falls "
                    f"outside them, or they cannot carry it")
        if rng[0] > lo[0]:
            lo = (rng[0], k)
        if rng[1] < hi[0]:
            hi = (rng[1], k)
    if lo[1] is not None and hi[1] is not None and lo[0] > hi[0] + 1e-9:
        def on(k):
            return "; ".join(arc.contacts[c].label or f"contact {c}" for c in touching[k])
        return (f"{_name(arc, lo[1])}, on {on(lo[1])}, is held only under a horizontal load of "
                f"at least {lo[0]:.4g} g and {_name(arc, hi[1])}, on {on(hi[1])}, only under at "
                f"most {hi[0]:.4g} g: no one load holds both (a contact missing or misplaced)")
    return None


def diagnose(prog, status: int) -> str | None:
    """What explains the program's ``status`` (2: infeasible, 3: unbounded) on ``prog``'s
    arcade, in words naming a block or contact (module docstring), or None."""
    arc = prog.arc
    on_ground = all(ct.a == GROUND or ct.b == GROUND for ct in arc.contacts)
    ground = ("every contact is on the ground (a = -1), so no block rests on another"
              if on_ground else None)
    if status == 3:
        return (f"{ground}: each block is held by the ground alone" if ground else None)
    block = _unheld_block(prog)
    parts = [p for p in (ground, block) if p]
    return "; ".join(parts) if parts else None
