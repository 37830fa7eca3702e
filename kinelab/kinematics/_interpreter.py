"""The solution plan evaluated in plain numpy, every operation on all samples at once.

The compiled kernel (``_kernel.py``, run by :func:`kinelab.kinematics._evaluate.run_compiled`) is
fast once compiled, but compiling takes seconds per entry point in a fresh process.  This
module evaluates the same plans with the same results and no compilation: each operation
of the plan runs once on arrays of all samples, with the kernel's formulas, tolerances and
status codes (from ``_codes.py``).  Plans with Newton groups follow the samples
in order, as the kernel's continuation does, one sample at a time; each Newton step
assembles and solves the group's equations with numpy.

The state is one array ``J`` of shape (n_items, 1 + M + M*M, n): for each item of the plan
(link angle, point x or y, slide) its value, K and L, over n samples; ``J[i, 0]`` is the
item's value at every sample, contiguous.

Beyond rounding (see the tests), one difference: an operation that cannot close (gap > 0)
leaves its outputs NaN at that sample here, so that the operations after it use no numbers
made from them; the kernel writes nothing of such a sample but its status and its failed
group's gap, so the outputs agree.
"""
from __future__ import annotations

import math

import numpy as np

from kinelab.kinematics import _codes as k
from kinelab.kinematics._plan import Plan
from kinelab.model import cam_values

__all__ = ["run"]

_CHUNK = 4096        # samples evaluated together: their arrays stay in the processor's cache
_FOLD_ARMS = 1e-12   # relative: an RRR dyad folds (rather than failing to close) only with
                     # arms equal to this (the kernel's _rrr, where the literal stands)
_MIN_STEP = 1e-9     # fraction of a sample's step below which continuation gives up (the
                     # kernel's _continuation, where the literal stands)
_CLEAR = 10.0        # continuation steps of _NODE_STEP beyond which a state is "well clear"
_AT = 0.1            # ... and within which it has stopped "at the sample" (kernel's literals)


# --------------------------------------------------------------------------------------
# Small pieces shared by the operations
# --------------------------------------------------------------------------------------
def _K(J, i, M):
    """K of item i, (M, n)."""
    return J[i, 1:1 + M]


def _L(J, i, M):
    """L of item i, (M, M, n) (a view: writing it writes J)."""
    return J[i, 1 + M:].reshape((M, M) + J.shape[2:])


def _outer(a, b):
    """(M, n) and (M, n) -> (M, M, n): a_m b_n."""
    return a[:, None] * b[None, :]


def _bigger(a, b):
    """b where b > a, else a: Python's (and the kernel's) max(a, b), NaN b ignored."""
    return np.where(b > a, b, a)


def _invalid(J, items, where):
    """The outputs of an operation that did not place them at these samples: NaN."""
    if where.any():
        for it in items:
            J[it][:, where] = np.nan


class _Tally:
    """Per sample: det J (product of the groups'), measure (their least), gap (their
    largest) and the first operation that could not close (-1: none), as the kernel's
    ``_tally``; ``newton`` the status of the Newton groups."""

    def __init__(self, n):
        self.det = np.ones(n)
        self.measure = np.ones(n)
        self.gap = np.zeros(n)
        self.failed = np.full(n, -1, np.int64)
        self.newton = np.zeros(n, np.int8)

    def add(self, op, d, ms, gap=None):
        self.det *= d
        np.copyto(self.measure, ms, where=ms < self.measure)
        if gap is not None:
            np.copyto(self.gap, gap, where=gap > self.gap)
            self.failed[(gap > 0.0) & (self.failed < 0)] = op

    def status(self):
        st = self.newton.copy()
        st[(st == k.ST_OK) & (self.gap > 0.0)] = k.ST_NO_ASSEMBLY
        return st


def _direction(J, link, beta):
    phi = J[link, 0] + beta
    return np.cos(phi), np.sin(phi)


def _at(v, where):
    """A number of an operation at some samples: itself when it is one for all of them
    (one design), else its values there (designs evaluated together, one value a sample)."""
    return v[where] if np.ndim(v) else v


def _carried(J, p, a, link, rx, ry, M):
    """p = a + r, r (ground frame) fixed in a link: K_p = K_a + K_link k x r,
    L_p = L_a + L_link k x r - K_link K_link r (the kernel's ``_carried``)."""
    J[p, 0] = J[a, 0] + rx
    J[p + 1, 0] = J[a + 1, 0] + ry
    km = _K(J, link, M)
    np.subtract(_K(J, a, M), km * ry, out=_K(J, p, M))
    np.add(_K(J, a + 1, M), km * rx, out=_K(J, p + 1, M))
    kk = _outer(km, km)
    lmn = _L(J, link, M)
    _L(J, p, M)[...] = _L(J, a, M) - lmn * ry - kk * rx
    _L(J, p + 1, M)[...] = _L(J, a + 1, M) + lmn * rx - kk * ry


def _line_point(J, out, base, dirlink, beta, t, Kt, Lt, M):
    """out = base + t u, u at angle theta_dirlink + beta; t with its K (M, n), L (M, M, n)."""
    ux, uy = _direction(J, dirlink, beta)
    J[out, 0] = J[base, 0] + t * ux
    J[out + 1, 0] = J[base + 1, 0] + t * uy
    w = _K(J, dirlink, M)
    tw = t * w
    _K(J, out, M)[...] = _K(J, base, M) + Kt * ux - tw * uy
    _K(J, out + 1, M)[...] = _K(J, base + 1, M) + Kt * uy + tw * ux
    nn = Kt[:, None] * w[None, :] + Kt[None, :] * w[:, None] + t * _L(J, dirlink, M)
    uu = Lt - _outer(tw, w)
    _L(J, out, M)[...] = _L(J, base, M) + uu * ux - nn * uy
    _L(J, out + 1, M)[...] = _L(J, base + 1, M) + uu * uy + nn * ux


def _relative_slide(J, p, o, g, beta, M):
    """s = u . (p - o), u at angle theta_g + beta: (s, K (M, n), L (M, M, n))."""
    ux, uy = _direction(J, g, beta)
    nx, ny = -uy, ux
    dx = J[p, 0] - J[o, 0]
    dy = J[p + 1, 0] - J[o + 1, 0]
    ud = ux * dx + uy * dy
    nd = nx * dx + ny * dy
    dmx = _K(J, p, M) - _K(J, o, M)
    dmy = _K(J, p + 1, M) - _K(J, o + 1, M)
    w = _K(J, g, M)
    Ks = w * nd + ux * dmx + uy * dmy
    ndm = nx * dmx + ny * dmy
    ldx = _L(J, p, M) - _L(J, o, M)
    ldy = _L(J, p + 1, M) - _L(J, o + 1, M)
    Ls = (_L(J, g, M) * nd - _outer(w, w) * ud + w[:, None] * ndm[None, :]
          + w[None, :] * ndm[:, None] + ux * ldx + uy * ldy)
    return ud, Ks, Ls


# --------------------------------------------------------------------------------------
# The operations: op(J, k, ints, floats, q, M, tally), ints and floats its row of the plan
# --------------------------------------------------------------------------------------
def _op_drive_angle(J, op, ii, ff, q, M, tally):
    b, a, mi = ii[1], ii[2], ii[3]
    sgn = ff[0]
    if a >= 0:
        J[b, 0] = J[a, 0] + sgn * q[:, mi]
        J[b, 1:] = J[a, 1:]
    else:
        J[b, 0] = 0.0 + sgn * q[:, mi]
        J[b, 1:] = 0.0
    J[b, 1 + mi] += sgn


