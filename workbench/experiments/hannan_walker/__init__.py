"""Hannan & Walker's elephant trunk: CC cable plans replayed on spring-and-cable physics.

``replay`` / ``scenario.hannan_walker_line`` / ``figures``: the planar 16-joint, 8-cable reading (the
paper's planar experiments).  ``spatial`` / ``scenario.hannan_walker_spatial`` / ``figures_3d``: the
robot as built, 16 two-DOF joints and 16 cables, Eq. 1 applied per cable plane (study
``hannan_walker_3d``; the two-DOF-joint model is ``spring_link_cardan``).
"""
