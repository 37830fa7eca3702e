"""Disk cams from a motion program (Norton, *Design of Machinery*, ch. 8).

- motion laws (:data:`LAW_NAMES`: simple harmonic, cycloidal, 3-4-5 and 4-5-6-7 polynomials,
  modified trapezoid, modified sine, a polynomial through boundary conditions); segments of
  rise, dwell and return (:class:`Segment`) making a :class:`MotionProgram` over one turn, its
  :class:`SVAJ` in closed form (:func:`motion`) and its jumps at the joints (:class:`Discontinuity`);
- profiles: :class:`Follower` (knife-edge, roller, flat-faced; translating or oscillating),
  :func:`profile` (pitch curve, profile, pressure angle, radius of curvature, undercutting) in
  a :class:`CamProfile`, :func:`smallest_base_circle`;
- dynamics: :func:`follower_forces` (the contact force of a spring-loaded follower, the jump
  check, the shaft torque) in a :class:`FollowerForces`;
- export: :func:`profile_svg` and :func:`write_dxf`;
- tasks: :func:`read_cam_task` (a task file's content, as ``kinelab cam`` reads it) and
  :func:`solve_cam_task`.
"""
from kinelab._lazy import exports

__getattr__, __dir__ = exports(__name__, {
    "kinelab.cams._laws": ("LAWS", "law_values", "polynomial_coefficients"),
    "kinelab.cams._program": ("Segment", "MotionProgram", "SVAJ", "Discontinuity", "KINDS",
                              "LAW_NAMES", "motion"),
    "kinelab.cams._profile": ("Follower", "CamProfile", "profile", "smallest_base_circle",
                              "FOLLOWER_TYPES", "FOLLOWER_MOTIONS"),
    "kinelab.cams._export": ("profile_svg", "write_dxf"),
    "kinelab.cams._dynamics": ("FollowerForces", "follower_forces"),
    "kinelab.cams._task": ("CamTask", "CamSolution", "read_cam_task", "solve_cam_task",
                           "read_segments", "segments_data"),
})

__all__ = ["LAWS", "LAW_NAMES", "KINDS", "law_values", "polynomial_coefficients", "Segment",
           "MotionProgram", "SVAJ", "Discontinuity", "Follower", "CamProfile", "profile",
           "smallest_base_circle", "FOLLOWER_TYPES", "FOLLOWER_MOTIONS", "profile_svg",
           "write_dxf", "FollowerForces", "follower_forces", "CamTask", "CamSolution",
           "read_cam_task", "solve_cam_task", "read_segments", "segments_data", "motion"]