def _op_lock_angle(J, op, ii, ff, q, M, tally):
    b, a = ii[1], ii[2]
    J[b, 0] = J[a, 0] + ff[0]
    J[b, 1:] = J[a, 1:]


def _op_rigid_point(J, op, ii, ff, q, M, tally):
    p, link, a = ii[1], ii[2], ii[3]
    rx, ry = ff[0], ff[1]
    c = np.cos(J[link, 0])
    s = np.sin(J[link, 0])
    _carried(J, p, a, link, c * rx - s * ry, s * rx + c * ry, M)


def _op_frame_point(J, op, ii, ff, q, M, tally):
    p, a, b = ii[1], ii[2], ii[3]
    lam, mu = ff[0], ff[1]
    dx = J[b] - J[a]
    dy = J[b + 1] - J[a + 1]
    J[p] = J[a] + lam * dx - mu * dy
    J[p + 1] = J[a + 1] + lam * dy + mu * dx


def _op_slide_point(J, op, ii, ff, q, M, tally):
    out, base, dirlink, mi = ii[1], ii[2], ii[3], ii[4]
    beta, s0, sgn = ff[0], ff[1], ff[2]
    Kt = np.zeros((M, np.size(sgn)))
    Kt[mi] = sgn
    _line_point(J, out, base, dirlink, beta, sgn * (q[:, mi] - s0), Kt, np.zeros((M, M, 1)), M)


def _op_slide_out(J, op, ii, ff, q, M, tally):
    sl, p, o, g = ii[1], ii[2], ii[3], ii[4]
    v, Ks, Ls = _relative_slide(J, p, o, g, ff[0], M)
    J[sl, 0] = ff[1] + v
    _K(J, sl, M)[...] = Ks
    _L(J, sl, M)[...] = Ls


def _op_two_points(J, op, ii, ff, q, M, tally):
    b, p1, p2 = ii[1], ii[2], ii[3]
    dx = J[p2, 0] - J[p1, 0]
    dy = J[p2 + 1, 0] - J[p1 + 1, 0]
    d2 = dx * dx + dy * dy
    J[b, 0] = np.arctan2(dy, dx) + ff[0]
    kx = _K(J, p2, M) - _K(J, p1, M)
    ky = _K(J, p2 + 1, M) - _K(J, p1 + 1, M)
    _K(J, b, M)[...] = (dx * ky - dy * kx) / d2
    lx = _L(J, p2, M) - _L(J, p1, M)
    ly = _L(J, p2 + 1, M) - _L(J, p1 + 1, M)
    # [m, n]: km = K[m] (rows), kn = K[n] (columns)
    kmx, kmy, knx, kny = kx[:, None], ky[:, None], kx[None, :], ky[None, :]
    _L(J, b, M)[...] = ((knx * kmy - kny * kmx + dx * ly - dy * lx) / d2
                        - 2.0 * (dx * kmy - dy * kmx) * (dx * knx + dy * kny) / (d2 * d2))


def _op_gear(J, op, ii, ff, q, M, tally):
    out, x, y = ii[1], ii[2], ii[3]
    c0, cx, cy = ff[0], ff[1], ff[2]
    J[out, 0] = c0 + cx * J[x, 0] + cy * J[y, 0]
    J[out, 1:] = cx * J[x, 1:] + cy * J[y, 1:]


def _op_gear_slide(J, op, ii, ff, q, M, tally):
    out, base, dirlink, x, y = ii[1], ii[2], ii[3], ii[4], ii[5]
    beta, c0, cx, cy = ff[0], ff[1], ff[2], ff[3]
    t = c0 + cx * J[x, 0] + cy * J[y, 0]
    Kt = cx * _K(J, x, M) + cy * _K(J, y, M)
    Lt = cx * _L(J, x, M) + cy * _L(J, y, M)
    _line_point(J, out, base, dirlink, beta, t, Kt, Lt, M)


def _cam_motion(J, op, ii_cam, ii_guide, n, ops_f, M):
    """S(theta) of the program in the rows after operation ``op``, theta = theta_cam -
    theta_guide (the guide 0 when -1), with its K (M, n) and L (M, M, n) by the chain rule:
    K = S' K_theta, L = S'' K_theta K_theta + S' L_theta."""
    rows = np.asarray(ops_f[op + 1:op + 1 + k.CAM_ROWS * n], float)
    theta = J[ii_cam, 0] - (J[ii_guide, 0] if ii_guide >= 0 else 0.0)
    Kth = _K(J, ii_cam, M) - (_K(J, ii_guide, M) if ii_guide >= 0 else 0.0)
    Lth = _L(J, ii_cam, M) - (_L(J, ii_guide, M) if ii_guide >= 0 else 0.0)
    if rows.ndim == 2:
        S, S1, S2 = cam_values(rows.reshape(n, -1), theta)
    else:           # designs together (a sample axis last): each distinct program on its samples
        tables, which = np.unique(np.moveaxis(rows, -1, 0).reshape(rows.shape[-1], -1), axis=0,
                                  return_inverse=True)
        S, S1, S2 = (np.empty_like(theta) for _ in range(3))
        for t, table in enumerate(tables):
            at = which.ravel() == t
            S[at], S1[at], S2[at] = cam_values(table.reshape(n, -1), theta[at])
    return S, S1 * Kth, S2 * _outer(Kth, Kth) + S1 * Lth


def _op_cam(J, op, ii, ops_f, q, M, tally):
    out, cam, guide, n = ii[1], ii[2], ii[3], ii[4]
    S, Ks, Ls = _cam_motion(J, op, cam, guide, n, ops_f, M)
    J[out, 0] = ops_f[op][0] + S + (J[guide, 0] if guide >= 0 else 0.0)
    _K(J, out, M)[...] = Ks + (_K(J, guide, M) if guide >= 0 else 0.0)
    _L(J, out, M)[...] = Ls + (_L(J, guide, M) if guide >= 0 else 0.0)


def _op_cam_slide(J, op, ii, ops_f, q, M, tally):
    out, base, dirlink, cam, guide, n = ii[1], ii[2], ii[3], ii[4], ii[5], ii[6]
    beta, c0 = ops_f[op][0], ops_f[op][1]
    S, Ks, Ls = _cam_motion(J, op, cam, guide, n, ops_f, M)
    _line_point(J, out, base, dirlink, beta, c0 + S, Ks, Ls, M)


def _op_cam_data(J, op, ii, ff, q, M, tally):
    """The rows of a cam's program: read by its operation."""


_WHOLE = {k.OP_CAM: _op_cam, k.OP_CAM_SLIDE: _op_cam_slide}   # these read the rows after them


def rrr_closure(lb, lc, D2):
    """The closure of RRR dyads with arms ``lb``, ``lc`` whose end joints are ``sqrt(D2)``
    apart (arrays that broadcast), as the kernel's ``_rrr`` decides it: whether the ends
    coincide to rounding (``folded``: see :func:`arms_fold`), the middle joint's place along
    (``alpha``) and across (``beta2``, its square) the line of the ends in units of that
    distance, whether it is on that line to rounding (``low``), and whether the dyad fails to
    close (``fail``, beyond rounding; never where folded)."""
    folded = D2 <= k.FOLDED * lb * lb
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_D2 = 1.0 / D2
        alpha = 0.5 * (lb * lb - lc * lc + D2) * inv_D2
        beta2 = lb * lb * inv_D2 - alpha * alpha
    low = beta2 < k.DISC_ZERO * lb * lb * inv_D2
    fail = low & (beta2 < -k.DISC_TOL * lb * lb * inv_D2) & ~folded
    return folded, alpha, beta2, low, fail


