"""Figures and animations of results (matplotlib, imported lazily)."""
from kinelab.plot._synthesis import (burmester_curves, motion_solution, path_solution,
                                     prescribed_positions, structural_error)

__all__ = ["prescribed_positions", "motion_solution", "burmester_curves", "structural_error",
           "path_solution"]
