#!/usr/bin/python3
"""Rigid blocks with corner contacts stepped by Siconos (INRIA), to cross-check archrock's own
engine (archrock.contact.nscd) on the same structure, the same step and the same contact laws.

Runs under the SYSTEM Python with Debian's ``python3-siconos`` (Siconos 4.4) and numpy only --
it never imports archrock, and archrock never imports siconos:

    /usr/bin/python3 benchmarks/siconos_blocks.py IN.json OUT.json

IN.json (SI units; the arrays are those of archrock's ``BlockSystem``):
  bodies: masses (nb,) [kg/m], centroids (nb, 2) [m] at rest, inertias (nb,) [kg m];
  contacts: owner, face (nc,) (-1: the ground), corner, face_start, tangent, normal (nc, 2) at
  rest (the normal toward the owner), length (nc,) [m];
  g [m/s^2], h [s], theta (Moreau-Jean's), mu, e; optional: solver ("nsgs", the default, or
  "lemke"), tolerance (the solver's, default 1e-8), activation [m] (a contact whose gap
  predicted at mid-step is below it enters the step's problem; default 1e-9), margin (a corner
  bears on its face up to this fraction of the face's length past its ends; default 0.05);
  cases: a list of {accel: the ground's acceleration per step [m/s^2] (a list, or a number with
  ``steps``), q0, v0 (nb, 3) optional (x, y, rotation from rest; vx, vy, omega), every: keep one
  step in ``every``, stop_rotation [rad]: stop once a body has turned by more than it}.
OUT.json: {siconos: version, cases: [{t (n,), q (n, nb, 3), v (n, nb, 3), steps, stopped,
seconds}]}, the first record the initial state.

Model: each block a ``LagrangianDS`` with q = (x, y, rotation), constant mass matrix
diag(m, m, I) and the body force (-m xg''(t), -m g, 0) of the ground's frame, set before each
step; each corner contact an ``Interaction`` with ``NewtonImpactFrictionNSL(e, 0, mu, 2)``
linking the corner's body and the face's body; ``MoreauJeanOSI(theta)`` and
``FrictionContact(2)`` (2-D NSGS), the default ``TimeStepping``.

The contact relation is the exact one, relinearised at every step: a ``LagrangianLinearTIR``
whose H and offset are re-set before each step so that y = H q + b is the corner's exact gap
(and position along the face) at q_k and H is its exact Jacobian there -- what Moreau-Jean uses
of a scleronomous relation (the gap at q_k for the active set, H(q_k) for the velocities).  A
Python ``LagrangianScleronomousR`` (a SWIG director) would be the textbook form, but it crashes
Siconos 4.4 in MoreauJeanOSI::computeFreeOutput.  Because the relations are re-set, the
one-step problem is told its blocks are stale every step (``setHasBeenUpdated(False)``), and the
bodies are nonlinear ``LagrangianDS`` so that the problem is never treated as time-invariant.
"""

from __future__ import annotations

import json
import math
import sys
import time

import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn

#: the 2-D friction solvers offered (Siconos' numerics): nonsmooth Gauss-Seidel, or Lemke's
#: pivoting on the LCP form of the 2-D Coulomb problem
SOLVERS = {"nsgs": sn.SICONOS_FRICTION_2D_NSGS, "lemke": sn.SICONOS_FRICTION_2D_LEMKE}

#: a corner off its face (past the ends by more than the margin) gets this gap [m]: never active
FAR = 1.0e3


def _rot(th):
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s], [s, c]])


