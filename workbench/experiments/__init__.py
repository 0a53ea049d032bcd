"""Paper experiments: one folder per research question, the only code that knows a paper's experiment.

Each folder holds the glue of one committed study (``studies/<name>.toml``): its scenario (the
load commands of a case), its analysis, its report figures and, for a study driven by something
other than ``run(robot, load, options)``, its study kind.  Generic layers (``study``, ``report``,
``physics``, ``models``, ``compare``, ...) never import this package; they find its code through
the rows of :mod:`workbench.registry`.  To add a study: add a folder here, then its rows in
``workbench/registry.py`` and ``studies/<name>.toml`` (``docs/architecture.md``).
"""
