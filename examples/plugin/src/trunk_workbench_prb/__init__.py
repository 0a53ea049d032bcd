"""trunk-workbench-prb: an example plug-in of the trunk workbench (``docs/plugins.md``).

It registers, through entry points of its ``pyproject.toml``, one model and one robot preset:

* ``prb_chain`` (group ``trunk_workbench.models``): a planar pseudo-rigid-body (Hencky bar-chain)
  model of a tendon-driven rod, :mod:`trunk_workbench_prb.chain`;
* ``prb_niti_pair`` (group ``trunk_workbench.presets``): a two-section NiTi rod of the sizes of
  Rao et al. (2021) with one antagonistic tendon pair per section, :mod:`trunk_workbench_prb.preset`.

The rows themselves are in :mod:`trunk_workbench_prb.rows` (data only: importing it imports no
model code).  Its tests are ``examples/plugin/tests``; its study ``examples/plugin/studies/prb_chain.toml``.
"""

__version__ = "0.1.0"
