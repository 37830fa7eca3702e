"""Dimensional synthesis of four-bars (*Mecanismos*, §3.2 and §6).

Motion generation (the coupler passes through prescribed positions: two to five exactly,
more by least squares), function generation (the rocker angle is a prescribed function of
the crank angle), path generation (a coupler point passes through prescribed points), and
the complete solution set of five path points with both fixed pivots given (every
one of its 36 roots, by homotopy continuation: :func:`five_point_path`), and
spherical four-bars (:func:`spherical_function` by the spherical Freudenstein equation,
:func:`spherical_three_orientations` and :func:`spherical_four_orientations` for coupler
orientations, each linkage a :class:`kinelab.spatial.SphericalFourBar` checked by its own
analysis), and
the designer's questions about limit positions: a crank-rocker for a rocker swing and a
time ratio (with the best transmission angle), quick returns for a time ratio.  Every synthesized linkage comes back as
a kinelab model, sketched in its first position, with the checks made by moving it with
the planar kinematics engine:

- **branch defect**: some prescribed position lies on the other assembly branch of
  position 1, or the crank cannot turn from position 1 to it (either way round)
  without passing a limit (toggle) or dead-centre configuration;
- **order defect**: turning the crank one way does not pass the positions in the order
  1, 2, ..., n;
- **circuit defect**: some position lies on the other circuit of a Grashof linkage, which
  no motion reaches without taking the linkage apart;
- the Grashof class and the smallest transmission angle on the way, measured by the engine;
  below a limit (30 deg unless the task says otherwise, ``min_transmission_angle``) it is a
  **transmission angle defect**.

All lengths in metres and angles in radians (``degrees=True`` where people type angles).
The notes' examples in centimetres are reproduced in metres: the synthesis is
scale-free, so every length simply scales by 0.01.
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.synthesis._approximate": ("approximate_positions", "fit_dyads"),
    "kinelab.synthesis._burmester": ("BurmesterCurves", "burmester_curves", "center_point_cubic",
                                     "center_points", "four_positions"),
    "kinelab.synthesis._five_positions": ("burmester_points", "five_positions", "burmester"),
    "kinelab.synthesis._five_point_path": ("FivePointLinkage", "FivePointSolutions",
                                           "five_point_path"),
    "kinelab.synthesis._function": ("FunctionSolution", "chebyshev_points", "freudenstein",
                                    "function_generation", "function_pairs",
                                    "function_generation_pairs"),
    "kinelab.synthesis._linkage": ("TRANSMISSION_LIMIT", "fourbar_model"),
    "kinelab.synthesis._motion": ("MotionSolution", "TwoPositions", "three_positions",
                                  "two_positions"),
    "kinelab.synthesis._path": ("MAX_PATH_POINTS", "PathSolution", "coupler_curves",
                                "curve_distances", "path_generation"),
    "kinelab.synthesis._pivots": ("fixed_pivot", "moving_pivot"),
    "kinelab.synthesis._positions": ("Poles", "Positions", "pole", "poles"),
    "kinelab.synthesis._quick_return": ("CrankRocker", "QuickReturn", "crank_rocker",
                                        "crank_rockers", "imbalance_angle", "max_time_ratio",
                                        "offset_slider_crank", "slotted_lever", "whitworth"),
    "kinelab.synthesis._results": ("SolutionList",),
    "kinelab.synthesis._nine_point_path": ("NinePointLinkage", "NinePointSolutions",
                                           "nine_point_path"),
    "kinelab.synthesis._sixbar": ("SIXBAR_KINDS", "SixBarSolution", "sixbar"),
    "kinelab.synthesis._spherical": ("SphericalCenterAxes", "SphericalFunctionSolution",
                                     "SphericalMotionSolution", "spherical_center_axes",
                                     "spherical_four_orientations", "spherical_freudenstein",
                                     "spherical_function", "spherical_three_orientations"),
})

__all__ = ["Positions", "Poles", "poles", "pole", "fixed_pivot", "moving_pivot",
           "two_positions", "TwoPositions", "three_positions", "MotionSolution",
           "four_positions", "center_points", "center_point_cubic", "burmester_curves",
           "BurmesterCurves", "SolutionList", "function_generation", "function_pairs",
           "FunctionSolution", "chebyshev_points", "freudenstein", "path_generation", "PathSolution",
           "coupler_curves", "curve_distances", "fourbar_model", "five_positions",
           "burmester_points", "approximate_positions", "fit_dyads", "crank_rocker",
           "crank_rockers", "CrankRocker", "offset_slider_crank", "slotted_lever", "whitworth",
           "QuickReturn", "imbalance_angle", "max_time_ratio", "MAX_PATH_POINTS", "TRANSMISSION_LIMIT",
           "five_point_path", "FivePointSolutions", "FivePointLinkage",
           "nine_point_path", "NinePointSolutions", "NinePointLinkage",
           "function_generation_pairs", "burmester", "sixbar", "SixBarSolution", "SIXBAR_KINDS",
           "spherical_freudenstein", "spherical_function", "SphericalFunctionSolution",
           "spherical_three_orientations", "SphericalMotionSolution", "spherical_center_axes",
           "SphericalCenterAxes", "spherical_four_orientations"]