def arms_fold(lb, lc):
    """Whether an RRR dyad whose end joints coincide closes: only with equal arms (to
    rounding), folded onto each other."""
    return np.abs(lb - lc) <= _FOLD_ARMS * lb


def _op_rrr(J, op, ii, ff, q, M, tally):
    """Circle-circle dyad (the kernel's ``_rrr`` and ``_rrr_folded``)."""
    b, c, X, Y, Z = ii[1], ii[2], ii[3], ii[4], ii[5]
    lb, lc, sigma, offb, offc = ff[0], ff[1], ff[2], ff[3], ff[4]
    dx = J[Z, 0] - J[X, 0]
    dy = J[Z + 1, 0] - J[X + 1, 0]
    D2 = dx * dx + dy * dy
    folded, alpha, beta2, low, fail = rrr_closure(lb, lc, D2)
    gap = np.zeros_like(D2)
    if fail.any():
        D = np.sqrt(D2[fail])
        gap[fail] = _bigger(D - _at(lb + lc, fail), _at(np.abs(lb - lc), fail) - D)
    beta2[low] = 0.0
    sb = sigma * np.sqrt(beta2)
    rbx = alpha * dx - sb * dy             # r_b = Y - X
    rby = alpha * dy + sb * dx
    rcx = rbx - dx                          # r_c = Y - Z
    rcy = rby - dy
    cr = sb * D2                            # cross(r_b, r_c)
    inv_cr = 1.0 / cr
    J[b, 0] = np.arctan2(rby, rbx) + offb
    J[c, 0] = np.arctan2(rcy, rcx) + offc
    wx = _K(J, Z, M) - _K(J, X, M)
    wy = _K(J, Z + 1, M) - _K(J, X + 1, M)
    Kb = _K(J, b, M)
    Kc = _K(J, c, M)
    np.multiply(wx * rcx + wy * rcy, inv_cr, out=Kb)
    np.multiply(wx * rbx + wy * rby, inv_cr, out=Kc)
    kb = _outer(Kb, Kb)
    kc = _outer(Kc, Kc)
    wx = _L(J, Z, M) - _L(J, X, M) + kb * rbx - kc * rcx
    wy = _L(J, Z + 1, M) - _L(J, X + 1, M) + kb * rby - kc * rcy
    np.multiply(wx * rcx + wy * rcy, inv_cr, out=_L(J, b, M))
    np.multiply(wx * rbx + wy * rby, inv_cr, out=_L(J, c, M))
    _carried(J, Y, X, b, rbx, rby, M)
    d = -cr
    ms = np.abs(cr) / (lb * lc)
    if folded.any():
        closes = arms_fold(lb, lc)
        stuck = folded & ~closes                # unequal arms cannot fold: no assembly
        if stuck.any():
            gap[stuck] = _at(np.abs(lb - lc), stuck) - np.sqrt(D2[stuck])
            fail |= stuck
        s = np.flatnonzero(folded & closes)
        if len(s):
            _rrr_folded(J, s, b, c, X, Y, Z, *(_at(v, s) for v in (lb, sigma, offb, offc)))
    special = folded | fail
    d[special] = 0.0
    ms[special] = 0.0
    _invalid(J, (b, c, Y, Y + 1), fail)
    tally.add(op, d, ms, gap)


def _rrr_folded(J, s, b, c, X, Y, Z, lb, sigma, offb, offc):
    """Samples s of an RRR dyad whose end joints coincide: Y where the motion takes it,
    K and L NaN (the kernel's ``_rrr_folded``)."""
    ex = J[Z, 1, s] - J[X, 1, s]
    ey = J[Z + 1, 1, s] - J[X + 1, 1, s]
    n = np.hypot(ex, ey)
    moving = n > 0.0
    rbx = np.where(moving, -sigma * lb * ey / n, np.nan)
    rby = np.where(moving, sigma * lb * ex / n, np.nan)
    a = np.arctan2(rby, rbx)
    J[b, 0, s] = a + offb
    J[c, 0, s] = a + offc
    J[Y, 0, s] = J[X, 0, s] + rbx
    J[Y + 1, 0, s] = J[X + 1, 0, s] + rby
    for it in (b, c, Y, Y + 1):
        J[it, 1:, s] = np.nan


def _op_rrp(J, op, ii, ff, q, M, tally):
    """Circle-line dyad (the kernel's ``_rrp``)."""
    b, X, Y, o, g = ii[1], ii[2], ii[3], ii[4], ii[5]
    lb, beta, sigma, offb = ff[0], ff[1], ff[2], ff[3]
    ux, uy = _direction(J, g, beta)
    nx, ny = -uy, ux
    w0x = J[o, 0] - J[X, 0]
    w0y = J[o + 1, 0] - J[X + 1, 0]
    uw = ux * w0x + uy * w0y
    hh = nx * w0x + ny * w0y            # signed distance of X from the line
    t2 = lb * lb - hh * hh
    low = t2 < k.DISC_ZERO * lb * lb
    fail = low & (t2 < -k.DISC_TOL * lb * lb)
    gap = np.where(fail, np.abs(hh) - lb, 0.0)
    t2[low] = 0.0
    t = sigma * np.sqrt(t2)
    s = t - uw                          # slide along the line from o
    rx = hh * nx + t * ux               # r = Y - X
    ry = hh * ny + t * uy
    J[b, 0] = np.arctan2(ry, rx) + offb
    kru = -ry * ux + rx * uy            # (k x r) . u
    wg = _K(J, g, M)
    swg = s * wg
    w1x = _K(J, o, M) + swg * nx - _K(J, X, M)
    w1y = _K(J, o + 1, M) + swg * ny - _K(J, X + 1, M)
    Kb = _K(J, b, M)
    np.divide(w1x * nx + w1y * ny, t, out=Kb)
    Ks = Kb * kru - (w1x * ux + w1y * uy)
    kb = _outer(Kb, Kb)
    kg = _outer(wg, wg)
    cor = Ks[:, None] * wg[None, :] + Ks[None, :] * wg[:, None]
    lg = _L(J, g, M)
    w2x = _L(J, o, M) + cor * nx + s * (lg * nx - kg * ux) - _L(J, X, M) + kb * rx
    w2y = _L(J, o + 1, M) + cor * ny + s * (lg * ny - kg * uy) - _L(J, X + 1, M) + kb * ry
    np.divide(w2x * nx + w2y * ny, t, out=_L(J, b, M))
    _carried(J, Y, X, b, rx, ry, M)
    d = t.copy()
    ms = np.abs(t) / lb
    d[fail] = 0.0
    ms[fail] = 0.0
    _invalid(J, (b, Y, Y + 1), fail)
    tally.add(op, d, ms, gap)


