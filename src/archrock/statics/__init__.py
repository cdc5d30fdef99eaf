"""Layer 2, statics: what an arch can carry before it turns into a mechanism.

* :mod:`.limit`: the Heyman optimum (static LP, four-hinge search certified by its line of
  thrust, mechanisms with lift-off), minimum thickness;
* :mod:`.friction`: the same with Coulomb friction at the joints;
* :mod:`.thrust`: the range of horizontal thrust under self-weight (spreading and closing supports).
"""
