"""Figures and animations of results (matplotlib, imported lazily)."""