def _op_rpr(J, op, ii, ff, q, M, tally):
    """Turning-line dyad (the kernel's ``_rpr`` and ``_rpr_through_pivot``)."""
    G, X, Z = ii[1], ii[2], ii[3]
    rho_x, rho_y, u_x, u_y, sigma = ff[0], ff[1], ff[2], ff[3], ff[4]
    wx = J[X, 0] - J[Z, 0]
    wy = J[X + 1, 0] - J[Z + 1, 0]
    D2 = wx * wx + wy * wy
    h = u_x * rho_y - u_y * rho_x           # distance of Z from the line, in G's frame
    rho2 = rho_x * rho_x + rho_y * rho_y
    hh = h * h
    through = (D2 <= k.FOLDED * rho2) & (hh <= k.FOLDED * rho2)
    t2 = D2 - hh
    big = _bigger(D2, hh)
    low = t2 < k.DISC_ZERO * big
    fail = low & (t2 < -k.DISC_TOL * big) & ~through
    gap = np.zeros_like(D2)
    if fail.any():
        gap[fail] = np.abs(_at(h, fail)) - np.sqrt(D2[fail])
    t2[low] = 0.0
    t = sigma * np.sqrt(t2)
    lx = -h * u_y + t * u_x
    ly = h * u_x + t * u_y
    th = np.arctan2(wy, wx) - np.arctan2(ly, lx)
    J[G, 0] = th
    c = np.cos(th)
    sn = np.sin(th)
    ux = c * u_x - sn * u_y
    uy = sn * u_x + c * u_y
    nx, ny = -uy, ux
    kwu = wx * uy - wy * ux                 # (k x w) . u
    dx = _K(J, X, M) - _K(J, Z, M)
    dy = _K(J, X + 1, M) - _K(J, Z + 1, M)
    om = _K(J, G, M)
    np.divide(dx * nx + dy * ny, t, out=om)
    Ks = dx * ux + dy * uy - om * kwu
    kk = _outer(om, om)
    cor = Ks[:, None] * om[None, :] + Ks[None, :] * om[:, None]
    r2x = _L(J, X, M) - _L(J, Z, M) + kk * wx - cor * nx
    r2y = _L(J, X + 1, M) - _L(J, Z + 1, M) + kk * wy - cor * ny
    np.divide(r2x * nx + r2y * ny, t, out=_L(J, G, M))
    d = -t
    ms = np.abs(t) / np.sqrt(rho2)
    if through.any():
        s = np.flatnonzero(through)
        ex = J[X, 1, s] - J[Z, 1, s]
        ey = J[X + 1, 1, s] - J[Z + 1, 1, s]
        sg = _at(sigma, s)
        th = np.arctan2(sg * ey, sg * ex) - np.arctan2(_at(u_y, s), _at(u_x, s))
        J[G, 0, s] = np.where((ex != 0.0) | (ey != 0.0), th, np.nan)
        J[G, 1:, s] = np.nan
    special = through | fail
    d[special] = 0.0
    ms[special] = 0.0
    _invalid(J, (G,), fail)
    tally.add(op, d, ms, gap)


def _op_lines(J, op, ii, ff, q, M, tally):
    """Intersection of two lines o_i + t_i u_i (the kernel's ``_lines``)."""
    out, o1, l1, o2, l2 = ii[1], ii[2], ii[3], ii[4], ii[5]
    beta1, beta2 = ff[0], ff[1]
    u1x, u1y = _direction(J, l1, beta1)
    u2x, u2y = _direction(J, l2, beta2)
    cr = u1x * u2y - u1y * u2x
    wx = J[o2, 0] - J[o1, 0]
    wy = J[o2 + 1, 0] - J[o1 + 1, 0]
    t1 = (wx * u2y - wy * u2x) / cr
    t2 = (wx * u1y - wy * u1x) / cr
    a1 = _K(J, l1, M)
    a2 = _K(J, l2, M)
    t1a1 = t1 * a1
    t2a2 = t2 * a2
    vx = _K(J, o2, M) - t2a2 * u2y - _K(J, o1, M) + t1a1 * u1y
    vy = _K(J, o2 + 1, M) + t2a2 * u2x - _K(J, o1 + 1, M) - t1a1 * u1x
    K1 = (vx * u2y - vy * u2x) / cr
    K2 = (vx * u1y - vy * u1x) / cr
    c1 = K1[:, None] * a1[None, :] + K1[None, :] * a1[:, None] + t1 * _L(J, l1, M)
    cc2 = K2[:, None] * a2[None, :] + K2[None, :] * a2[:, None] + t2 * _L(J, l2, M)
    q1 = _outer(t1a1, a1)
    q2 = _outer(t2a2, a2)
    ax = (_L(J, o2, M) - cc2 * u2y - q2 * u2x) - (_L(J, o1, M) - c1 * u1y - q1 * u1x)
    ay = (_L(J, o2 + 1, M) + cc2 * u2x - q2 * u2y) - (_L(J, o1 + 1, M) + c1 * u1x - q1 * u1y)
    L1 = (ax * u2y - ay * u2x) / cr
    _line_point(J, out, o1, l1, beta1, t1, K1, L1, M)
    parallel = cr == 0.0
    d = -cr
    _invalid(J, (out, out + 1), parallel)
    tally.add(op, d, np.abs(cr))


_OPS = {k.OP_DRIVE_ANGLE: _op_drive_angle, k.OP_LOCK_ANGLE: _op_lock_angle,
        k.OP_RIGID_POINT: _op_rigid_point, k.OP_FRAME_POINT: _op_frame_point,
        k.OP_SLIDE_POINT: _op_slide_point, k.OP_SLIDE_OUT: _op_slide_out,
        k.OP_TWO_POINTS: _op_two_points, k.OP_RRR: _op_rrr, k.OP_RRP: _op_rrp,
        k.OP_RPR: _op_rpr, k.OP_LINES: _op_lines, k.OP_GEAR: _op_gear,
        k.OP_GEAR_SLIDE: _op_gear_slide, k.OP_CAM_DATA: _op_cam_data}


# --------------------------------------------------------------------------------------
# Newton groups.  Every equation of a group is one of two kinds:
#   angle rows   theta_b - theta_a - (Q q + offset) = 0       (driven angles, prismatic joints)
#   point rows   c . (p_a - p_b) - (Q q - s0) = 0             (revolute joints, in x and in y;
#                the normal of a prismatic joint; a driven slide), with c fixed or turning
#                with a guide: c = n or u, dc/dtheta = c' (= -u or n), d2c/dtheta2 = -c.
# Each kind is evaluated on all its rows at once; the kernel's _group_residual and
# _group_rhs are these equations written row by row.
# --------------------------------------------------------------------------------------
_FIXED, _NORMAL, _ALONG = 0, 1, 2


