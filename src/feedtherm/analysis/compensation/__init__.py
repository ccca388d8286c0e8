"""Thermal-error compensation: from a few sensor temperatures to the screw's elongation D,
and the positioning error E(x, t) along the stroke.

- :mod:`.data`: random training and held-out cycles run through a model with every candidate sensor;
- :mod:`.noise`: each candidate's kind (contact, infrared), its noise and offset, the noisy readings;
- :mod:`.regression`: the industry baseline, multiple linear regression with optional lags and a ridge;
- :mod:`.selection`: greedy forward choice of K sensors on held-out error;
- :mod:`.metrics`: residual error of a law over cycles (RMS, maximum, reduction);
- :mod:`.conditioning`: a law's largest weight and the error each sensor's declared offset causes;
- :mod:`.stroke`: the positioning error E(x, t) along the stroke, a Legendre basis in x per regressor;
- :mod:`.law` and :mod:`.evaluator`: the law as a JSON document, and its evaluation on a stream;
- :mod:`.pairs`, :mod:`.adapt`, :mod:`.leave_one_out`, :mod:`.adaptation`: a law updated on measured
  pairs of its machine (Bayesian), and how far the update carries to a condition left out.
"""
