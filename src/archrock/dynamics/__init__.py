"""Layer 4, dynamics: the arch as a rocking mechanism under a ground motion.

* :mod:`.fourlink`: Oppenheim's four-link model (loop closure, M, L, F, P, tables of phi'');
* :mod:`.impact`: impact laws (the paper's, momentum, fixed, least loss) and ``ImpactSpec``;
* :mod:`.kernel`: the RK4 state machine over a chain of mechanisms (numba when installed);
* :mod:`.response`: ``prepare`` and ``respond`` for one arch (fast kernel or scipy reference);
* :mod:`.batch`, :mod:`.population`, :mod:`.sweep`: the same for many arches and motions.
"""