class _Group:
    """One Newton group of a plan, as index arrays (built once per plan)."""

    def __init__(self, g, groups_i, con_i, con_f, M):
        o, nlk, c0, c1 = (int(v) for v in groups_i[g, :4])
        self.g, self.o, self.nlk, self.n = g, o, nlk, 3 * nlk
        self.links = groups_i[g, 4:4 + nlk].copy()
        self.anchors = groups_i[g, 4 + nlk:4 + 2 * nlk].copy()
        sides, arows, prows = [], [], []
        angles = [(-1, -1)]     # the ground's angle (0): the guide of rows that have none

        def side(gi, p, rx, ry):
            sides.append((int(gi), int(p), float(rx), float(ry)))
            return len(sides) - 1

        def angle(gi, link):
            angles.append((int(gi), int(link)))
            return len(angles) - 1

        row = 0
        for c in range(c0, c1):
            ci, cf = con_i[c], con_f[c]
            kind = int(ci[0])
            if kind == k.C_REVOLUTE:
                a, b = side(ci[1], ci[2], cf[0], cf[1]), side(ci[4], ci[5], cf[2], cf[3])
                prows += [(row, a, b, _FIXED, 1.0, 0.0, 0, 0.0, -1, 0.0),
                          (row + 1, a, b, _FIXED, 0.0, 1.0, 0, 0.0, -1, 0.0)]
                row += 2
            elif kind == k.C_DRIVE_ANGLE:
                arows.append((row, angle(ci[1], ci[3]), angle(ci[4], ci[6]), float(cf[0]),
                              int(ci[7]), 0.0))
                row += 1
            else:
                og, sl = side(ci[1], ci[2], cf[0], cf[1]), side(ci[4], ci[5], cf[2], cf[3])
                guide = angle(ci[1], ci[3])
                if kind == k.C_PRISMATIC:
                    arows.append((row, guide, angle(ci[4], ci[6]), 0.0, -1, float(cf[5])))
                    prows.append((row + 1, sl, og, _NORMAL, 0.0, 0.0, guide, float(cf[4]), -1, 0.0))
                    row += 2
                else:
                    prows.append((row, sl, og, _ALONG, 0.0, 0.0, guide, float(cf[4]), int(ci[7]),
                                  float(cf[5])))
                    row += 1
        n = self.n
        self.rows = row         # n for a group solved by Newton; any number for a sketch's rank
        sg = np.array([v[0] for v in sides], np.int64)
        sp = np.array([v[1] for v in sides], np.int64)
        self.srx = np.array([v[2] for v in sides])
        self.sry = np.array([v[3] for v in sides])
        self.s_grp = sg >= 0
        self.s_g = np.where(self.s_grp, sg, 0)
        self.s_p = np.where(self.s_grp, 0, sp)
        ag = np.array([v[0] for v in angles], np.int64)
        al = np.array([v[1] for v in angles], np.int64)
        self.a_grp = ag >= 0
        self.a_g = np.where(self.a_grp, ag, 0)
        self.a_known = ~self.a_grp & (al >= 0)        # a known link (not the ground)
        self.a_l = np.where(self.a_known, al, 0)
        # angle rows
        self.ar = np.array([r[0] for r in arows], np.int64)
        self.aa = np.array([r[1] for r in arows], np.int64)
        self.ab = np.array([r[2] for r in arows], np.int64)
        self.aQ = np.zeros((len(arows), M))
        for i, r in enumerate(arows):
            if r[4] >= 0:
                self.aQ[i, r[4]] = r[3]
        self.a_off = np.array([r[5] for r in arows])
        A0 = np.zeros((row, n))
        for r, a, b, *_ in arows:
            if ag[b] >= 0:
                A0[r, 3 * ag[b] + 2] += 1.0
            if ag[a] >= 0:
                A0[r, 3 * ag[a] + 2] -= 1.0
        self.A0 = A0
        # point rows
        pr = np.array([r[0] for r in prows], np.int64)
        self.pr = pr
        self.pa = np.array([r[1] for r in prows], np.int64)
        self.pb = np.array([r[2] for r in prows], np.int64)
        kinds = np.array([r[3] for r in prows], np.int64)
        self.fixed = kinds == _FIXED
        self.normal = kinds == _NORMAL
        self.guided = ~self.fixed
        self.fx = np.array([r[4] for r in prows])
        self.fy = np.array([r[5] for r in prows])
        self.pg = np.array([r[6] for r in prows], np.int64)
        self.pbeta = np.array([r[7] for r in prows])
        self.pQ = np.zeros((len(prows), M))
        for i, r in enumerate(prows):
            if r[8] >= 0:
                self.pQ[i, r[8]] = 1.0
        self.p_s0 = np.array([r[9] for r in prows])
        # where the Jacobian's entries of point rows go (bincount adds them in this order:
        # the guide's term first, then the slider's side, then the guide's side, as the kernel)
        g_guide = np.where(self.guided, ag[self.pg], -1)
        self.j_guide = self.guided & (g_guide >= 0)
        self.j_a = self.s_grp[self.pa]
        self.j_b = self.s_grp[self.pb]
        ga, gb = self.s_g[self.pa], self.s_g[self.pb]
        self.j_idx = np.concatenate([
            pr[self.j_guide] * n + 3 * g_guide[self.j_guide] + 2,
            pr[self.j_a] * n + 3 * ga[self.j_a], pr[self.j_a] * n + 3 * ga[self.j_a] + 1,
            pr[self.j_a] * n + 3 * ga[self.j_a] + 2,
            pr[self.j_b] * n + 3 * gb[self.j_b], pr[self.j_b] * n + 3 * gb[self.j_b] + 1,
            pr[self.j_b] * n + 3 * gb[self.j_b] + 2])
        self.upper = np.triu_indices(M)


class _Known:
    """What a group's equations read from the known items at one sample (fixed during a
    solve): positions, rates and second derivatives of the known sides and angles."""

    def __init__(self, G, jc, M):
        p = G.s_p
        known = ~G.s_grp
        self.px = jc[p, 0]
        self.py = jc[p + 1, 0]
        self.vel = np.where(known[:, None, None], np.stack([jc[p, 1:1 + M], jc[p + 1, 1:1 + M]], 1), 0.0)
        self.acc = np.stack([jc[p, 1 + M:], jc[p + 1, 1 + M:]], 1).reshape(len(p), 2, M, M)
        link = G.a_l
        self.angle = np.where(G.a_known, jc[link, 0], 0.0)
        self.rate = np.where(G.a_known[:, None], jc[link, 1:1 + M], 0.0)
        self.second = np.where(G.a_known[:, None, None],
                               jc[link, 1 + M:].reshape(len(link), M, M), 0.0)


def _frame(G, x, kn):
    """The rotated arms r of the group's sides (vx, vy), the sides' positions, the angles,
    and the point rows' directions c, c' and d = p_a - p_b, at the group's unknowns x."""
    th = x[2::3]
    cth, sth = np.cos(th), np.sin(th)
    cg, sg = cth[G.s_g], sth[G.s_g]
    vx = cg * G.srx - sg * G.sry
    vy = sg * G.srx + cg * G.sry
    px = np.where(G.s_grp, x[3 * G.s_g] + vx, kn.px)
    py = np.where(G.s_grp, x[3 * G.s_g + 1] + vy, kn.py)
    ang = np.where(G.a_grp, x[3 * G.a_g + 2], kn.angle)
    phi = ang[G.pg] + G.pbeta
    ux, uy = np.cos(phi), np.sin(phi)
    cx = np.where(G.fixed, G.fx, np.where(G.normal, -uy, ux))
    cy = np.where(G.fixed, G.fy, np.where(G.normal, ux, uy))
    cpx = np.where(G.fixed, 0.0, np.where(G.normal, -ux, -uy))
    cpy = np.where(G.fixed, 0.0, np.where(G.normal, -uy, ux))
    dx = px[G.pa] - px[G.pb]
    dy = py[G.pa] - py[G.pb]
    return vx, vy, ang, cx, cy, cpx, cpy, dx, dy


def _residual(G, x, kn, qa, qp):
    """Residuals and Jacobian of a group (the kernel's ``_group_residual``)."""
    vx, vy, ang, cx, cy, cpx, cpy, dx, dy = _frame(G, x, kn)
    phi = np.empty(G.rows)
    phi[G.ar] = ang[G.ab] - ang[G.aa] - qa
    phi[G.pr] = cx * dx + cy * dy - qp
    va, vb = G.pa, G.pb
    ja, jb = G.j_a, G.j_b
    vals = np.concatenate([
        (cpx * dx + cpy * dy)[G.j_guide],
        cx[ja], cy[ja], (-cx * vy[va] + cy * vx[va])[ja],
        -cx[jb], -cy[jb], (cx * vy[vb] - cy * vx[vb])[jb]])
    A = G.A0 + np.bincount(G.j_idx, vals, G.rows * G.n).reshape(G.rows, G.n)
    return phi, A


