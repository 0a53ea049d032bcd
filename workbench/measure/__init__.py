"""Measurements as a reference: read a robot's measured data, calibrate each model, predict held-out data.

The calibration study kind (``[study] kind = "calibration"``, ``docs/measurements.md``): ``types``
(the values passed between the parts), the data-file reader and the study file's ``[measurements]``
and ``[calibration]`` tables, the seeded split, the least-squares calibration and the study kind.
A generic layer above ``study`` (it runs through the study pipeline's executors) and below ``report``.
"""
