"""Studies of one design in depth, each built on the one evaluation (:mod:`pumplink.evaluate`):
the force analysis, the speed study, the independent checks, the model-choice report, the piston
pump, the textbook's mechanisms, the workshop drawing and the kinematic methods."""