def _rates(G, x, kn, A, q, M):
    """K (n, M) and L (n, M, M) of a group at its solution x, solved with the Jacobian A of
    the last Newton step (the kernel's ``_group_rhs`` and its solves)."""
    vx, vy, ang, cx, cy, cpx, cpy, dx, dy = _frame(G, x, kn)
    n = G.n
    guided = G.guided[:, None]
    # K: the known sides' rates only (the group's own are J K)
    rhs = np.empty((n, M))
    rhs[G.ar] = -(kn.rate[G.ab] - kn.rate[G.aa] - G.aQ)
    dd = kn.vel[G.pa] - kn.vel[G.pb]
    cpd = cpx * dx + cpy * dy
    v = np.where(guided, kn.rate[G.pg] * cpd[:, None], 0.0) + cx[:, None] * dd[:, 0] + cy[:, None] * dd[:, 1]
    rhs[G.pr] = -(v - G.pQ)
    Kw = np.linalg.solve(A, rhs)
    # L: the centripetal and Coriolis terms with the group's K
    w = Kw[3 * G.s_g + 2]                                   # (ns, M): the sides' links' rates
    grp = G.s_grp[:, None]
    vel = np.stack([np.where(grp, Kw[3 * G.s_g] - w * vy[:, None], 0.0),
                    np.where(grp, Kw[3 * G.s_g + 1] + w * vx[:, None], 0.0)], 1) + kn.vel
    ww = w[:, :, None] * w[:, None, :]
    acc = np.where(G.s_grp[:, None, None, None],
                   np.stack([-ww * vx[:, None, None], -ww * vy[:, None, None]], 1), kn.acc)
    rate = np.where(G.a_grp[:, None], Kw[3 * G.a_g + 2], kn.rate)
    wm = np.where(guided, rate[G.pg], 0.0)                  # (rows, M)
    ag = np.where(guided[:, :, None], kn.second[G.pg], 0.0)
    dm = vel[G.pa] - vel[G.pb]                              # (rows, 2, M)
    ad = acc[G.pa] - acc[G.pb]                              # (rows, 2, M, M)
    cdm = cpx[:, None] * dm[:, 0] + cpy[:, None] * dm[:, 1]
    cppd = -(cx * dx + cy * dy)
    e = (ag * cpd[:, None, None] + wm[:, :, None] * wm[:, None, :] * cppd[:, None, None]
         + wm[:, :, None] * cdm[:, None, :] + wm[:, None, :] * cdm[:, :, None]
         + cx[:, None, None] * ad[:, 0] + cy[:, None, None] * ad[:, 1])
    rhs2 = np.empty((n, M, M))
    rhs2[G.ar] = -(kn.second[G.ab] - kn.second[G.aa])
    rhs2[G.pr] = -e
    m, j = G.upper
    Lu = np.linalg.solve(A, rhs2[:, m, j])
    Lw = np.empty((n, M, M))
    Lw[:, m, j] = Lu
    Lw[:, j, m] = Lu
    return Kw, Lw


class _State:
    """The Newton groups' state along a continuation: their unknowns x with K and L, the
    input where they were solved and their det (the kernel's gx, gK, gL, gq, gdet), and the
    state before it (x1, K1, L1, q1; q1 NaN where there is none), for the predictor."""

    def __init__(self, x0, ng, M):
        self.x = np.array(x0, float)
        self.K = np.zeros((len(x0), M))
        self.L = np.zeros((len(x0), M, M))
        self.q = np.zeros((ng, M))
        self.det = np.zeros(ng)
        self.x1, self.K1, self.L1 = self.x.copy(), self.K.copy(), self.L.copy()
        self.q1 = np.full((ng, M), np.nan)

    def copy(self):
        other = object.__new__(_State)
        other.set(self)
        return other

    def set(self, other):
        self.x, self.K, self.L = other.x.copy(), other.K.copy(), other.L.copy()
        self.q, self.det = other.q.copy(), other.det.copy()
        self.x1, self.K1, self.L1 = other.x1.copy(), other.K1.copy(), other.L1.copy()
        self.q1 = other.q1.copy()

    def store(self, G, x, K, L, q, det):
        """Group G solved at q: its last state becomes the one before."""
        o, n = G.o, G.n
        for last, before, new in ((self.x, self.x1, x), (self.K, self.K1, K), (self.L, self.L1, L)):
            before[o:o + n] = last[o:o + n]
            last[o:o + n] = new
        self.q1[G.g] = self.q[G.g]
        self.q[G.g] = q
        self.det[G.g] = det

    def hermite_terms(self, G, q, M):
        """What the quintic through group G's last two states adds to the second-order
        predictor at q (the kernel's ``_hermite_reach`` and ``_hermite_terms``), or None."""
        if M != 1:
            return None
        h = float(self.q[G.g, 0] - self.q1[G.g, 0])
        if not (h != 0.0 and math.isfinite(h)):
            return None
        u = float(q[0] - self.q[G.g, 0]) / h
        if abs(u) > k.HERMITE_REACH:
            return None
        o, n = G.o, G.n
        x0, k0, l0 = self.x[o:o + n], self.K[o:o + n, 0], self.L[o:o + n, 0, 0]
        a = self.x1[o:o + n] - (x0 - k0 * h + 0.5 * l0 * h * h)
        b = (self.K1[o:o + n, 0] - (k0 - l0 * h)) * h
        c = (self.L1[o:o + n, 0, 0] - l0) * h * h
        a5 = -0.5 * c - 3.0 * b - 6.0 * a
        a4 = -c - 7.0 * b - 15.0 * a
        a3 = -0.5 * c - 4.0 * b - 10.0 * a
        return u * u * u * (a3 + u * (a4 + u * a5))


def _newton_group(G, state, q, jc, M, scale):
    """Solve group G at input q (M,) from its state by Newton-Raphson and write its links'
    poses, K and L to jc (n_items, C); returns (status, det, measure).  The state changes
    only on success, and not where the group is too near a singular configuration to
    predict from (the kernel's ``_newton_group``).  Steps are measured in the unknowns' own
    units (anchors in sizes of the mechanism, angles in rad: see ``_codes``)."""
    o, n = G.o, G.n
    sx, sK, sL = state.x[o:o + n], state.K[o:o + n], state.L[o:o + n]
    dq = q - state.q[G.g]
    xp = sx.copy()
    for m in range(M):                      # second-order predictor S + K dq + 1/2 dq L dq
        xp = xp + sK[:, m] * dq[m]
        for j in range(M):
            xp = xp + 0.5 * sL[:, m, j] * dq[m] * dq[j]
    quintic = state.hermite_terms(G, q, M)  # ... and the quintic through the last two states
    if quintic is not None:
        xp = xp + quintic
    unit = np.where(np.arange(n) % 3 == 2, 1.0, scale)     # of each unknown
    step = math.sqrt(float(np.sum(((xp - sx) / unit) ** 2)))
    kn = _Known(G, jc, M)
    qa = G.aQ @ q + G.a_off
    qp = G.pQ @ q - G.p_s0
    x = xp.copy()
    converged = False
    det = 0.0
    A = None
    last = math.inf
    for _ in range(k.NEWTON_MAX_ITER):
        phi, A = _residual(G, x, kn, qa, qp)
        det = float(np.linalg.det(A))
        try:
            dx = np.linalg.solve(A, -phi)
        except np.linalg.LinAlgError:       # an exactly singular Jacobian: no step
            break
        x = x + dx
        dn = math.sqrt(float(np.sum((dx / unit) ** 2)))
        if not math.isfinite(dn):
            break
        if dn <= k.NEWTON_TOL or (dn <= k.NEWTON_STALL and dn > 0.5 * last):
            converged = True
            break
        last = dn
    if not converged:
        return k.ST_NO_CONVERGENCE, 0.0, 0.0
    if math.sqrt(float(np.sum(((x - xp) / unit) ** 2))) > k.JUMP_RATIO * step + k.JUMP_FLOOR:
        return k.ST_NO_CONVERGENCE, 0.0, 0.0
    Kw, Lw = _rates(G, x, kn, A, q, M)
    measure = _smallest_singular_value(G, A, scale)
    if measure >= k.BASE_MIN:
        state.store(G, x, Kw, Lw, q, det)
    a, links = G.anchors, G.links
    jc[a, 0], jc[a + 1, 0], jc[links, 0] = x[0::3], x[1::3], x[2::3]
    jc[a, 1:1 + M], jc[a + 1, 1:1 + M], jc[links, 1:1 + M] = Kw[0::3], Kw[1::3], Kw[2::3]
    flat = Lw.reshape(n, M * M)
    jc[a, 1 + M:], jc[a + 1, 1 + M:], jc[links, 1 + M:] = flat[0::3], flat[1::3], flat[2::3]
    return k.ST_OK, det, measure