class Blocks:
    """The Siconos model of one structure and one case."""

    def __init__(self, data, case):
        self._read_structure(data)
        nb = self.m.size
        q0 = np.zeros((nb, 3))
        q0[:, :2] = self.x0
        if case.get("q0") is not None:
            q0 = np.asarray(case["q0"], float).reshape(nb, 3)
        v0 = np.zeros((nb, 3)) if case.get("v0") is None else np.asarray(case["v0"], float)
        accel = case["accel"]
        if np.isscalar(accel):
            accel = np.full(int(case["steps"]), float(accel))
        self.accel = np.asarray(accel, float)
        self.nsds = sk.NonSmoothDynamicalSystem(0.0, (self.accel.size + 1) * self.h)
        self._add_bodies(q0, v0.reshape(nb, 3))
        self._add_contacts(float(data["e"]), float(data["mu"]))
        self._add_simulation(data)
        self._relink(q0)

    def _read_structure(self, data):
        b, c = data["bodies"], data["contacts"]
        self.m = np.asarray(b["masses"], float)
        self.x0 = np.asarray(b["centroids"], float).reshape(-1, 2)
        self.inertia = np.asarray(b["inertias"], float)
        self.owner = np.asarray(c["owner"], int)
        self.face = np.asarray(c["face"], int)
        self.corner = np.asarray(c["corner"], float).reshape(-1, 2)
        self.fstart = np.asarray(c["face_start"], float).reshape(-1, 2)
        self.tangent = np.asarray(c["tangent"], float).reshape(-1, 2)
        self.normal = np.asarray(c["normal"], float).reshape(-1, 2)
        self.length = np.asarray(c["length"], float)
        self.g, self.h = float(data["g"]), float(data["h"])
        self.margin = float(data.get("margin", 0.05))

    def _add_bodies(self, q0, v0):
        """One LagrangianDS a block, q = (x, y, rotation), M = diag(m, m, I)."""
        self.ds = []
        for i in range(self.m.size):
            mass = np.diag([self.m[i], self.m[i], self.inertia[i]])
            ds = sk.LagrangianDS(q0[i].copy(), v0[i].copy(), mass)
            ds.setFExtPtr(np.array([0.0, -self.m[i] * self.g, 0.0]))
            self.nsds.insertDynamicalSystem(ds)
            self.ds.append(ds)

    def _add_contacts(self, e, mu):
        """One Interaction a corner contact, between the corner's and the face's bodies (the
        relations and interactions are kept here: Siconos holds no Python reference)."""
        self.rel, self.inter = [], []
        law = sk.NewtonImpactFrictionNSL(e, 0.0, mu, 2)
        for k in range(self.owner.size):
            bodies = self._bodies(k)
            rel = sk.LagrangianLinearTIR(np.zeros((2, 3 * len(bodies))), np.array([FAR, 0.0]))
            inter = sk.Interaction(law, rel)
            self.nsds.link(inter, *[self.ds[i] for i in bodies])
            self.rel.append(rel)
            self.inter.append(inter)

    def _add_simulation(self, data):
        self.osi = sk.MoreauJeanOSI(float(data.get("theta", 1.0)))
        # a contact enters the step's problem when its gap predicted at mid-step is below this
        # [m] rather than below 0: a closed contact left open by rounding (1e-15 m) must stay
        self.osi.setConstraintActivationThreshold(float(data.get("activation", 1e-9)))
        solver = data.get("solver", "nsgs")
        if solver not in SOLVERS:
            raise ValueError(f"solver: {solver!r}; allowed one of {', '.join(SOLVERS)}")
        self.osnspb = sk.FrictionContact(2, SOLVERS[solver])
        opts = self.osnspb.numericsSolverOptions()
        opts.dparam[0] = float(data.get("tolerance", 1e-8))  # SICONOS_DPARAM_TOL
        opts.iparam[0] = int(data.get("max_iterations", 10000))  # SICONOS_IPARAM_MAX_ITER
        td = sk.TimeDiscretisation(0.0, self.h)
        self.sim = sk.TimeStepping(self.nsds, td, self.osi, self.osnspb)

    def _bodies(self, k):
        return [i for i in (int(self.owner[k]), int(self.face[k])) if i >= 0]

    def q(self):
        return np.array([np.asarray(d.q(), float) for d in self.ds])

    def v(self):
        return np.array([np.asarray(d.velocity(), float) for d in self.ds])

    def _relink(self, q):
        """Each contact's H and offset: its exact gap, position along the face and Jacobian
        at the positions ``q`` (nb, 3)."""
        for k in range(self.owner.size):
            p, f = int(self.owner[k]), int(self.face[k])
            if p >= 0:
                cp = q[p, :2]
                pt = cp + _rot(q[p, 2]) @ (self.corner[k] - self.x0[p])
            else:
                pt = self.corner[k]
            if f >= 0:
                cf, rf = q[f, :2], _rot(q[f, 2])
                start = cf + rf @ (self.fstart[k] - self.x0[f])
                t, n = rf @ self.tangent[k], rf @ self.normal[k]
            else:
                start, t, n = self.fstart[k], self.tangent[k], self.normal[k]
            d = pt - start
            gap, along = float(d @ n), float(d @ t)
            ln = self.length[k]
            rows, qs = [], []
            for body, sign in ((p, 1.0), (f, -1.0)):
                if body < 0:
                    continue
                r = pt - q[body, :2]  # the contact point from the body's mass centre
                rows.append(sign * np.array([[n[0], n[1], r[0] * n[1] - r[1] * n[0]],
                                             [t[0], t[1], r[0] * t[1] - r[1] * t[0]]]))
                qs.append(q[body])
            big_h = np.hstack(rows)
            qc = np.concatenate(qs)
            off_face = ln > 0 and not -self.margin * ln <= along <= (1 + self.margin) * ln
            if off_face:
                big_h = np.zeros_like(big_h)
                offset = np.array([FAR, 0.0])
            else:
                offset = np.array([gap, along]) - big_h @ qc
            self.rel[k].setJachqPtr(big_h)
            self.rel[k].setEPtr(offset)

    def run(self, every=1, stop_rotation=None):
        """Step through the case's samples; the records (module docstring)."""
        every = max(1, int(every))
        ts, qs, vs = [0.0], [self.q()], [self.v()]
        stopped, done_steps = False, 0
        t0 = time.perf_counter()
        for step, a in enumerate(self.accel):
            for i, ds in enumerate(self.ds):
                ds.setFExtPtr(np.array([-self.m[i] * a, -self.m[i] * self.g, 0.0]))
            if step:  # (the first step's relations were set with the model)
                self._relink(self.q())
                # the relations changed: the outputs, active sets and blocks with them
                self.osnspb.setHasBeenUpdated(False)
                self.sim.updateOutput(0)
                self.sim.updateOutput(1)
                self.sim.updateIndexSets()
            self.sim.computeOneStep()
            self.sim.nextStep()
            done_steps = step + 1
            q = self.q()
            done = stop_rotation is not None and np.max(np.abs(q[:, 2])) > stop_rotation
            if (step + 1) % every == 0 or done or step + 1 == self.accel.size:
                ts.append((step + 1) * self.h)
                qs.append(q)
                vs.append(self.v())
            if done:
                stopped = True
                break
        return {"t": ts, "q": np.array(qs).tolist(), "v": np.array(vs).tolist(),
                "steps": done_steps, "stopped": stopped,
                "seconds": time.perf_counter() - t0}


def main(argv):
    if len(argv) != 3:
        print("usage: siconos_blocks.py IN.json OUT.json", file=sys.stderr)
        return 2
    with open(argv[1]) as fh:
        data = json.load(fh)
    out = {"siconos": getattr(sk, "__version__", None) or _version(), "cases": []}
    try:
        for case in data["cases"]:
            model = Blocks(data, case)
            out["cases"].append(model.run(case.get("every", 1), case.get("stop_rotation")))
    except KeyError as exc:
        print(f"siconos_blocks: error: {argv[1]}: missing field {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"siconos_blocks: error: {argv[1]}: {exc}", file=sys.stderr)
        return 2
    with open(argv[2], "w") as fh:
        json.dump(out, fh)
    return 0


def _version():
    try:
        from importlib.metadata import version

        return version("siconos")
    except Exception:  # noqa: BLE001 -- Debian's package carries no metadata
        return "4.4 (python3-siconos)"


if __name__ == "__main__":
    sys.exit(main(sys.argv))
