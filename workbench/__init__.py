"""trunk-workbench: constant-curvature kinematics vs Exudyn physics for continuum robots.

Sub-packages, one per concern:

- :mod:`workbench.kinematics` -- constant-curvature kinematics (numpy only)
- :mod:`workbench.robot` -- robot descriptions (frozen dataclasses) and presets
- :mod:`workbench.physics` -- Exudyn models (ANCF, geometrically exact beam, spring-link)
- :mod:`workbench.reference` -- independent reference solutions (elastica, ...)
- :mod:`workbench.study` -- study configs, sweep expansion, executors, result store
- :mod:`workbench.compare` -- CC-vs-physics metrics over result tables
- :mod:`workbench.report` -- HTML reports and figures
"""

__version__ = "0.1.0"
