"""The finite-element first bending frequency of a non-uniform robot (``workbench.robot.derived``) against
an independent one: the free vibration of the same robot in the Exudyn geometrically exact beam (beam3d).

Robot: two 0.4 m steel sections, 6 mm then 4 mm, 8 disks of 5 g each, a 20 g payload (no analytic value).
Excitation as in ``tests/physics/test_beam3d.py::test_free_vibration_first_frequency``: a tiny tendon
tension (1e-3 N) switched on at t = 1 ms; the frequency from the upward zero crossings of the tip
deflection about its mean.  beam3d lumps each disk onto its element's two nodes and includes shear and
rotary inertia, so the two agree to its discretisation and lumping, not exactly: 0.5 % (half the
tolerance of the uniform test there; the measured difference is in ``docs/robot-show.md``).
"""

from __future__ import annotations


import numpy as np
import pytest

from workbench.robot import CrossSection, LoadCase, Payload, Robot, Section, TendonActuation, TendonGroup
from workbench.robot.derived import first_bending_frequency


@pytest.mark.slow
def test_stepped_robot_frequency_matches_beam3d_free_vibration():
    from workbench.models.result import SolverOptions
    from workbench.physics import beam3d

    g1 = TendonGroup(angles=(0.0,), offset=0.015, area=1e-7, strength=2e9)
    sections = tuple(Section(length=0.4, cross_section=CrossSection.circular(d), n_disks=8, disk_mass=0.005,
                             tendons=g1 if j == 1 else None) for j, d in enumerate((6e-3, 4e-3)))
    robot = Robot(sections=sections, payload=Payload(mass=0.02))
    f_fe = first_bending_frequency(robot)
    assert f_fe.method == "finite elements"
    T1 = 1.0 / f_fe.hertz
    act = TendonActuation("tension", (1e-3,), start_times=(1e-3,), ramp_durations=(0.0,))
    res = beam3d.run(robot, LoadCase(actuation=act, analysis="dynamic", duration=6 * T1),
                     SolverOptions(n_elements=32, tendon_model="eyelets", time_step=T1 / 200, spectral_radius=0.9))
    t, x = res.time, res.series["tip_position"][:, 0]
    keep = t > 0.01
    t, x = t[keep], x[keep] - 0.5 * (x[keep].max() + x[keep].min())
    i = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    tc = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    assert len(tc) >= 5
    f_beam = (len(tc) - 1) / (tc[-1] - tc[0])
    assert f_beam == pytest.approx(f_fe.hertz, rel=5e-3)
