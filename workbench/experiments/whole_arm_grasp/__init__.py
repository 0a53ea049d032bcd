"""Whole-arm grasping with contact (Hannan & Walker Fig 6; Shao's scooping): the CC plan of a wrap vs the physical wrap."""
