"""Hannan & Walker's elephant trunk: the CC cable plan of a line and a grasp shape replayed on spring-and-cable physics."""