def _smallest_singular_value(G, A: np.ndarray, scale: float) -> float:
    """The singularity measure of a Newton group: the kernel's ``_smallest_singular_value``
    (A made dimensionless, equilibrated, then inverse iteration with its LU factors, step for
    step; see the kernel's ``_norms``)."""
    from scipy.linalg import lu_factor, lu_solve

    n = len(A)
    ru = np.full(n, 1.0 / scale)
    ru[G.ar] = 1.0                                   # angle equations, in rad
    cu = np.where(np.arange(n) % 3 == 2, 1.0, scale)  # anchors in sizes, angles in rad
    c = np.sqrt(np.einsum("ij,ij->j", ru[:, None] * A * cu, ru[:, None] * A * cu))
    cn = np.where(c > 0.0, c / cu, 0.0)
    if not np.all(cn > 0.0):
        return 0.0
    rn = np.sqrt(np.einsum("ij,ij->i", A / cn, A / cn))
    if not np.all(rn > 0.0):
        return 0.0
    factors = lu_factor(A, check_finite=False)
    if np.any(np.diag(factors[0]) == 0.0):
        return 0.0
    v = 1.0 + np.arange(n) / n
    v = v / math.sqrt(float(v @ v))
    sigma = 0.0
    for step in range(k.SINGULAR_STEPS):
        w = lu_solve(factors, v * cn, trans=1, check_finite=False) * rn
        size = math.sqrt(float(w @ w))
        if not math.isfinite(size) or size == 0.0:
            return 0.0
        sigma = 1.0 / size
        if step == k.SINGULAR_STEPS - 1:    # (the next v would serve no further step)
            break
        v = lu_solve(factors, w * rn, check_finite=False) * cn
        size = math.sqrt(float(v @ v))
        if not math.isfinite(size) or size == 0.0:
            return 0.0
        v = v / size
    return min(sigma, 1.0)


# --------------------------------------------------------------------------------------
# Running a plan
# --------------------------------------------------------------------------------------
class _Tables:
    """A plan arranged for this module, kept on the plan: each operation's function and
    integer fields, and the Newton groups' index arrays."""

    def __init__(self, p: Plan, M: int, con_f=None):
        self.ops = [(_OPS.get(int(row[0])), op, tuple(int(v) for v in row))
                    for op, row in enumerate(p.ops_i)]
        self.groups = []
        if p.groups is not None:
            groups_i, con_i, plan_f, _ = p.groups
            con_f = plan_f if con_f is None else con_f
            self.groups = [_Group(g, groups_i, con_i, con_f, M) for g in range(len(groups_i))]


def _tables(p: Plan, M: int) -> _Tables:
    key = ("interpreter", M)
    t = p._columns.get(key)
    if t is None:
        t = p._columns[key] = _Tables(p, M)
    return t


def _new_jet(p: Plan, C: int, n: int, const_values: np.ndarray) -> np.ndarray:
    """Jets of n samples with the plan's constants: (n_const,) for all, or (n_const, n)."""
    J = np.zeros((p.n_items, C, n))
    J[p.const_items, 0] = const_values if const_values.ndim == 2 else const_values[:, None]
    return J


def _evaluate(T, J, q, ops_f, M, state=None, scale=1.0):
    """Run every operation of the plan on the samples of J at the inputs q (n, M);
    Newton groups (one sample: n = 1) solve from ``state``.  Returns the tally."""
    tally = _Tally(J.shape[2])
    for fn, op, ii in T.ops:
        if ii[0] in _WHOLE:
            _WHOLE[ii[0]](J, op, ii, ops_f, q, M, tally)
            continue
        if fn is not None:
            fn(J, op, ii, ops_f[op], q, M, tally)
            continue
        # a Newton group: where it does not converge it leaves the jet as it was (its
        # anchors may be points placed before it), as the kernel does
        if tally.failed[0] < 0:         # no group of this sample failed so far
            st, d, ms = _newton_group(T.groups[ii[1]], state, q[0], J[:, :, 0], M, scale)
            tally.add(op, d, ms)
            if st != k.ST_OK:
                tally.newton[0] = st
                tally.failed[0] = op
    return tally


def _write(S, lo, hi, qd, qdd, M, angle_rows, out):
    """Samples lo:hi of the outputs from S (n_stored, C, hi - lo), the stored items' jets:
    angles wrapped to (-pi, pi]; rates S' = K q', S'' = K q'' + q'^T L q' (the kernel's
    ``_write_sample``)."""
    if not len(S):
        return
    t = S[angle_rows, 0]
    bad = ~((-math.pi < t) & (t <= math.pi))
    if bad.any():
        tb = t[bad]
        t[bad] = tb - 2.0 * math.pi * np.ceil((tb - math.pi) / (2.0 * math.pi))
        S[angle_rows, 0] = t
    out["jets"][lo:hi] = S.transpose(2, 0, 1)
    qd = qd[lo:hi] if len(qd) > 1 else qd[:1]
    qdd = qdd[lo:hi] if len(qdd) > 1 else qdd[:1]
    rates = out["rates"][lo:hi]
    if M == 1:
        w, wd = qd[:, 0], qdd[:, 0]
        K, L = S[:, 1], S[:, 2]
        rates[:, :, 0] = (K * w).T
        rates[:, :, 1] = (K * wd + L * (w * w)).T
        return
    v = 0.0
    a = 0.0
    for m in range(M):
        km = S[:, 1 + m]
        v = v + km * qd[:, m]
        a = a + km * qdd[:, m]
        for j in range(M):
            a = a + S[:, 1 + M + m * M + j] * qd[:, m] * qd[:, j]
    rates[:, :, 0] = v.T
    rates[:, :, 1] = a.T


