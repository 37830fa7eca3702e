"""Figures and animations of results (matplotlib, imported only inside the functions).

:func:`curves` (position, velocity, acceleration against the input), :func:`coefficients`
(K and L), :func:`coupler_curve`, :func:`transmission`, :func:`mechanism` (the linkage at one
sample), :func:`animate` (GIF or MP4) and :func:`save` (a figure, atomically).
"""
from kinelab.plot._animate import animate, can_write_mp4
from kinelab.plot._figures import (coefficients, coupler_curve, curves, input_axis, mechanism, save,
                                   transmission)

__all__ = ["curves", "coefficients", "coupler_curve", "transmission", "mechanism", "animate",
           "save", "can_write_mp4", "input_axis"]
