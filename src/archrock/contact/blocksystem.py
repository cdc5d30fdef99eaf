"""The blocks and joints of a structure as the rigid-block engine sees them
(:mod:`archrock.contact.nscd`): one record of arrays, built from an arch, an arch on piers, a
displaced arch or an arcade.

Bodies: every block with its exact mass [kg/m], mass centre [m] and polar moment about it
[kg m] (loads included, as the arch gives them).  Body -1 is the ground (and the abutments),
which does not move in the ground's frame.

Contacts: the topology is known from the geometry, so no contact search is made.  Every joint
between body ``a`` and body ``b`` gives four *corner contacts*: each end of each side's face
against the other side's face -- block b's corner against a's face, and a's corner against b's
face, at both ends.  A joint can then close, open, hinge about either end and slide, and the gap
and normal of each corner contact are those of the current, finite configuration (the engine
moves each face with its block), not a small-rotation approximation.  The face normal stored
points from the face's block toward the corner's block.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._records import readonly_arrays
from ..errors import ArchInputError

__all__ = ["BlockSystem", "blocks_of_arch", "blocks_of_arcade", "block_on_ground"]

GROUND = -1


@dataclass(frozen=True, eq=False)
class BlockSystem:
    """Bodies and corner contacts of a structure (module docstring).

    masses (nb,) [kg/m]; centroids (nb, 2) [m]; inertias (nb,) [kg m] about the mass centre;
    joints: the number of joints (contacts of the geometry); for each corner contact k:
    ``owner[k]`` the body whose corner it is, ``face[k]`` the body whose face it touches (-1:
    the ground), ``corner[k]`` (2,) and ``face_start[k]`` (2,) [m] at rest, ``tangent[k]`` and
    ``normal[k]`` the face's unit vectors at rest (normal toward the owner), ``length[k]`` [m]
    the face's length, ``joint[k]`` and ``end[k]`` (0 or 1) the joint and end it belongs to;
    ``size`` [m] the structure's size (its time and length scales)."""

    masses: np.ndarray
    centroids: np.ndarray
    inertias: np.ndarray
    owner: np.ndarray
    face: np.ndarray
    corner: np.ndarray
    face_start: np.ndarray
    tangent: np.ndarray
    normal: np.ndarray
    length: np.ndarray
    joint: np.ndarray
    end: np.ndarray
    joints: int
    size: float
    name: str = field(default="", compare=False)

    def __post_init__(self):
        readonly_arrays(self)

    @property
    def n_bodies(self) -> int:
        return int(self.masses.size)

    @property
    def n_contacts(self) -> int:
        return int(self.owner.size)


def _corner_contacts(faces, sides, centroids):
    """The corner contacts of joints given as (a, b, face_a (2, 2), face_b (2, 2)) [m]: the face
    of a's side and of b's side (the same segment where the joint is closed)."""
    rows = []
    for j, ((a, b), (fa, fb)) in enumerate(zip(sides, faces)):
        for owner, other, fown, foth in ((b, a, fb, fa), (a, b, fa, fb)):
            t = foth[1] - foth[0]
            length = float(np.hypot(*t))
            if not length > 0.0:
                raise ArchInputError(f"joint {j}: a face of zero length; allowed faces with "
                                     f"two distinct ends")
            start, tu = foth[0], t / length
            nrm = np.array([-tu[1], tu[0]])
            mid = start + 0.5 * length * tu
            if other >= 0:
                away = np.dot(centroids[other] - mid, nrm) < 0  # normal leaves the face's block
            else:
                away = np.dot(centroids[owner] - mid, nrm) > 0  # the ground's face: toward owner
            if not away:
                nrm = -nrm
            for e in (0, 1):
                rows.append((owner, other, fown[e], start, tu, nrm, length, j, e))
    return rows


def _pack(masses, centroids, inertias, rows, joints, size, name) -> BlockSystem:
    arr = lambda i, dt=float: np.array([r[i] for r in rows], dt)  # noqa: E731
    m = np.asarray(masses, float)
    c = np.asarray(centroids, float).reshape(-1, 2)
    inert = np.asarray(inertias, float)
    if not (m.size and np.all(np.isfinite(m)) and np.all(m > 0) and np.all(inert > 0)
            and np.all(np.isfinite(c))):
        raise ArchInputError("blocks: every mass and moment of inertia must be finite and > 0")
    return BlockSystem(m, c, inert, arr(0, np.int64), arr(1, np.int64), arr(2), arr(3), arr(4),
                       arr(5), arr(6), arr(7, np.int64), arr(8, np.int64), int(joints),
                       float(size), name)


def blocks_of_arch(arch) -> BlockSystem:
    """The blocks and joints of a :class:`~archrock.geometry.VoussoirArch` (every family, file,
    arch on piers and displaced arch): blocks 0..n-1 in order, joint j between block j-1 and
    block j, joints 0 and n on the ground (the abutments' faces)."""
    n = arch.n
    pts = np.asarray(arch.joint_points, float)
    centroids = np.asarray(arch.centroids, float)
    move = getattr(arch, "move", None)
    base = getattr(arch, "base", None)
    abut = getattr(arch, "abutment_faces", None)
    sides, faces = [], []
    for j in range(n + 1):
        a, b = (j - 1 if j > 0 else GROUND), (j if j < n else GROUND)
        if move is None or base is None:
            fa = fb = pts[j]
        else:  # a displaced arch: each side's face moved with its own block
            orig = np.asarray(base.joint_points, float)[j]
            fa = move(a, orig) if a >= 0 else np.asarray(abut, float)[0]
            fb = move(b, orig) if b >= 0 else np.asarray(abut, float)[1]
        sides.append((a, b))
        faces.append((np.asarray(fa, float), np.asarray(fb, float)))
    rows = _corner_contacts(faces, sides, centroids)
    return _pack(arch.masses, centroids, arch.inertias, rows, n + 1, arch.size,
                 getattr(arch, "name", ""))


def blocks_of_arcade(arc) -> BlockSystem:
    """The blocks and contacts of an :class:`~archrock.geometry.arcade.Arcade` (its graph:
    contact c between blocks ``a`` and ``b``, -1 the ground)."""
    centroids = np.asarray(arc.centroids, float)
    sides = [(int(ct.a), int(ct.b)) for ct in arc.contacts]
    faces = [(np.asarray(ct.points, float),) * 2 for ct in arc.contacts]
    rows = _corner_contacts(faces, sides, centroids)
    return _pack(arc.masses, centroids, arc.inertias, rows, len(sides), arc.size,
                 getattr(arc, "name", ""))


def block_on_ground(width: float, height: float, density: float = 2000.0) -> BlockSystem:
    """Housner's block: a rectangle ``width`` x ``height`` [m] standing on the ground (one joint,
    its base, from (-width/2, 0) to (width/2, 0)).  Its size is the half-diagonal R."""
    for name, v in (("width", width), ("height", height), ("density", density)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not 0 < v < 1e6:
            raise ArchInputError(f"{name}: {v!r}; allowed 0 < {name} < 1e6")
    m = density * width * height
    inertia = m * (width ** 2 + height ** 2) / 12.0
    c = np.array([[0.0, 0.5 * height]])
    face = np.array([[-0.5 * width, 0.0], [0.5 * width, 0.0]])
    rows = _corner_contacts([(face, face)], [(GROUND, 0)], c)
    return _pack([m], c, [inertia], rows, 1, 0.5 * float(np.hypot(width, height)),
                 f"block {width:g} x {height:g} m")
