"""Angles as the corpus checks compare them: one wrap, shared by the drive path, map registration and navigation."""
import math


def wrap(angle: float) -> float:
    """`angle` in (-pi, pi], the same direction."""
    return math.atan2(math.sin(angle), math.cos(angle))
