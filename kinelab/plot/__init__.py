"""Figures and animations of results (matplotlib, imported only inside the functions).

:func:`curves` (position, velocity, acceleration against the input), :func:`coefficients`
(K and L), :func:`coupler_curve`, :func:`transmission`, :func:`mechanism` (the linkage at one
sample), :func:`animate` (GIF or MP4) and :func:`save` (a figure, atomically).

Graphical methods: :func:`velocity_polygon` and :func:`acceleration_polygon` (to scale, beside
the mechanism), :func:`instant_centers` (with Kennedy's circle diagram), :func:`centrodes`,
:func:`derivatives` (of a measured curve, with error bands); the constructions step by step,
in English or Portuguese: :func:`tangent_construction` (graphical differentiation),
:func:`velocity_image` (by similar triangles), :func:`kennedy_steps` (with the circle
diagram).

Dynamics: :func:`effort_curves`, :func:`reaction_curves`, :func:`shaking_curves`,
:func:`energy_curves`.

Synthesis: :func:`prescribed_positions` (and their poles), :func:`motion_solution` (the
linkage in each position), :func:`burmester_curves`, :func:`five_positions` (the two
centre-point curves and Burmester's points), :func:`structural_error`,
:func:`path_solution`, :func:`limit_positions` (a crank-rocker or quick return at its dead
centres).

Spatial: :func:`spherical_fourbar` (the sphere, the joint axes and the links' arcs, in 3-D),
:func:`animate_spherical_fourbar` (the same moving over its input, GIF or MP4),
:func:`spatial_mechanism` (a spherical or spatial model in 3-D).

Sweeps: :func:`tolerance_band` and :func:`error_histogram` (a tolerance study).

Cams: :func:`cam_svaj` (the SVAJ diagram), :func:`cam_profile`, :func:`cam_pressure` (the
pressure angle over the cycle), :func:`cam_curvature` (radius of curvature), :func:`cam_forces`
(the follower's contact force, its jump region, and the shaft torque).
"""
from kinelab.plot._animate import animate, can_write_mp4
from kinelab.plot._cams import cam_curvature, cam_forces, cam_pressure, cam_profile, cam_svaj
from kinelab.plot._constructions import kennedy_steps, tangent_construction, velocity_image
from kinelab.plot._dynamics import effort_curves, energy_curves, reaction_curves, shaking_curves
from kinelab.plot._figures import (coefficients, coupler_curve, curves, input_axis, mechanism, save,
                                   transmission)
from kinelab.plot._graphical import (PANEL_CM, acceleration_polygon, centrodes, derivatives,
                                     drawing_scale, instant_centers, velocity_polygon)
from kinelab.plot._spatial import animate_spherical_fourbar, spatial_mechanism, spherical_fourbar
from kinelab.plot._sweep import error_histogram, tolerance_band
from kinelab.plot._synthesis import (burmester_curves, five_positions, limit_positions,
                                     motion_solution, path_solution, prescribed_positions,
                                     structural_error)

__all__ = ["curves", "coefficients", "coupler_curve", "transmission", "mechanism", "animate",
           "save", "can_write_mp4", "input_axis", "prescribed_positions", "motion_solution",
           "burmester_curves", "structural_error", "path_solution", "limit_positions",
           "five_positions", "effort_curves",
           "reaction_curves", "shaking_curves", "energy_curves", "velocity_polygon",
           "acceleration_polygon", "instant_centers", "centrodes", "derivatives", "drawing_scale",
           "PANEL_CM", "tolerance_band", "error_histogram", "tangent_construction",
           "velocity_image", "kennedy_steps", "cam_svaj", "cam_profile", "cam_pressure",
           "cam_curvature", "cam_forces", "spherical_fourbar",
           "spatial_mechanism", "animate_spherical_fourbar"]
