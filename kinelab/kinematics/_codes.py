"""The kernel's interface, shared by its compiled form (``_kernel.py``) and its numpy form
(``_interpreter.py``): the codes of a plan's operations and of a sample's status, the
numerical tolerances both apply, and the packed plan of the one-sample entry point.

Nothing here imports numba: the rest of kinelab reads these without loading the compiler.
The compiled kernel takes these numbers in when it is compiled, and numba's cache on disk
sees changes to ``_kernel.py`` only: after changing a number here, touch ``_kernel.py`` (or
remove ``kinelab/kinematics/__pycache__/*.nb?``) so that it is compiled again.
"""
from __future__ import annotations

import numpy as np

# operation codes: rows of ops_i / ops_f.  Points are given by the item of their x.
OP_DRIVE_ANGLE = 1   # i: b, a (-1: ground frame), m           f: sign
OP_LOCK_ANGLE = 2    # i: b, a                                 f: offset
OP_RIGID_POINT = 3   # i: p, link, anchor                      f: rx, ry (link frame)
OP_SLIDE_POINT = 4   # i: out, base, dirlink, m                f: beta, s0, sign
OP_LINES = 5         # i: out, o1, l1, o2, l2                  f: beta1, beta2
OP_RRR = 6           # i: b, c, X, Y, Z                         f: lb, lc, sigma, offb, offc
OP_RRP = 7           # i: b, X, Y, o, g                         f: lb, beta, sigma, offb
OP_RPR = 8           # i: G, X, Z                               f: rho_x, rho_y, u_x, u_y, sigma
OP_NEWTON = 9        # i: group
OP_SLIDE_OUT = 10    # i: slide, p, o, g                        f: beta, s0
OP_TWO_POINTS = 11   # i: b, p1, p2                             f: offset
OP_FRAME_POINT = 12  # i: p, a, b                               f: lam, mu
OP_GEAR = 13         # i: out, x, y (items)                     f: c0, cx, cy
                     #   out = c0 + cx x + cy y: a gear pair's angle (exactly linear)
OP_GEAR_SLIDE = 14   # i: out, base, dirlink, x, y              f: beta, c0, cx, cy
                     #   a rack's point on its line at t = c0 + cx x + cy y
OP_CAM = 15          # i: out, cam, guide (-1: frame), pieces     f: c0
                     #   an oscillating follower's angle: out = theta_guide + c0 + S(theta),
                     #   theta = theta_cam - theta_guide (the guide 0 when -1)
OP_CAM_SLIDE = 16    # i: out, base, dirlink, cam, guide, pieces  f: beta, c0
                     #   a translating follower's point on its line at t = c0 + S(theta)
OP_CAM_DATA = 17     # the program's table after its cam operation: CAM_ROWS rows a piece
                     #   (kinelab.model._cams: PIECE_WIDTH numbers), skipped when run
CAM_ROWS = 3         # rows of ops_f a piece of a cam program takes (3 x 8 = PIECE_WIDTH)

# Newton-group constraint kinds (rows of con_i / con_f); a side is either a link of the
# group (g >= 0, with a point given in the link's frame) or known (g = -1, a point item).
C_REVOLUTE = 0     # i: kind, gi, pi, li, gj, pj, lj             f: rix, riy, rjx, rjy
C_PRISMATIC = 1    # i: kind, gg, po, lg, gs, pp, ls             f: rox, roy, rpx, rpy, beta, offset
C_DRIVE_ANGLE = 2  # i: kind, ga, -, la, gb, -, lb, m            f: sign
C_DRIVE_SLIDE = 3  # i: kind, gg, po, lg, gs, pp, ls, m          f: rox, roy, rpx, rpy, beta, s0

# status codes written per sample
ST_OK = 0
ST_NO_ASSEMBLY = 1     # a closed-form group cannot close (gap > 0)
ST_NO_CONVERGENCE = 2  # a Newton group failed even with the smallest continuation step

DISC_TOL = 1e-12   # relative: a discriminant this far below zero is rounding at a limit position
DISC_ZERO = 1e-15  # relative: a discriminant this close to zero is zero (its rounding is a
                   # few eps): a dyad at its straight position comes out straight, exactly
FOLDED = 1e-16     # an RRR dyad whose ends are closer than 1e-8 of its arm has folded: the
                   # direction of d = Z - X is rounding, the direction it moves along is not

# Newton groups measure their unknowns in their own units, so that nothing depends on the
# unit a mechanism is drawn in: an anchor's x and y in sizes of the mechanism (the plan's
# ``scale``), an angle in radians.  Their Jacobian's singularity measure is the smallest
# singular value of the Jacobian with its columns, then its rows, scaled to unit norm, which
# no unit changes (the kernel's ``_smallest_singular_value``, SINGULAR_STEPS steps of inverse
# iteration).
NEWTON_MAX_ITER = 12
NEWTON_TOL = 1e-13        # step (in those units) at which Newton has converged
NEWTON_STALL = 1e-10      # ... or a step below this that is not half the one before: near a
                          # singular configuration rounding, amplified by the Jacobian's
                          # condition, keeps the steps from shrinking; the solution is then as
                          # accurate as the configuration allows