def _closed_form(p, T, q, qd, qdd, nums, stored, out, M):
    """A plan without Newton groups: all samples of all designs at once, a chunk at a time.
    With one design its numbers are numbers; with several, each number of an operation is
    an array of the chunk's samples, each with its design's value."""
    C = 1 + M + M * M
    angle_rows = np.flatnonzero(stored < p.n_angles)
    if nums.D == 1:
        ff, const_values = nums.ops_f[0].tolist(), nums.const_values[0]
    per = len(q) // nums.D
    for lo in range(0, len(q), _CHUNK):
        hi = min(len(q), lo + _CHUNK)
        if nums.D > 1:
            design = np.arange(lo, hi) // per
            ff = np.moveaxis(nums.ops_f[design], 0, -1)      # (operations, numbers, samples)
            const_values = nums.const_values[design].T
        J = _new_jet(p, C, hi - lo, const_values)
        tally = _evaluate(T, J, q[lo:hi], ff, M)
        status = tally.status()
        failed = status != k.ST_OK
        tally.det[failed] = 0.0         # as the kernel: the failed group's det and measure
        tally.measure[failed] = 0.0
        out["status"][lo:hi] = status
        out["diag"][lo:hi, 0] = tally.det
        out["diag"][lo:hi, 1] = tally.measure
        out["fail"][lo:hi, 0] = tally.gap
        out["fail"][lo:hi, 1] = tally.failed
        _write(J[stored], lo, hi, qd, qdd, M, angle_rows, out)


def _continuation(p, T, q, qd, qdd, q_start, q_unit, ops_f, const_values, scale, stored, x0,
                  out, M):
    """A plan with Newton groups, following the samples in order from a start (the
    kernel's ``_continuation``, step for step).  Returns (q, x) where the run ended."""
    N = len(q)
    ff = ops_f.tolist()
    C = 1 + M + M * M
    J = _new_jet(p, C, 1, const_values)
    state = _State(x0, len(T.groups), M)
    state.q[:] = q_start

    def evaluate(qt):
        tally = _evaluate(T, J, qt.reshape(1, M), ff, M, state, scale)
        res = (float(tally.det[0]), float(tally.measure[0]), float(tally.gap[0]),
               float(tally.failed[0]))
        return int(tally.status()[0]), res

    st0, res = evaluate(q_start)            # the sketch: the groups converge at once
    if st0 != k.ST_OK:
        out["status"][:] = st0
        out["diag"][:] = res[:2]
        out["fail"][:] = res[2:]
        return q_start.copy(), np.array(x0, float)
    S = np.zeros((len(stored), C, N))       # the stored jets of the samples, written at the end
    angle_rows = np.flatnonzero(stored < p.n_angles)
    qprev = q_start.copy()
    clear = state.copy()                    # the state on the sample's path, well clear of it
    max_step = k.CONTINUATION_STEP
    for i in range(N):
        dist = math.sqrt(float(np.sum(((q[i] - qprev) / q_unit) ** 2)))
        h = max_step / dist if dist > max_step else 1.0
        t = 0.0
        st = k.ST_OK
        clear.set(state)
        while t < 1.0:
            tt = min(1.0, t + h)
            before = state.copy()
            st, res = evaluate(qprev + tt * (q[i] - qprev))
            if st == k.ST_OK:
                t = tt
                h = min(2.0 * h, max_step / dist) if dist > 0.0 else 1.0
                if (1.0 - t) * dist >= _CLEAR * k.NODE_STEP * max_step:
                    clear.set(state)
            else:
                state.set(before)
                if st == k.ST_NO_ASSEMBLY or h < _MIN_STEP:
                    break
                h *= 0.5
        if st != k.ST_OK and dist > 0.0 and (1.0 - t) * dist <= _AT * k.NODE_STEP * max_step:
            # stopped right at the sample: a singular configuration the motion passes,
            # placed from either side, predicted from a state well clear of it
            state.set(clear)
            placed, res = _place_between(q[i], qprev, k.NODE_STEP * max_step / dist, J, evaluate,
                                         p.n_angles, M)
            if placed:
                st = k.ST_OK
                t = 1.0
                res = (0.0, 0.0) + res[2:]
        out["status"][i] = st
        out["diag"][i] = res[:2]
        if st == k.ST_OK:
            S[:, :, i] = J[stored, :, 0]
        else:
            out["fail"][i] = res[2:]
        qprev = qprev + t * (q[i] - qprev)
    ok = np.flatnonzero(out["status"] == k.ST_OK)
    if len(ok) == N:
        _write(S, 0, N, qd, qdd, M, angle_rows, out)
    elif len(ok):                           # the samples that assembled, in runs
        for lo, hi in _runs(ok):
            _write(S[:, :, lo:hi], lo, hi, qd, qdd, M, angle_rows, out)
    return qprev, state.x.copy()


def _runs(idx):
    """Consecutive runs (lo, hi) of sorted indices."""
    cut = np.flatnonzero(np.diff(idx) != 1) + 1
    return [(int(r[0]), int(r[-1]) + 1) for r in np.split(idx, cut)]


def _place_between(qi, qprev, eps, J, evaluate, n_angles, M):
    """Place a sample on a singular configuration that the motion passes from the motion a
    little before and after it: the mean of the second-order predictions from both sides,
    angles averaged across their wrap (the kernel's ``_place_between``).  Returns (placed,
    the last evaluation's result); J then holds the sample (its K and L mean nothing)."""
    jc = J[:, :, 0]
    before = None
    res = None
    for sgn in (-1.0, 1.0):
        qt = qi + sgn * eps * (qi - qprev)
        st, res = evaluate(qt)
        if st != k.ST_OK:
            return False, res
        dm = qi - qt
        v = jc[:, 0].copy()
        for m in range(M):
            v = v + jc[:, 1 + m] * dm[m]
            for j in range(M):
                v = v + 0.5 * jc[:, 1 + M + m * M + j] * dm[m] * dm[j]
        if before is None:
            before = v
        else:
            d = v[:n_angles] - before[:n_angles]
            v[:n_angles] = before[:n_angles] + (d - 2.0 * math.pi * np.ceil((d - math.pi) / (2.0 * math.pi)))
            jc[:, 0] = 0.5 * (before + v)
    return True, res


def run(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None, designs=None):
    """Evaluate a plan over the rows of ``q`` (N, M) with rates ``qd``, ``qdd`` (N, M) or
    (1, M): the arguments and the outputs of :func:`kinelab.kinematics._evaluate.run`
    (jets, rates, diag, status, fail and, for plans with Newton groups, the state where
    the run ended), computed with numpy and no compilation: D designs of a plan without
    Newton groups all at once, with Newton groups one after the other."""
    from kinelab.kinematics._evaluate import Numbers, outputs
    q = np.asarray(q, float)
    qd = np.asarray(qd, float)
    qdd = np.asarray(qdd, float)
    _, stored, out = outputs(p, q, ops_f, stored)
    N, M = q.shape
    nums = Numbers(p, N, ops_f, start, designs)
    ends = []
    with np.errstate(all="ignore"):     # an exact singularity gives inf or NaN, then flagged
        if p.groups is None:
            _closed_form(p, _tables(p, M), q, qd, qdd, nums, stored, out, M)
            return out
        for d in range(nums.D):
            lo, hi = nums.starts[d], nums.starts[d + 1]
            rows = {key: a[lo:hi] for key, a in out.items()}
            rates = [r if len(r) == 1 else r[lo:hi] for r in (qd, qdd)]
            T = _tables(p, M) if designs is None else _Tables(p, M, nums.con_f[d])
            ends.append(_continuation(p, T, q[lo:hi], *rates, nums.q0[d], nums.q_unit[d],
                                      nums.ops_f[d], nums.const_values[d], nums.scale[d],
                                      stored, nums.x0[d], rows, M))
    out["state"] = (ends[0] if designs is None else
                    (np.array([e[0] for e in ends]), np.array([e[1] for e in ends])))
    return out
