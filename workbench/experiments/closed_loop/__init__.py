"""Closed-loop control on the physics: Hannan & Walker's Eq. 10-11 controller reading the physics tip.

``controller`` (the resolved-rate / null-space controller, open loop and in the loop), ``plants``
(the cable map, physics and CC plants), ``scenario`` (path and controller parameters), ``worker``
(one case's rows), ``kind`` (the ``closed_loop`` study kind), ``figures`` (the report).
Study: ``studies/closed_loop.toml``.
"""