JUMP_RATIO = 0.2          # a correction this large against the predicted step means a jump
JUMP_FLOOR = 1e-9         # ... added to the predicted step in that test (in those units)
SINGULAR_STEPS = 2        # of inverse iteration for the measure of a Newton group
BASE_MIN = 1e-6           # a group solved where its measure is
                          # below this is written but not kept to predict from: next to a
                          # singular configuration K and L are rounding
NODE_STEP = 1e-3          # a sample on a singular configuration the motion passes (a change
                          # point) is placed from this fraction of a continuation step either side
CONTINUATION_STEP = 0.3   # largest continuation step of a Newton group: rad, or sizes of the
                          # mechanism for a slide (the input's unit, ``input_units``).  The
                          # second-order predictor misses by about step**3 / 6 there, which
                          # Newton closes in four steps and the jump test tells from a branch
                          # change; samples up to 17 degrees apart take one step each
LIKELY_LAST = 1e-5        # a Newton step after one this small (in those units) is likely the
                          # last: the singularity measure's scalings are taken there
HERMITE_REACH = 2.0       # with one input, a step at most this many times the one before is
                          # predicted by the quintic through the last two states (their S, K
                          # and L), which misses by about step**6: samples 5 degrees apart
                          # then converge in two Newton steps

SINGULAR_TOL = 5e-3
"""Singularity measure (a sine, see ``KinematicSolution.singularity``) below which a sample is
flagged singular.  Rounding in the positions, of relative size eps = 2.2e-16, reaches K with
a factor of about eps / s**2 and L with about eps / s**3 near a singular configuration of
measure s (near a limit position s**2 shrinks like the distance to it, so there both are
about eps / s**2).  At s = 5e-3 that is 1e-11 for K and 1e-8 for L: every K and L that is
not flagged is accurate to 1e-8 relative (tests/kinematics/test_conditioning.py checks it
against 60-digit references).  A change point is flagged within about 5e-3 rad of it; a
limit position within about 1e-5 rad.  (Here, not in ``_analyze``: the dynamics kernel
compiles it in.)"""

def input_units(kinds, scale) -> np.ndarray:
    """The unit in which continuation measures each input's steps: 1 rad for an angle, the
    mechanism's size for a slide."""
    return np.array([1.0 if kind == "angle" else scale for kind in kinds], float)


# One sample at a time (an input dragged in an interactive view): the plan and the outputs
# packed in a few arrays, since each array argument costs about 0.1 us at the call.
HEADER = 7  # plan_i starts with n_items, n_angles, ops, ops_i columns, ops_f columns,
            # const items, stored items


def pack_plan(ops_i, ops_f, const_items, const_values, n_items, n_angles, stored):
    """A plan for the kernel's one-sample entries (``evaluate_one_sample``): (plan_i, plan_f)."""
    head = [n_items, n_angles, ops_i.shape[0], ops_i.shape[1], ops_f.shape[1],
            len(const_items), len(stored)]
    plan_i = np.concatenate([head, ops_i.ravel(), const_items, stored]).astype(np.int64)
    plan_f = np.concatenate([ops_f.ravel(), const_values]).astype(np.float64)
    return plan_i, plan_f


def one_sample_layout(n_stored, M):
    """Where the kernel's one-sample entries write in ``out``: the slices of the jets (n_stored,
    1 + M + M*M), the rates (n_stored, 2), det J and the singularity measure, the gap and the
    failed operation, and the status; and the length of ``out``."""
    w = n_stored * (1 + M + M * M)
    r = w + 2 * n_stored
    return slice(0, w), slice(w, r), slice(r, r + 2), slice(r + 2, r + 4), r + 4, r + 5


def pack_tracked(ops_i, ops_f, const_items, const_values, n_items, n_angles, stored, M):
    """A plan for the kernel's ``run_tracked`` entries with the scratch space of its samples:
    (ints, floats), two 2-D arrays.  ints: a row (n_items, n_angles, operations, ops_i
    columns, ops_f columns, stored items), ops_i, a row of the stored items, two rows for the
    lanes' status and failed operation, one for the status.  floats: ops_f, the jet of every
    item (n_items rows of 1 + M + M*M: the constant items' values set, as each sample leaves
    the others all written), then rows of scratch (see ``_kernel._tracked``) and the sample
    x (3 rows of M)."""
    n_ops, wi = ops_i.shape
    wf = ops_f.shape[1]
    w = 1 + M + M * M
    ints = np.zeros((5 + n_ops, max(wi, len(stored), 8)), np.int64)
    ints[0, :6] = n_items, n_angles, n_ops, wi, wf, len(stored)
    ints[1:1 + n_ops, :wi] = ops_i
    ints[1 + n_ops, :len(stored)] = stored
    floats = np.zeros((n_ops + n_items + 9 + M, max(wf, w, 8)))
    floats[:n_ops, :wf] = ops_f
    floats[n_ops + np.asarray(const_items, np.int64), 0] = const_values
    return ints, floats


def tracked_layout(n_stored, M):
    """Where the kernel's ``run_tracked`` entries write in ``out`` (2 n_stored + 2 rows of
    1 + M + M*M, flat): the jets (rows 0 .. n_stored - 1), the rates (the next n_stored rows,
    first two columns), det J and the singularity measure (the next row), the gap, the
    failed operation and the status (the last row); and the length of ``out``."""
    w = 1 + M + M * M
    return w, (2 * n_stored + 2) * w
