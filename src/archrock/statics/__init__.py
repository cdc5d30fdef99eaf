"""Layer 2, statics: what an arch can carry before it turns into a mechanism.

* :mod:`.limit`: the Heyman optimum (:func:`~.limit.limit_analysis`), built from
  :mod:`.hinges` (hinges, mechanisms, the four-hinge candidates), :mod:`.sums` (their
  virtual-work multipliers), :mod:`.kinematic` (the four-hinge search and the governing
  mechanism), :mod:`.lp` (the static LP and the line of thrust), :mod:`.liftoff` (mechanisms
  with lift-off from the LP's dual) and :mod:`.thickness` (minimum thickness);
* :mod:`.friction`: the same with Coulomb friction at the joints;
* :mod:`.thrust`: the range of horizontal thrust under self-weight (spreading and closing supports);
* :mod:`.supports`: prescribed support movements, the displaced arch and the displacement capacity.
"""
