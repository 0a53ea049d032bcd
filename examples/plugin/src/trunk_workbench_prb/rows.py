"""The registry rows of this plug-in, each loaded by one entry point of ``pyproject.toml``.

Each row has exactly the type of the workbench's built-in rows of its group
(:data:`workbench.registry.ROW_TYPES`): a :class:`~workbench.registry.ModelInfo` for
``trunk_workbench.models``, a ``"module:function"`` string for ``trunk_workbench.presets``.
Data only, like ``workbench/registry.py``: importing this module imports no model code (the
workbench loads it in every process that lists or validates, before any model runs).
"""

from __future__ import annotations

from workbench.registry import Capabilities, ModelInfo

__all__ = ["MODEL", "PRESET"]

#: The ``prb_chain`` model (:mod:`trunk_workbench_prb.chain`).  Its capabilities are what its
#: ``run`` accepts (it refuses everything else itself: ``tests/test_prb_chain.py``); order 2 is the
#: tip's convergence order in the number of links measured by that test against the elastica.
MODEL = ModelInfo(
    "trunk_workbench_prb.chain:run", "PRB chain", "#e377c2", order=2.0, capabilities=Capabilities(
        dimensions=("planar",), actuation=("tension",), tendon_models=("continuum",), length_tendon_models=(),
        spatial_length_tendon_models=(), loads=("tip_force", "tip_torque"), analyses=("static",), torsion=False, gravity="in_plane",
        tapered_continuum_tendons=(), spatial_tapered_continuum_tendons=(), disk_weights="at the disk",
        extensibility=(), tendon_path="continuum", tendon_friction=False,
        note="planar pseudo-rigid-body (Hencky bar-chain) rod, n_elements rigid links; continuum tendons of "
             "constant offset in tension mode, static only (plug-in trunk-workbench-prb)"))

#: The ``prb_niti_pair`` preset (:func:`trunk_workbench_prb.preset.prb_niti_pair`).
PRESET = "trunk_workbench_prb.preset:prb_niti_pair"
