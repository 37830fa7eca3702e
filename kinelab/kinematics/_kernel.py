"""The compiled interpreter that evaluates a solution plan, one sample at a time.

A *plan* (built by ``_plan.py``) is a short list of operations that, applied in order,
turn the input values q into every link angle and point position of a mechanism, together
with their first and second derivatives with respect to q: the velocity coefficients
K = dS/dq and the acceleration coefficients L = d2S/dq2 of the course notes.  Each
operation solves one small group of unknowns in closed form (a driven link, a dyad of
class II: RRR, RRP, RPR, two lines) or, for larger Assur groups, by Newton-Raphson with
continuation from the previous sample.

Every scalar coordinate (a link angle, a point's x or y, a slide) is an *item* with a
*jet*: one row ``[value, K_0 .. K_{M-1}, L_00, L_01, .. L_{M-1,M-1}]`` of the array
``jet``.  A point is two consecutive items (x, then y).  Keeping the whole state of a
sample in one small array keeps it in cache and makes every call cheap.

Derivatives are exact: every closed form is differentiated by hand; K and L of a dyad come
from the same 2x2 matrix as its position (Cramer's rule), the notes' J.  For M > 1 inputs
the second derivatives are bilinear: ``L[m, n] = d2 S / dq_m dq_n``.  The entry points
release the GIL: threads share the samples of a plan without Newton groups; continuation
is sequential.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from kinelab.kinematics._codes import (BASE_MIN, CAM_ROWS, OP_CAM, OP_CAM_SLIDE, C_DRIVE_ANGLE, C_DRIVE_SLIDE, C_PRISMATIC,
                                       C_REVOLUTE, CONTINUATION_STEP, DISC_TOL, DISC_ZERO,
                                       FOLDED, HEADER, HERMITE_REACH, JUMP_FLOOR, JUMP_RATIO,
                                       LIKELY_LAST, NEWTON_MAX_ITER, NEWTON_STALL, NEWTON_TOL,
                                       NODE_STEP, SINGULAR_STEPS,
                                       OP_DRIVE_ANGLE, OP_FRAME_POINT, OP_GEAR, OP_GEAR_SLIDE,
                                       OP_LINES, OP_LOCK_ANGLE,
                                       OP_NEWTON, OP_RIGID_POINT, OP_RPR, OP_RRP, OP_RRR,
                                       OP_SLIDE_OUT, OP_SLIDE_POINT, OP_TWO_POINTS,
                                       ST_NO_ASSEMBLY, ST_NO_CONVERGENCE, ST_OK)

# numba's cache of this file knows its text only: the digest of the files whose constants and
# functions it compiles in (kinelab._compiled.compiled_from; a test keeps it true)
COMPILED_FROM = "f5e765e27a8034cb"


def _jit(**options):
    # error_model="numpy": a division by zero at an exact singularity gives inf/nan (then
    # flagged), not a Python exception from inside the kernel
    return njit(cache=True, error_model="numpy", fastmath={"contract"}, **options)


# --------------------------------------------------------------------------------------
# closed-form groups.  jet has shape (lanes, n_items, 1 + M + M*M): one lane per sample of
# a block (see _evaluate); each helper works on the lane it is given.
# --------------------------------------------------------------------------------------
@_jit(inline="always")
def _carried(jet, lane, p, a, link, rx, ry, M):
    """p = a + r, with r (ground frame, now) fixed in a link whose jet is known:
    K_p = K_a + K_link k x r,  L_p = L_a + L_link k x r - K_link K_link r."""
    jet[lane, p, 0] = jet[lane, a, 0] + rx
    jet[lane, p + 1, 0] = jet[lane, a + 1, 0] + ry
    for m in range(M):
        km = jet[lane, link, 1 + m]
        jet[lane, p, 1 + m] = jet[lane, a, 1 + m] - km * ry
        jet[lane, p + 1, 1 + m] = jet[lane, a + 1, 1 + m] + km * rx
        for n in range(M):
            c2 = 1 + M + m * M + n
            kk = km * jet[lane, link, 1 + n]
            lmn = jet[lane, link, c2]
            jet[lane, p, c2] = jet[lane, a, c2] - lmn * ry - kk * rx
            jet[lane, p + 1, c2] = jet[lane, a + 1, c2] + lmn * rx - kk * ry


@_jit(inline="always")
def _rigid_point(jet, lane, p, link, a, rx, ry, M):
    """p = a + R(theta_link) r, r in the link's frame."""
    c = math.cos(jet[lane, link, 0])
    s = math.sin(jet[lane, link, 0])
    _carried(jet, lane, p, a, link, c * rx - s * ry, s * rx + c * ry, M)


@_jit(inline="always")
def _frame_point(jet, lane, p, a, b, lam, mu, M):
    """p = a + lam d + mu k x d with d = b - a: a point rigid with a link through two of its
    known points.  Linear in the two points, so their K and L carry over with no angle (and
    no sine or cosine) at all."""
    for c in range(1 + M + M * M):
        dx = jet[lane, b, c] - jet[lane, a, c]
        dy = jet[lane, b + 1, c] - jet[lane, a + 1, c]
        jet[lane, p, c] = jet[lane, a, c] + lam * dx - mu * dy
        jet[lane, p + 1, c] = jet[lane, a + 1, c] + lam * dy + mu * dx


@_jit(inline="always")
def _direction(jet, lane, link, beta):
    """Unit vector at angle theta_link + beta (a slide direction fixed in the link)."""
    phi = jet[lane, link, 0] + beta
    return math.cos(phi), math.sin(phi)


@_jit()
def _line_point(jet, lane, out, base, dirlink, beta, t, Kt, Lt, M):
    """out = base + t u, u at angle theta_dirlink + beta; t with its K (M,) and L (M, M)."""
    ux, uy = _direction(jet, lane, dirlink, beta)
    jet[lane, out, 0] = jet[lane, base, 0] + t * ux
    jet[lane, out + 1, 0] = jet[lane, base + 1, 0] + t * uy
    for m in range(M):
        wm = jet[lane, dirlink, 1 + m]
        jet[lane, out, 1 + m] = jet[lane, base, 1 + m] + Kt[m] * ux - t * wm * uy
        jet[lane, out + 1, 1 + m] = jet[lane, base + 1, 1 + m] + Kt[m] * uy + t * wm * ux
        for n in range(M):
            c2 = 1 + M + m * M + n
            wn = jet[lane, dirlink, 1 + n]
            nn = Kt[m] * wn + Kt[n] * wm + t * jet[lane, dirlink, c2]   # along n = k x u
            uu = Lt[m, n] - t * wm * wn                            # along u
            jet[lane, out, c2] = jet[lane, base, c2] + uu * ux - nn * uy
            jet[lane, out + 1, c2] = jet[lane, base + 1, c2] + uu * uy + nn * ux


@_jit()
def _cam_values(ops_f, k, n, theta):
    """S, dS/dtheta, d2S/dtheta2 of the cam program whose n pieces fill the CAM_ROWS rows a
    piece after operation k (kinelab.model._cams: where the piece starts, its segment's start
    and width, x0, level, height, B, k, phase, then c_0 .. c_14), at the cam angle theta
    (taken modulo a turn; a piece holds from its start to the next one's)."""
    turn = 2.0 * math.pi
    t = theta - turn * math.floor(theta / turn)
    if t >= turn:
        t -= turn
    r = k + 1
    for i in range(1, n):
        if ops_f[k + 1 + CAM_ROWS * i, 0] <= t:
            r = k + 1 + CAM_ROWS * i
    start, beta, x0 = ops_f[r, 1], ops_f[r, 2], ops_f[r, 3]
    level, h, b, kk, ph = ops_f[r, 4], ops_f[r, 5], ops_f[r, 6], ops_f[r, 7], ops_f[r + 1, 0]
    x = (t - start) / beta
    u = x - x0
    f = 0.0
    f1 = 0.0
    f2 = 0.0
    for i in range(15 - 1, -1, -1):       # Horner, with the first two derivatives
        c = ops_f[r + 1 + (i + 1) // 8, (i + 1) % 8]
        f2 = f2 * u + 2.0 * f1
        f1 = f1 * u + f
        f = f * u + c
    arg = kk * x + ph
    sa = math.sin(arg)
    ca = math.cos(arg)
    f += b * sa
    f1 += b * kk * ca
    f2 -= b * kk * kk * sa
    return level + h * f, h * f1 / beta, h * f2 / (beta * beta)


@_jit()
def _cam_motion(jet, lane, ops_f, k, n, cam, guide, M, Kt, Lt):
    """S(theta) of the program after operation k at theta = theta_cam - theta_guide (the
    guide 0 when -1); its K into Kt and L into Lt by the chain rule: K = S' K_theta,
    L = S'' K_theta K_theta + S' L_theta."""
    theta = jet[lane, cam, 0] - (jet[lane, guide, 0] if guide >= 0 else 0.0)
    S, S1, S2 = _cam_values(ops_f, k, n, theta)
    for m in range(M):
        km = jet[lane, cam, 1 + m] - (jet[lane, guide, 1 + m] if guide >= 0 else 0.0)
        Kt[m] = S1 * km
        for q in range(M):
            c2 = 1 + M + m * M + q
            kq = jet[lane, cam, 1 + q] - (jet[lane, guide, 1 + q] if guide >= 0 else 0.0)
            lmq = jet[lane, cam, c2] - (jet[lane, guide, c2] if guide >= 0 else 0.0)
            Lt[m, q] = S2 * km * kq + S1 * lmq
    return S


@_jit()
def _relative_slide(jet, lane, p, o, g, beta, M, Ks, Ls):
    """s = u . (p - o) with u at angle theta_g + beta; returns s, fills Ks (M,), Ls (M, M)."""
    ux, uy = _direction(jet, lane, g, beta)
    nx = -uy
    ny = ux
    dx = jet[lane, p, 0] - jet[lane, o, 0]
    dy = jet[lane, p + 1, 0] - jet[lane, o + 1, 0]
    ud = ux * dx + uy * dy
    nd = nx * dx + ny * dy
    for m in range(M):
        dmx = jet[lane, p, 1 + m] - jet[lane, o, 1 + m]
        dmy = jet[lane, p + 1, 1 + m] - jet[lane, o + 1, 1 + m]
        wm = jet[lane, g, 1 + m]
        Ks[m] = wm * nd + ux * dmx + uy * dmy
        for n in range(M):
            c2 = 1 + M + m * M + n
            dnx = jet[lane, p, 1 + n] - jet[lane, o, 1 + n]
            dny = jet[lane, p + 1, 1 + n] - jet[lane, o + 1, 1 + n]
            wn = jet[lane, g, 1 + n]
            ldx = jet[lane, p, c2] - jet[lane, o, c2]
            ldy = jet[lane, p + 1, c2] - jet[lane, o + 1, c2]
            Ls[m, n] = (jet[lane, g, c2] * nd - wm * wn * ud
                        + wm * (nx * dnx + ny * dny) + wn * (nx * dmx + ny * dmy)
                        + ux * ldx + uy * ldy)
    return ud


@_jit(inline="always")
def _rrr(jet, lane, b, c, X, Y, Z, lb, lc, sigma, offb, offc, M):
    """Circle-circle dyad; returns (det, measure, gap).  gap > 0: cannot close by gap (m).

    With d = Z - X, the joint is Y = X + alpha d + sigma beta k x d, where alpha and beta
    are the along and across distances of Y over |d|: no |d| is needed, so one square root
    and one division stand between the input and Y.  Then r_b x r_c = sigma beta |d|^2.
    """
    dx = jet[lane, Z, 0] - jet[lane, X, 0]
    dy = jet[lane, Z + 1, 0] - jet[lane, X + 1, 0]
    D2 = dx * dx + dy * dy
    if D2 <= FOLDED * lb * lb:      # X and Z coincide to rounding: d has no direction
        if abs(lb - lc) > 1e-12 * lb:
            return 0.0, 0.0, abs(lb - lc) - math.sqrt(D2)
        _rrr_folded(jet, lane, b, c, X, Y, Z, lb, sigma, offb, offc, M)
        return 0.0, 0.0, 0.0
    inv_D2 = 1.0 / D2
    alpha = 0.5 * (lb * lb - lc * lc + D2) * inv_D2
    beta2 = lb * lb * inv_D2 - alpha * alpha
    if beta2 < DISC_ZERO * lb * lb * inv_D2:
        if beta2 < -DISC_TOL * lb * lb * inv_D2:
            D = math.sqrt(D2)
            return 0.0, 0.0, max(D - (lb + lc), abs(lb - lc) - D)
        beta2 = 0.0
    sb = sigma * math.sqrt(beta2)
    rbx = alpha * dx - sb * dy             # r_b = Y - X
    rby = alpha * dy + sb * dx
    rcx = rbx - dx                          # r_c = Y - Z
    rcy = rby - dy
    cr = sb * D2                            # cross(r_b, r_c)
    inv_cr = 1.0 / cr
    jet[lane, b, 0] = math.atan2(rby, rbx) + offb
    jet[lane, c, 0] = math.atan2(rcy, rcx) + offc
    # velocity: wb k x rb - wc k x rc = vZ - vX  (dot with rc and with rb)
    for m in range(M):
        wx = jet[lane, Z, 1 + m] - jet[lane, X, 1 + m]
        wy = jet[lane, Z + 1, 1 + m] - jet[lane, X + 1, 1 + m]
        jet[lane, b, 1 + m] = (wx * rcx + wy * rcy) * inv_cr
        jet[lane, c, 1 + m] = (wx * rbx + wy * rby) * inv_cr
    # acceleration: same matrix, right side with the centripetal terms
    for m in range(M):
        for n in range(M):
            c2 = 1 + M + m * M + n
            kb = jet[lane, b, 1 + m] * jet[lane, b, 1 + n]
            kc = jet[lane, c, 1 + m] * jet[lane, c, 1 + n]
            wx = jet[lane, Z, c2] - jet[lane, X, c2] + kb * rbx - kc * rcx
            wy = jet[lane, Z + 1, c2] - jet[lane, X + 1, c2] + kb * rby - kc * rcy
            jet[lane, b, c2] = (wx * rcx + wy * rcy) * inv_cr
            jet[lane, c, c2] = (wx * rbx + wy * rby) * inv_cr
    _carried(jet, lane, Y, X, b, rbx, rby, M)
    return -cr, abs(cr) / (lb * lc), 0.0


@_jit()
def _rrr_folded(jet, lane, b, c, X, Y, Z, lb, sigma, offb, offc, M):
    """An RRR dyad with equal arms whose end joints coincide (a kite four-bar whose crank
    pin reaches the rocker pivot): the arms fold onto each other, and Y, anywhere on their
    common circle, is where the motion takes it, the limit of Y = X + sigma lb k x d/|d| as
    d = Z - X shrinks along its rate (of the first input).  A singular configuration: K and
    L are not defined (NaN)."""
    ex = jet[lane, Z, 1] - jet[lane, X, 1]
    ey = jet[lane, Z + 1, 1] - jet[lane, X + 1, 1]
    n = math.hypot(ex, ey)
    rbx = -sigma * lb * ey / n if n > 0.0 else math.nan
    rby = sigma * lb * ex / n if n > 0.0 else math.nan
    jet[lane, b, 0] = math.atan2(rby, rbx) + offb
    jet[lane, c, 0] = math.atan2(rby, rbx) + offc
    for col in range(1, 1 + M + M * M):
        jet[lane, b, col] = math.nan
        jet[lane, c, col] = math.nan
    _carried(jet, lane, Y, X, b, rbx, rby, M)


@_jit()
def _rrp(jet, lane, b, X, Y, o, g, lb, beta, sigma, offb, M, Ks):
    """Circle-line dyad: Y on the line o + s u (u fixed in link g), |Y - X| = lb."""
    ux, uy = _direction(jet, lane, g, beta)
    nx = -uy
    ny = ux
    w0x = jet[lane, o, 0] - jet[lane, X, 0]
    w0y = jet[lane, o + 1, 0] - jet[lane, X + 1, 0]
    uw = ux * w0x + uy * w0y
    hh = nx * w0x + ny * w0y            # signed distance of X from the line
    t2 = lb * lb - hh * hh
    if t2 < DISC_ZERO * lb * lb:
        if t2 < -DISC_TOL * lb * lb:
            return 0.0, 0.0, abs(hh) - lb
        t2 = 0.0
    t = sigma * math.sqrt(t2)
    s = t - uw                          # slide along the line from o
    rx = hh * nx + t * ux               # r = Y - X
    ry = hh * ny + t * uy
    jet[lane, b, 0] = math.atan2(ry, rx) + offb
    ru = t                              # r . u
    kru = -ry * ux + rx * uy            # (k x r) . u
    for m in range(M):
        wg = jet[lane, g, 1 + m]
        w1x = jet[lane, o, 1 + m] + s * wg * nx - jet[lane, X, 1 + m]
        w1y = jet[lane, o + 1, 1 + m] + s * wg * ny - jet[lane, X + 1, 1 + m]
        wb = (w1x * nx + w1y * ny) / ru
        jet[lane, b, 1 + m] = wb
        Ks[m] = wb * kru - (w1x * ux + w1y * uy)
    for m in range(M):
        for n in range(M):
            c2 = 1 + M + m * M + n
            kb = jet[lane, b, 1 + m] * jet[lane, b, 1 + n]
            kg = jet[lane, g, 1 + m] * jet[lane, g, 1 + n]
            cor = Ks[m] * jet[lane, g, 1 + n] + Ks[n] * jet[lane, g, 1 + m]
            lg = jet[lane, g, c2]
            w2x = jet[lane, o, c2] + cor * nx + s * (lg * nx - kg * ux) - jet[lane, X, c2] + kb * rx
            w2y = jet[lane, o + 1, c2] + cor * ny + s * (lg * ny - kg * uy) - jet[lane, X + 1, c2] + kb * ry
            jet[lane, b, c2] = (w2x * nx + w2y * ny) / ru
    _carried(jet, lane, Y, X, b, rx, ry, M)
    return ru, abs(ru) / lb, 0.0


@_jit()
def _rpr(jet, lane, G, X, Z, rho_x, rho_y, u_x, u_y, sigma, M, Ks):
    """Turning-line dyad: X - Z = R(theta_G) (rho + s u), rho and u in G's frame.

    Its measure is the slide from the foot of Z over |rho| (X - Z at the sketch): zero where
    the line stands perpendicular to X - Z, a limit position or, with no offset, the point
    X passing through the pivot Z.
    """
    wx = jet[lane, X, 0] - jet[lane, Z, 0]
    wy = jet[lane, X + 1, 0] - jet[lane, Z + 1, 0]
    D2 = wx * wx + wy * wy
    h = u_x * rho_y - u_y * rho_x           # distance of Z from the line, in G's frame
    rho2 = rho_x * rho_x + rho_y * rho_y
    if D2 <= FOLDED * rho2 and h * h <= FOLDED * rho2:
        _rpr_through_pivot(jet, lane, G, X, Z, u_x, u_y, sigma, M)
        return 0.0, 0.0, 0.0
    t2 = D2 - h * h
    if t2 < DISC_ZERO * max(D2, h * h):
        if t2 < -DISC_TOL * max(D2, h * h):
            return 0.0, 0.0, abs(h) - math.sqrt(D2)
        t2 = 0.0
    t = sigma * math.sqrt(t2)
    # in G's frame w' = rho + s u = h n' + t u'  with n' = k x u'
    lx = -h * u_y + t * u_x
    ly = h * u_x + t * u_y
    th = math.atan2(wy, wx) - math.atan2(ly, lx)
    jet[lane, G, 0] = th
    c = math.cos(th)
    sn = math.sin(th)
    ux = c * u_x - sn * u_y
    uy = sn * u_x + c * u_y
    nx = -uy
    ny = ux
    wu = t                                  # w . u
    kwu = wx * uy - wy * ux                 # (k x w) . u
    for m in range(M):
        dx = jet[lane, X, 1 + m] - jet[lane, Z, 1 + m]
        dy = jet[lane, X + 1, 1 + m] - jet[lane, Z + 1, 1 + m]
        om = (dx * nx + dy * ny) / wu
        jet[lane, G, 1 + m] = om
        Ks[m] = dx * ux + dy * uy - om * kwu
    for m in range(M):
        for n in range(M):
            c2 = 1 + M + m * M + n
            kk = jet[lane, G, 1 + m] * jet[lane, G, 1 + n]
            cor = Ks[m] * jet[lane, G, 1 + n] + Ks[n] * jet[lane, G, 1 + m]
            r2x = jet[lane, X, c2] - jet[lane, Z, c2] + kk * wx - cor * nx
            r2y = jet[lane, X + 1, c2] - jet[lane, Z + 1, c2] + kk * wy - cor * ny
            jet[lane, G, c2] = (r2x * nx + r2y * ny) / wu
    return -wu, abs(wu) / math.sqrt(rho2), 0.0


@_jit()
def _rpr_through_pivot(jet, lane, G, X, Z, u_x, u_y, sigma, M):
    """A turning line with no offset whose point X passes through its pivot Z (a slotted
    link whose crank pin crosses the lever pivot): the line's direction is where the
    motion takes it, sigma times the direction of X - Z's rate (of the first input).  A
    singular configuration: K and L are not defined (NaN)."""
    ex = jet[lane, X, 1] - jet[lane, Z, 1]
    ey = jet[lane, X + 1, 1] - jet[lane, Z + 1, 1]
    th = math.atan2(sigma * ey, sigma * ex) - math.atan2(u_y, u_x)
    jet[lane, G, 0] = th if ex != 0.0 or ey != 0.0 else math.nan
    for col in range(1, 1 + M + M * M):
        jet[lane, G, col] = math.nan


@_jit()
def _lines(jet, lane, out, o1, l1, o2, l2, beta1, beta2, M, K1, K2, L1):
    """Intersection of two lines o_i + t_i u_i, u_i at angle theta_{l_i} + beta_i."""
    p1 = jet[lane, l1, 0] + beta1
    p2 = jet[lane, l2, 0] + beta2
    u1x = math.cos(p1)
    u1y = math.sin(p1)
    u2x = math.cos(p2)
    u2y = math.sin(p2)
    cr = u1x * u2y - u1y * u2x
    if cr == 0.0:                   # parallel: no point (NaN, not another sample's), det J = 0
        for c in range(1 + M + M * M):
            jet[lane, out, c] = math.nan
            jet[lane, out + 1, c] = math.nan
        return 0.0, 0.0, 0.0
    wx = jet[lane, o2, 0] - jet[lane, o1, 0]
    wy = jet[lane, o2 + 1, 0] - jet[lane, o1 + 1, 0]
    t1 = (wx * u2y - wy * u2x) / cr
    t2 = (wx * u1y - wy * u1x) / cr
    for m in range(M):
        a1 = jet[lane, l1, 1 + m]
        a2 = jet[lane, l2, 1 + m]
        vx = jet[lane, o2, 1 + m] - t2 * a2 * u2y - jet[lane, o1, 1 + m] + t1 * a1 * u1y
        vy = jet[lane, o2 + 1, 1 + m] + t2 * a2 * u2x - jet[lane, o1 + 1, 1 + m] - t1 * a1 * u1x
        K1[m] = (vx * u2y - vy * u2x) / cr
        K2[m] = (vx * u1y - vy * u1x) / cr
    for m in range(M):
        for n in range(M):
            c2 = 1 + M + m * M + n
            a1m = jet[lane, l1, 1 + m]
            a1n = jet[lane, l1, 1 + n]
            a2m = jet[lane, l2, 1 + m]
            a2n = jet[lane, l2, 1 + n]
            c1 = K1[m] * a1n + K1[n] * a1m + t1 * jet[lane, l1, c2]   # normal part, line 1
            cc2 = K2[m] * a2n + K2[n] * a2m + t2 * jet[lane, l2, c2]
            q1 = t1 * a1m * a1n                                # centripetal part
            q2 = t2 * a2m * a2n
            ax = (jet[lane, o2, c2] - cc2 * u2y - q2 * u2x) - (jet[lane, o1, c2] - c1 * u1y - q1 * u1x)
            ay = (jet[lane, o2 + 1, c2] + cc2 * u2x - q2 * u2y) - (jet[lane, o1 + 1, c2] + c1 * u1x - q1 * u1y)
            L1[m, n] = (ax * u2y - ay * u2x) / cr
    _line_point(jet, lane, out, o1, l1, beta1, t1, K1, L1, M)
    return -cr, abs(cr), 0.0


@_jit()
def _two_points(jet, lane, b, p1, p2, offset, M):
    """Angle of a link through two placed points: theta = atan2(p2 - p1) + offset."""
    dx = jet[lane, p2, 0] - jet[lane, p1, 0]
    dy = jet[lane, p2 + 1, 0] - jet[lane, p1 + 1, 0]
    d2 = dx * dx + dy * dy
    jet[lane, b, 0] = math.atan2(dy, dx) + offset
    for m in range(M):
        kx = jet[lane, p2, 1 + m] - jet[lane, p1, 1 + m]
        ky = jet[lane, p2 + 1, 1 + m] - jet[lane, p1 + 1, 1 + m]
        jet[lane, b, 1 + m] = (dx * ky - dy * kx) / d2
    for m in range(M):
        kmx = jet[lane, p2, 1 + m] - jet[lane, p1, 1 + m]
        kmy = jet[lane, p2 + 1, 1 + m] - jet[lane, p1 + 1, 1 + m]
        for n in range(M):
            c2 = 1 + M + m * M + n
            knx = jet[lane, p2, 1 + n] - jet[lane, p1, 1 + n]
            kny = jet[lane, p2 + 1, 1 + n] - jet[lane, p1 + 1, 1 + n]
            lx = jet[lane, p2, c2] - jet[lane, p1, c2]
            ly = jet[lane, p2 + 1, c2] - jet[lane, p1 + 1, c2]
            jet[lane, b, c2] = ((knx * kmy - kny * kmx + dx * ly - dy * lx) / d2
                          - 2.0 * (dx * kmy - dy * kmx) * (dx * knx + dy * kny) / (d2 * d2))


# --------------------------------------------------------------------------------------
# Newton groups: links whose poses (anchor x, y and angle) are solved together
# --------------------------------------------------------------------------------------
@_jit()
def _lu_factor(A, piv, n):
    """In-place LU with partial pivoting of A[:n, :n]; returns the determinant.  U's
    diagonal is kept as its reciprocals (0.0 for a zero pivot), so that the solves multiply
    where they would divide: a division's latency is several multiplications'."""
    det = 1.0
    for k in range(n):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, n):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                p = i
        piv[k] = p
        if p != k:
            det = -det
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
        d = A[k, k]
        det *= d
        if d == 0.0:
            continue
        r = 1.0 / d
        A[k, k] = r
        for i in range(k + 1, n):
            f = A[i, k] * r
            A[i, k] = f
            if f == 0.0:                    # (a sparse Jacobian's rows often need none)
                continue
            for j in range(k + 1, n):
                A[i, j] -= f * A[k, j]
    return det


@_jit()
def _lu_solve(A, piv, b, n):
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= A[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= A[i, j] * b[j]
        b[i] = s * A[i, i]


# The group's unknowns x = (x_anchor, y_anchor, theta) per link live in gx; their K and L
# (the columns of the group's own jet) in gK (n, M) and gL (n, M, M).  A "side" helper
# returns a quantity of one end of a constraint, from the group or from the known jet.

@_jit()
def _link_trig(x, nlk, cs):
    """cs[2j], cs[2j+1] <- cos and sin of the angle of group link j (once per evaluation)."""
    for j in range(nlk):
        cs[2 * j] = math.cos(x[3 * j + 2])
        cs[2 * j + 1] = math.sin(x[3 * j + 2])


@_jit()
def _side_pos(gi, p, rx, ry, x, cs, jet):
    if gi >= 0:
        c = cs[2 * gi]
        s = cs[2 * gi + 1]
        return x[3 * gi] + c * rx - s * ry, x[3 * gi + 1] + s * rx + c * ry
    return jet[p, 0], jet[p + 1, 0]


@_jit()
def _side_vel(gi, p, rx, ry, cs, gK, jet, m, known_only):
    if gi >= 0:
        if known_only:
            return 0.0, 0.0
        c = cs[2 * gi]
        s = cs[2 * gi + 1]
        vx = c * rx - s * ry
        vy = s * rx + c * ry
        w = gK[3 * gi + 2, m]
        return gK[3 * gi, m] - w * vy, gK[3 * gi + 1, m] + w * vx
    return jet[p, 1 + m], jet[p + 1, 1 + m]


@_jit()
def _side_acc(gi, p, rx, ry, cs, gK, jet, m, n, M):
    """Second derivative without the group's own second derivatives (those are J L)."""
    if gi >= 0:
        c = cs[2 * gi]
        s = cs[2 * gi + 1]
        kk = gK[3 * gi + 2, m] * gK[3 * gi + 2, n]
        return -kk * (c * rx - s * ry), -kk * (s * rx + c * ry)
    c2 = 1 + M + m * M + n
    return jet[p, c2], jet[p + 1, c2]


@_jit()
def _side_angle(gi, link, x, jet):
    if gi >= 0:
        return x[3 * gi + 2]
    return jet[link, 0] if link >= 0 else 0.0


@_jit()
def _side_rate(gi, link, gK, jet, m, known_only):
    if gi >= 0:
        return 0.0 if known_only else gK[3 * gi + 2, m]
    return jet[link, 1 + m] if link >= 0 else 0.0


@_jit()
def _side_second(gi, link, jet, m, n, M):
    if gi >= 0 or link < 0:
        return 0.0
    return jet[link, 1 + M + m * M + n]


@_jit()
def _jac_point(A, row, gi, rx, ry, cs, cx, cy):
    """Add d(c . p)/d(unknowns) for a point p of group link gi (nothing if p is known)."""
    if gi < 0:
        return
    c = cs[2 * gi]
    s = cs[2 * gi + 1]
    vx = c * rx - s * ry
    vy = s * rx + c * ry
    A[row, 3 * gi] += cx
    A[row, 3 * gi + 1] += cy
    A[row, 3 * gi + 2] += -cx * vy + cy * vx


@_jit()
def _slide_frame(con_i, con_f, k, x, cs, jet):
    """Guide angle, slide direction u and d = p - o of prismatic constraint k."""
    gg, po, lg, gs, pp = con_i[k, 1], con_i[k, 2], con_i[k, 3], con_i[k, 4], con_i[k, 5]
    tg = _side_angle(gg, lg, x, jet)
    ux = math.cos(tg + con_f[k, 4])
    uy = math.sin(tg + con_f[k, 4])
    ox, oy = _side_pos(gg, po, con_f[k, 0], con_f[k, 1], x, cs, jet)
    px, py = _side_pos(gs, pp, con_f[k, 2], con_f[k, 3], x, cs, jet)
    return tg, ux, uy, px - ox, py - oy


@_jit()
def _group_residual(c0, c1, con_i, con_f, x, cs, q, jet, A, phi, with_jac):
    """Residuals phi and (optionally) Jacobian A of one group's constraints; cs holds the
    cosines and sines of the group's link angles (``_link_trig``)."""
    row = 0
    for k in range(c0, c1):
        kind = con_i[k, 0]
        if kind == C_REVOLUTE:
            gi, pi_, gj, pj = con_i[k, 1], con_i[k, 2], con_i[k, 4], con_i[k, 5]
            xi, yi = _side_pos(gi, pi_, con_f[k, 0], con_f[k, 1], x, cs, jet)
            xj, yj = _side_pos(gj, pj, con_f[k, 2], con_f[k, 3], x, cs, jet)
            phi[row] = xi - xj
            phi[row + 1] = yi - yj
            if with_jac:
                _jac_point(A, row, gi, con_f[k, 0], con_f[k, 1], cs, 1.0, 0.0)
                _jac_point(A, row, gj, con_f[k, 2], con_f[k, 3], cs, -1.0, 0.0)
                _jac_point(A, row + 1, gi, con_f[k, 0], con_f[k, 1], cs, 0.0, 1.0)
                _jac_point(A, row + 1, gj, con_f[k, 2], con_f[k, 3], cs, 0.0, -1.0)
            row += 2
        elif kind == C_DRIVE_ANGLE:
            ga, la, gb, lb, m = con_i[k, 1], con_i[k, 3], con_i[k, 4], con_i[k, 6], con_i[k, 7]
            phi[row] = (_side_angle(gb, lb, x, jet) - _side_angle(ga, la, x, jet)
                        - con_f[k, 0] * q[m])
            if with_jac:
                if gb >= 0:
                    A[row, 3 * gb + 2] += 1.0
                if ga >= 0:
                    A[row, 3 * ga + 2] -= 1.0
            row += 1
        else:  # prismatic constraint or driven slide
            gg, po, lg, gs, pp, ls = (con_i[k, 1], con_i[k, 2], con_i[k, 3], con_i[k, 4],
                                      con_i[k, 5], con_i[k, 6])
            rox, roy, rpx, rpy = con_f[k, 0], con_f[k, 1], con_f[k, 2], con_f[k, 3]
            tg, ux, uy, dx, dy = _slide_frame(con_i, con_f, k, x, cs, jet)
            nx = -uy
            ny = ux
            if kind == C_PRISMATIC:
                phi[row] = _side_angle(gs, ls, x, jet) - tg - con_f[k, 5]
                phi[row + 1] = nx * dx + ny * dy
                if with_jac:
                    if gs >= 0:
                        A[row, 3 * gs + 2] += 1.0
                    if gg >= 0:
                        A[row, 3 * gg + 2] -= 1.0
                        A[row + 1, 3 * gg + 2] -= ux * dx + uy * dy
                    _jac_point(A, row + 1, gs, rpx, rpy, cs, nx, ny)
                    _jac_point(A, row + 1, gg, rox, roy, cs, -nx, -ny)
                row += 2
            else:
                m = con_i[k, 7]
                phi[row] = ux * dx + uy * dy - (q[m] - con_f[k, 5])
                if with_jac:
                    if gg >= 0:
                        A[row, 3 * gg + 2] += nx * dx + ny * dy
                    _jac_point(A, row, gs, rpx, rpy, cs, ux, uy)
                    _jac_point(A, row, gg, rox, roy, cs, -ux, -uy)
                row += 1


@_jit()
def _group_rhs(c0, c1, con_i, con_f, x, cs, gK, jet, m, n, second, M, rhs):
    """Right-hand sides of J K[:, m] = rhs (second=False) and J L[:, m, n] = rhs (second=True)."""
    row = 0
    for k in range(c0, c1):
        kind = con_i[k, 0]
        if kind == C_REVOLUTE:
            gi, pi_, gj, pj = con_i[k, 1], con_i[k, 2], con_i[k, 4], con_i[k, 5]
            if second:
                aix, aiy = _side_acc(gi, pi_, con_f[k, 0], con_f[k, 1], cs, gK, jet, m, n, M)
                ajx, ajy = _side_acc(gj, pj, con_f[k, 2], con_f[k, 3], cs, gK, jet, m, n, M)
            else:
                aix, aiy = _side_vel(gi, pi_, con_f[k, 0], con_f[k, 1], cs, gK, jet, m, True)
                ajx, ajy = _side_vel(gj, pj, con_f[k, 2], con_f[k, 3], cs, gK, jet, m, True)
            rhs[row] = -(aix - ajx)
            rhs[row + 1] = -(aiy - ajy)
            row += 2
        elif kind == C_DRIVE_ANGLE:
            ga, la, gb, lb, mi = con_i[k, 1], con_i[k, 3], con_i[k, 4], con_i[k, 6], con_i[k, 7]
            if second:
                rhs[row] = -(_side_second(gb, lb, jet, m, n, M) - _side_second(ga, la, jet, m, n, M))
            else:
                v = _side_rate(gb, lb, gK, jet, m, True) - _side_rate(ga, la, gK, jet, m, True)
                if mi == m:
                    v -= con_f[k, 0]
                rhs[row] = -v
            row += 1
        else:
            gg, po, lg, gs, pp, ls = (con_i[k, 1], con_i[k, 2], con_i[k, 3], con_i[k, 4],
                                      con_i[k, 5], con_i[k, 6])
            rox, roy, rpx, rpy = con_f[k, 0], con_f[k, 1], con_f[k, 2], con_f[k, 3]
            tg, ux, uy, dx, dy = _slide_frame(con_i, con_f, k, x, cs, jet)
            nx = -uy
            ny = ux
            ud = ux * dx + uy * dy
            nd = nx * dx + ny * dy
            if not second:
                wg = _side_rate(gg, lg, gK, jet, m, True)
                vpx, vpy = _side_vel(gs, pp, rpx, rpy, cs, gK, jet, m, True)
                vox, voy = _side_vel(gg, po, rox, roy, cs, gK, jet, m, True)
                ddx = vpx - vox
                ddy = vpy - voy
                if kind == C_PRISMATIC:
                    rhs[row] = -(_side_rate(gs, ls, gK, jet, m, True) - wg)
                    rhs[row + 1] = -(-wg * ud + nx * ddx + ny * ddy)
                else:
                    v = wg * nd + ux * ddx + uy * ddy
                    if con_i[k, 7] == m:
                        v -= 1.0
                    rhs[row] = -v
            else:
                wm = _side_rate(gg, lg, gK, jet, m, False)
                wn = _side_rate(gg, lg, gK, jet, n, False)
                ag = _side_second(gg, lg, jet, m, n, M)
                vpx, vpy = _side_vel(gs, pp, rpx, rpy, cs, gK, jet, m, False)
                vox, voy = _side_vel(gg, po, rox, roy, cs, gK, jet, m, False)
                dmx = vpx - vox
                dmy = vpy - voy
                vpx, vpy = _side_vel(gs, pp, rpx, rpy, cs, gK, jet, n, False)
                vox, voy = _side_vel(gg, po, rox, roy, cs, gK, jet, n, False)
                dnx = vpx - vox
                dny = vpy - voy
                apx, apy = _side_acc(gs, pp, rpx, rpy, cs, gK, jet, m, n, M)
                aox, aoy = _side_acc(gg, po, rox, roy, cs, gK, jet, m, n, M)
                adx = apx - aox
                ady = apy - aoy
                if kind == C_PRISMATIC:
                    rhs[row] = -(_side_second(gs, ls, jet, m, n, M) - ag)
                    rhs[row + 1] = -(-ag * ud - wm * wn * nd
                                     - wm * (ux * dnx + uy * dny) - wn * (ux * dmx + uy * dmy)
                                     + nx * adx + ny * ady)
                else:
                    rhs[row] = -(ag * nd - wm * wn * ud
                                 + wm * (nx * dnx + ny * dny) + wn * (nx * dmx + ny * dmy)
                                 + ux * adx + uy * ady)
            row += 2 if kind == C_PRISMATIC else 1




@_jit()
def _hermite_reach(q, gq, g, ng, M):
    """The step to q from group g's last state in units of the step between its last two
    states, u = (q - q0) / (q0 - q1); 0.0 where the quintic predictor does not apply: more
    than one input, no state before, or a step more than HERMITE_REACH such steps long."""
    if M != 1:
        return 0.0
    h = gq[g, 0] - gq[ng + g, 0]
    if not (h != 0.0 and math.isfinite(h)):
        return 0.0
    u = (q[0] - gq[g, 0]) / h
    return u if abs(u) <= HERMITE_REACH else 0.0


@_jit()
def _hermite_terms(gx, gK, gL, gq, g, ng, i0, i1, u):
    """What the quintic through the last state (x0, K0, L0 of row i0, at q0) and the one
    before (row i1, at q1 = q0 - h) adds to the second-order predictor S + K dq + 1/2 L dq**2
    at q = q0 + u h: a3 u**3 + a4 u**4 + a5 u**5, with a_k = c_k h**k from the states' misfit
    to the parabola of the last one (a at x1, b h at K1, c h**2 at L1).  Its error is in
    h**6, against h**3 of the parabola (one input only)."""
    h = gq[g, 0] - gq[ng + g, 0]
    x0 = gx[i0]
    k0 = gK[i0, 0]
    l0 = gL[i0, 0, 0]
    a = gx[i1] - (x0 - k0 * h + 0.5 * l0 * h * h)
    b = (gK[i1, 0] - (k0 - l0 * h)) * h
    c = (gL[i1, 0, 0] - l0) * h * h
    a5 = -0.5 * c - 3.0 * b - 6.0 * a
    a4 = -c - 7.0 * b - 15.0 * a
    a3 = -0.5 * c - 4.0 * b - 10.0 * a
    return u * u * u * (a3 + u * (a4 + u * a5))


@_jit()
def _newton_group(g, groups_i, con_i, con_f, scale, q, jet, gx, gK, gL, gq, gdet, M, work, piv):
    """Solve group g at input q by continuation from its stored state; write the result.

    ``groups_i`` rows: (first unknown, number of links, first constraint, end constraint,
    then for each link its angle item and anchor item are in ``groups_i[g, 4:]`` order:
    link items start at column 4, anchors follow).  Returns (status, det, measure).  The
    stored state (gx, gK, gL, gq, gdet) changes only on success.  gx, gK, gL and gq hold two
    states one above the other: the last solved (rows 0:nx, 0:ng) and the one before it
    (rows nx:2nx, ng:2ng; its input NaN where there is none), which the predictor uses.
    """
    o = groups_i[g, 0]
    nlk = groups_i[g, 1]
    c0 = groups_i[g, 2]
    c1 = groups_i[g, 3]
    n = 3 * nlk
    A = work[:n * n].reshape((n, n))
    phi = work[n * n:n * n + n]
    x = work[n * n + n:n * n + 2 * n]
    xp = work[n * n + 2 * n:n * n + 3 * n]
    Kw = work[n * n + 3 * n:n * n + 3 * n + n * M].reshape((n, M))
    Lw = work[n * n + 3 * n + n * M:n * n + 3 * n + n * M + n * M * M].reshape((n, M, M))
    nx = gx.shape[0] >> 1
    ng = gq.shape[0] >> 1
    # the predictor: S + K dq + 1/2 dq L dq, and with one input and the state before at hand,
    # the quintic through both states' S, K and L (``_hermite_terms``).  Steps are measured in
    # the unknowns' own units: an anchor's x and y in sizes of the mechanism, an angle in rad
    u = _hermite_reach(q, gq, g, ng, M)
    inv = 1.0 / scale
    step = 0.0
    for i in range(n):
        v = gx[o + i]
        for m in range(M):
            dm = q[m] - gq[g, m]
            v += gK[o + i, m] * dm
            for k in range(M):
                v += 0.5 * gL[o + i, m, k] * dm * (q[k] - gq[g, k])
        if u != 0.0:
            v += _hermite_terms(gx, gK, gL, gq, g, ng, o + i, nx + o + i, u)
        xp[i] = v
        x[i] = v
        step += ((v - gx[o + i]) * (1.0 if i % 3 == 2 else inv)) ** 2
    step = math.sqrt(step)
    e = n * n + 3 * n + n * M + n * M * M
    cs = work[e:e + 2 * nlk]
    cn = work[e + 2 * nlk:e + 2 * nlk + n]          # the scalings of A's columns
    rn = work[e + 2 * nlk + n:e + 2 * nlk + 2 * n]  # ... and of its rows (``_norms``)
    v = work[e + 2 * nlk + 2 * n:e + 2 * nlk + 3 * n]
    w = work[e + 2 * nlk + 3 * n:e + 2 * nlk + 4 * n]
    converged = False
    det = 0.0
    last = math.inf
    normed = False      # whether cn, rn are of the Jacobian factorised last
    for it in range(NEWTON_MAX_ITER):
        A[:, :] = 0.0
        _link_trig(x, nlk, cs)
        _group_residual(c0, c1, con_i, con_f, x, cs, q, jet, A, phi, True)
        normed = last <= LIKELY_LAST        # the scalings, where this step is likely the last
        if normed:
            _norms(c0, c1, con_i, A, n, scale, cn, rn)
        det = _lu_factor(A, piv, n)
        if _lu_singular(A, n):
            break
        for i in range(n):
            phi[i] = -phi[i]
        _lu_solve(A, piv, phi, n)
        dn = 0.0
        for i in range(n):
            w[i] = x[i]                     # where the Jacobian was taken
            x[i] += phi[i]
            dn += (phi[i] * (1.0 if i % 3 == 2 else inv)) ** 2
        dn = math.sqrt(dn)
        if not math.isfinite(dn):
            break
        if dn <= NEWTON_TOL or (dn <= NEWTON_STALL and dn > 0.5 * last):
            converged = True
            break
        last = dn
    if not converged:
        return ST_NO_CONVERGENCE, 0.0, 0.0
    if not normed:      # converged sooner than foreseen: that Jacobian again, for its scalings
        A[:, :] = 0.0
        _link_trig(w, nlk, cs)
        _group_residual(c0, c1, con_i, con_f, w, cs, q, jet, A, phi, True)
        _norms(c0, c1, con_i, A, n, scale, cn, rn)
        _lu_factor(A, piv, n)
    corr = 0.0
    for i in range(n):
        corr += ((x[i] - xp[i]) * (1.0 if i % 3 == 2 else inv)) ** 2
    if math.sqrt(corr) > JUMP_RATIO * step + JUMP_FLOOR:
        return ST_NO_CONVERGENCE, 0.0, 0.0
    # K and L: linear solves with the last factorisation, whose Jacobian differs from the
    # one at the solution by the last Newton step (below 1e-13 of the mechanism's size)
    _link_trig(x, nlk, cs)
    for m in range(M):
        _group_rhs(c0, c1, con_i, con_f, x, cs, Kw, jet, m, m, False, M, phi)
        _lu_solve(A, piv, phi, n)
        for i in range(n):
            Kw[i, m] = phi[i]
    for m in range(M):
        for k in range(m, M):
            _group_rhs(c0, c1, con_i, con_f, x, cs, Kw, jet, m, k, True, M, phi)
            _lu_solve(A, piv, phi, n)
            for i in range(n):
                Lw[i, m, k] = phi[i]
                Lw[i, k, m] = phi[i]
    measure = _smallest_singular_value(A, piv, n, cn, rn, v, w)
    # accept: store the state (unless too near a singular configuration to predict from)
    # and write the links' angles and anchor points
    if measure >= BASE_MIN:
        for i in range(n):
            gx[nx + o + i] = gx[o + i]
            gx[o + i] = x[i]
            for m in range(M):
                gK[nx + o + i, m] = gK[o + i, m]
                gK[o + i, m] = Kw[i, m]
                for k in range(M):
                    gL[nx + o + i, m, k] = gL[o + i, m, k]
                    gL[o + i, m, k] = Lw[i, m, k]
        for m in range(M):
            gq[ng + g, m] = gq[g, m]
            gq[g, m] = q[m]
        gdet[g] = det
    for j in range(nlk):
        link = groups_i[g, 4 + j]
        a = groups_i[g, 4 + nlk + j]
        jet[a, 0] = x[3 * j]
        jet[a + 1, 0] = x[3 * j + 1]
        jet[link, 0] = x[3 * j + 2]
        for m in range(M):
            jet[a, 1 + m] = Kw[3 * j, m]
            jet[a + 1, 1 + m] = Kw[3 * j + 1, m]
            jet[link, 1 + m] = Kw[3 * j + 2, m]
            for k in range(M):
                c2 = 1 + M + m * M + k
                jet[a, c2] = Lw[3 * j, m, k]
                jet[a + 1, c2] = Lw[3 * j + 1, m, k]
                jet[link, c2] = Lw[3 * j + 2, m, k]
    return ST_OK, det, measure


# The singularity measure of a Newton group: the smallest singular value of its Jacobian A
# made dimensionless and then equilibrated.  Dimensionless: each unknown in its unit (an
# anchor's x and y in sizes of the mechanism, an angle in rad: A's columns times cu) and each
# equation in its unit (a length equation in sizes, an angle equation in rad: A's rows times
# ru), so that the matrix is the same whatever the unit the mechanism is drawn in.  Then its
# columns, then its rows, scaled to unit norm: B = diag(1 / rn) A diag(1 / cn), with cn and
# rn holding those scalings and units together.  B's smallest singular value is its distance
# to the nearest singular matrix (Eckart-Young); for a dyad it is about half the sine of the
# angle between its arms.  Estimated by inverse iteration on (B^T B)^-1 with the LU factors of
# A (B^-1 = diag(cn) A^-1 diag(rn), B^-T = diag(rn) A^-T diag(cn)): SINGULAR_STEPS steps from
# a fixed start.  Near a singular configuration, where it matters, the smallest singular value
# is far below the others and the iteration converges at once (Pyslvs' Stephenson II at its
# most singular, 0.0139: to 2e-4); elsewhere the estimate may be high, never low (up to a few
# times over the triad six-bar's cycle and Stephenson II's).


@_jit()
def _norms(c0, c1, con_i, A, n, scale, cn, rn):
    """cn, rn <- the column and row scalings of B (above), before A is factorised."""
    row = 0
    for k in range(c0, c1):                 # rn <- each equation's unit: 1 / size or 1 (rad)
        kind = con_i[k, 0]
        if kind == C_REVOLUTE:
            rn[row] = 1.0 / scale
            rn[row + 1] = 1.0 / scale
            row += 2
        elif kind == C_DRIVE_ANGLE:
            rn[row] = 1.0
            row += 1
        elif kind == C_PRISMATIC:
            rn[row] = 1.0
            rn[row + 1] = 1.0 / scale
            row += 2
        else:
            rn[row] = 1.0 / scale
            row += 1
    for j in range(n):
        cu = 1.0 if j % 3 == 2 else scale
        c = 0.0
        for i in range(n):
            t = rn[i] * A[i, j] * cu
            c += t * t
        cn[j] = math.sqrt(c) / cu if c > 0.0 else 0.0
    for i in range(n):
        r = 0.0
        for j in range(n):
            if cn[j] > 0.0:
                t = A[i, j] / cn[j]
                r += t * t
        rn[i] = math.sqrt(r)


@_jit()
def _lu_singular(A, n):
    """Whether the LU factors of A have a zero pivot (A exactly singular)."""
    for k in range(n):
        if A[k, k] == 0.0:
            return True
    return False


@_jit()
def _lu_solve_transposed(A, piv, b, n):
    """Solve A^T y = b in place with the factors of ``_lu_factor`` (P A = L U, so
    A^T = U^T L^T P): U^T s = b, L^T t = s, then the row swaps undone in reverse."""
    for i in range(n):
        t = b[i]
        for j in range(i):
            t -= A[j, i] * b[j]
        b[i] = t * A[i, i]
    for i in range(n - 1, -1, -1):
        t = b[i]
        for j in range(i + 1, n):
            t -= A[j, i] * b[j]
        b[i] = t
    for k in range(n - 1, -1, -1):
        p = piv[k]
        if p != k:
            t = b[k]
            b[k] = b[p]
            b[p] = t


@_jit()
def _smallest_singular_value(A, piv, n, cn, rn, v, w):
    """The singularity measure of a Newton group (see above), from the LU factors of A and
    the scalings ``_norms`` gave before the factorisation; v, w are scratch of length n."""
    for i in range(n):
        if cn[i] == 0.0 or rn[i] == 0.0:
            return 0.0
        v[i] = 1.0 + i / n                  # a fixed start with no special direction
    s = 0.0
    for i in range(n):
        s += v[i] * v[i]
    s = math.sqrt(s)
    for i in range(n):
        v[i] /= s
    sigma = 0.0
    for it in range(SINGULAR_STEPS):
        for i in range(n):                  # w = B^-T v = R^-1 A^-T C^-1 v
            w[i] = v[i] * cn[i]
        _lu_solve_transposed(A, piv, w, n)
        s = 0.0
        for i in range(n):
            w[i] *= rn[i]
            s += w[i] * w[i]
        s = math.sqrt(s)
        if not math.isfinite(s) or s == 0.0:
            return 0.0
        sigma = 1.0 / s                     # |B^-T v| = 1 / sigma_min for v the singular vector
        if it == SINGULAR_STEPS - 1:        # (the next v would serve no further step)
            break
        for i in range(n):                  # v = B^-1 w = C^-1 A^-1 R^-1 w, normalised
            v[i] = w[i] * rn[i]
        _lu_solve(A, piv, v, n)
        s = 0.0
        for i in range(n):
            v[i] *= cn[i]
            s += v[i] * v[i]
        s = math.sqrt(s)
        if not math.isfinite(s) or s == 0.0:
            return 0.0
        for i in range(n):
            v[i] /= s
    return min(sigma, 1.0)


# --------------------------------------------------------------------------------------
# A block of samples: run every operation of the plan on each
# --------------------------------------------------------------------------------------
BLOCK = 4   # samples evaluated side by side; their chains of square roots, divisions and
            # atan2 overlap in the processor (about a quarter faster than one at a time)


@_jit()
def _evaluate(qs, qd, qdd, lo, hi, write, ops_i, ops_f, jet, M, Kt, Kt2, Lt, groups_i, con_i,
              con_f, scale, gx, gK, gL, gq, gdet, work, piv, res, lane_f, lane_i, n_angles,
              stored, o_jet, o_rate, o_diag, o_status, o_fail):
    """Run the plan at the inputs qs[lo:hi], a block of jet.shape[0] samples at a time.

    jet (lanes, n_items, 1 + M + M*M) holds the block's samples, one per lane; lane_f
    (3, lanes) their det, measure and gap (> 0: a group cannot close), lane_i (2, lanes)
    their Newton status and first failed operation (-1: none).  Each operation runs on
    every lane of the block before the next, so that the lanes' work overlaps; a lane that
    failed runs on (its numbers are not used) except through Newton groups.  With ``write``
    each sample's status, diagnostics and (when it assembles) its jets and rates go to its
    row of the outputs.  Returns the status of the last sample, and leaves its (det,
    measure, gap, failed op) in res.  Kt, Kt2 (M,) and Lt (M, M) are scratch for the
    groups' own slides.  Newton groups keep one state (gx, ...), so a plan with them is
    evaluated one sample at a time, as continuation does.
    """
    lanes = jet.shape[0]
    status = ST_OK
    for i0 in range(lo, hi, lanes):
        nb = min(lanes, hi - i0)
        for e in range(nb):
            lane_f[0, e] = 1.0
            lane_f[1, e] = 1.0
            lane_f[2, e] = 0.0
            lane_i[0, e] = ST_OK
            lane_i[1, e] = -1
        for k in range(ops_i.shape[0]):
            op = ops_i[k, 0]
            if op == OP_FRAME_POINT:
                for e in range(nb):
                    _frame_point(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                 ops_f[k, 1], M)
            elif op == OP_RIGID_POINT:
                for e in range(nb):
                    _rigid_point(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                 ops_f[k, 1], M)
            elif op == OP_DRIVE_ANGLE:
                b, a, mi = ops_i[k, 1], ops_i[k, 2], ops_i[k, 3]
                sgn = ops_f[k, 0]
                for e in range(nb):
                    jet[e, b, 0] = (jet[e, a, 0] if a >= 0 else 0.0) + sgn * qs[i0 + e, mi]
                    for c in range(1, 1 + M + M * M):
                        jet[e, b, c] = jet[e, a, c] if a >= 0 else 0.0
                    jet[e, b, 1 + mi] += sgn
            elif op == OP_GEAR:
                out, x, y = ops_i[k, 1], ops_i[k, 2], ops_i[k, 3]
                c0, cx, cy = ops_f[k, 0], ops_f[k, 1], ops_f[k, 2]
                for e in range(nb):
                    jet[e, out, 0] = c0 + cx * jet[e, x, 0] + cy * jet[e, y, 0]
                    for c in range(1, 1 + M + M * M):
                        jet[e, out, c] = cx * jet[e, x, c] + cy * jet[e, y, c]
            elif op == OP_GEAR_SLIDE:
                x, y = ops_i[k, 4], ops_i[k, 5]
                c0, cx, cy = ops_f[k, 1], ops_f[k, 2], ops_f[k, 3]
                for e in range(nb):
                    for m in range(M):
                        Kt[m] = cx * jet[e, x, 1 + m] + cy * jet[e, y, 1 + m]
                        for n in range(M):
                            c2 = 1 + M + m * M + n
                            Lt[m, n] = cx * jet[e, x, c2] + cy * jet[e, y, c2]
                    _line_point(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                c0 + cx * jet[e, x, 0] + cy * jet[e, y, 0], Kt, Lt, M)
            elif op == OP_CAM:
                out, cam, guide, n = ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_i[k, 4]
                for e in range(nb):
                    S = _cam_motion(jet, e, ops_f, k, n, cam, guide, M, Kt, Lt)
                    jet[e, out, 0] = ops_f[k, 0] + S + (jet[e, guide, 0] if guide >= 0 else 0.0)
                    for m in range(M):
                        jet[e, out, 1 + m] = Kt[m] + (jet[e, guide, 1 + m] if guide >= 0 else 0.0)
                        for q in range(M):
                            c2 = 1 + M + m * M + q
                            jet[e, out, c2] = Lt[m, q] + (jet[e, guide, c2] if guide >= 0 else 0.0)
            elif op == OP_CAM_SLIDE:
                for e in range(nb):
                    S = _cam_motion(jet, e, ops_f, k, ops_i[k, 6], ops_i[k, 4], ops_i[k, 5], M,
                                    Kt, Lt)
                    _line_point(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                ops_f[k, 1] + S, Kt, Lt, M)
            elif op == OP_TWO_POINTS:
                for e in range(nb):
                    _two_points(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0], M)
            elif op == OP_LOCK_ANGLE:
                b, a = ops_i[k, 1], ops_i[k, 2]
                for e in range(nb):
                    jet[e, b, 0] = jet[e, a, 0] + ops_f[k, 0]
                    for c in range(1, 1 + M + M * M):
                        jet[e, b, c] = jet[e, a, c]
            elif op == OP_SLIDE_POINT:
                mi = ops_i[k, 4]
                sgn = ops_f[k, 2]
                for m in range(M):
                    Kt[m] = sgn if m == mi else 0.0
                    for n in range(M):
                        Lt[m, n] = 0.0
                for e in range(nb):
                    _line_point(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                sgn * (qs[i0 + e, mi] - ops_f[k, 1]), Kt, Lt, M)
            elif op == OP_RRR:
                for e in range(nb):
                    d, ms, gap = _rrr(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_i[k, 4],
                                      ops_i[k, 5], ops_f[k, 0], ops_f[k, 1], ops_f[k, 2],
                                      ops_f[k, 3], ops_f[k, 4], M)
                    _tally(lane_f, lane_i, e, k, d, ms, gap)
            elif op == OP_RRP:
                for e in range(nb):
                    d, ms, gap = _rrp(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_i[k, 4],
                                      ops_i[k, 5], ops_f[k, 0], ops_f[k, 1], ops_f[k, 2],
                                      ops_f[k, 3], M, Kt)
                    _tally(lane_f, lane_i, e, k, d, ms, gap)
            elif op == OP_RPR:
                for e in range(nb):
                    d, ms, gap = _rpr(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3], ops_f[k, 0],
                                      ops_f[k, 1], ops_f[k, 2], ops_f[k, 3], ops_f[k, 4], M, Kt)
                    _tally(lane_f, lane_i, e, k, d, ms, gap)
            elif op == OP_LINES:
                for e in range(nb):
                    d, ms, gap = _lines(jet, e, ops_i[k, 1], ops_i[k, 2], ops_i[k, 3],
                                        ops_i[k, 4], ops_i[k, 5], ops_f[k, 0], ops_f[k, 1], M,
                                        Kt, Kt2, Lt)
                    _tally(lane_f, lane_i, e, k, d, ms, gap)
            elif op == OP_NEWTON:
                for e in range(nb):
                    if lane_i[1, e] < 0:            # no group of this sample failed so far
                        st, d, ms = _newton_group(ops_i[k, 1], groups_i, con_i, con_f, scale,
                                                  qs[i0 + e], jet[e], gx, gK, gL, gq, gdet, M,
                                                  work, piv)
                        _tally(lane_f, lane_i, e, k, d, ms, 0.0)
                        if st != ST_OK:
                            lane_i[0, e] = st
                            lane_i[1, e] = k
            elif op == OP_SLIDE_OUT:
                sl = ops_i[k, 1]
                for e in range(nb):
                    v = _relative_slide(jet, e, ops_i[k, 2], ops_i[k, 3], ops_i[k, 4],
                                        ops_f[k, 0], M, Kt, Lt)
                    jet[e, sl, 0] = ops_f[k, 1] + v
                    for m in range(M):
                        jet[e, sl, 1 + m] = Kt[m]
                        for n in range(M):
                            jet[e, sl, 1 + M + m * M + n] = Lt[m, n]
        for e in range(nb):
            status = lane_i[0, e]
            if status == ST_OK and lane_f[2, e] > 0.0:
                status = ST_NO_ASSEMBLY
            if write:
                i = i0 + e
                _write_status(i, status, lane_f[0, e], lane_f[1, e], o_diag, o_status)
                if status == ST_OK:
                    _write_sample(i, qd, qdd, M, n_angles, stored, jet, e, o_jet, o_rate)
                else:
                    _write_failure(i, lane_f[2, e], lane_i[1, e], o_fail)
    e = (hi - lo - 1) % lanes           # the last sample, for a caller that reads res
    res[0] = lane_f[0, e]
    res[1] = lane_f[1, e]
    res[2] = lane_f[2, e]
    res[3] = lane_i[1, e]
    return status


@_jit(inline="always")
def _tally(lane_f, lane_i, e, k, d, ms, gap):
    """Account for a group (operation k) in lane e: its det multiplies the lane's, its
    measure may lower the lane's, its gap (> 0: it cannot close) may raise the lane's; the
    first operation with a gap is the one that failed, and the lane's gap is its gap (the
    operations after it run on numbers another sample left)."""
    lane_f[0, e] *= d
    lane_f[1, e] = min(lane_f[1, e], ms)
    if lane_i[1, e] < 0:
        lane_f[2, e] = max(lane_f[2, e], gap)
        if gap > 0.0:
            lane_i[1, e] = k


@_jit(inline="always")
def _write_status(i, status, det, measure, o_diag, o_status):
    """Row i of the status (an int8), of det J and of the singularity measure."""
    o_status[i] = status
    o_diag[i, 0] = det
    o_diag[i, 1] = measure


@_jit(inline="always")
def _write_failure(i, gap, failed, o_fail):
    """Row i of o_fail, only for a sample that failed: the gap (m) and the operation that
    failed.  (Callers reach it from the else of their write of a sample that assembled: a
    separate ``if`` after the status costs every sample about 13 ns.)"""
    o_fail[i, 0] = gap
    o_fail[i, 1] = failed


@_jit(inline="always")
def _write_sample(i, qd, qdd, M, n_angles, stored, jet, lane, o_jet, o_rate):
    """Copy the jets of the stored items (those the plan solves) from a lane of the block to
    row i, angles wrapped to (-pi, pi]; rates: S' = K q', S'' = K q'' + q'^T L q'.

    This is where a sweep meets memory: the inputs' rates are read once, before the items
    (a store to o_jet could alias them), and only an angle out of range is wrapped.
    """
    n = stored.shape[0]
    r = i if qd.shape[0] > 1 else 0         # the rates: one row per sample, or one for all
    rr = i if qdd.shape[0] > 1 else 0
    if M == 1:
        w = qd[r, 0]
        wd = qdd[rr, 0]
        ww = w * w
        for j in range(n):
            it = stored[j]
            k1 = jet[lane, it, 1]
            l1 = jet[lane, it, 2]
            t = jet[lane, it, 0]
            if it < n_angles and not -math.pi < t <= math.pi:
                t = _wrapped(t)
            o_jet[i, j, 0] = t
            o_jet[i, j, 1] = k1
            o_jet[i, j, 2] = l1
            o_rate[i, j, 0] = k1 * w
            o_rate[i, j, 1] = k1 * wd + l1 * ww
        return
    for j in range(n):
        it = stored[j]
        t = jet[lane, it, 0]
        if it < n_angles and not -math.pi < t <= math.pi:
            t = _wrapped(t)
        o_jet[i, j, 0] = t
        v = 0.0
        a = 0.0
        for m in range(M):
            km = jet[lane, it, 1 + m]
            o_jet[i, j, 1 + m] = km
            v += km * qd[r, m]
            a += km * qdd[rr, m]
            for n_ in range(M):
                lmn = jet[lane, it, 1 + M + m * M + n_]
                o_jet[i, j, 1 + M + m * M + n_] = lmn
                a += lmn * qd[r, m] * qd[r, n_]
        o_rate[i, j, 0] = v
        o_rate[i, j, 1] = a


@_jit()
def _wrapped(t):
    """An angle in (-pi, pi], as :func:`kinelab.solvers.wrap_angle`."""
    return t - 2.0 * math.pi * math.ceil((t - math.pi) / (2.0 * math.pi))


@_jit()
def _new_jet(lanes, n_items, M, const_items, const_values):
    jet = np.zeros((lanes, n_items, 1 + M + M * M))
    for e in range(lanes):
        for j in range(const_items.shape[0]):
            jet[e, const_items[j], 0] = const_values[j]
    return jet


@_jit()
def _closed_form(q, qd, qdd, lo, hi, ops_i, ops_f, const_items, const_values, n_items,
                 n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, M):
    """Samples lo:hi of a plan without Newton groups, with their own scratch state."""
    jet = _new_jet(BLOCK, n_items, M, const_items, const_values)
    Kt = np.zeros(M)
    Kt2 = np.zeros(M)
    Lt = np.zeros((M, M))
    res = np.zeros(4)
    lane_f = np.zeros((3, BLOCK))
    lane_i = np.zeros((2, BLOCK), np.int64)
    gi = np.zeros((1, 8), np.int64)      # no Newton group: empty stand-ins
    gf = np.zeros((1, 8))
    g1 = np.zeros(1)
    g2 = np.zeros((1, M))
    g3 = np.zeros((1, M, M))
    piv = np.zeros(1, np.int64)
    _evaluate(q, qd, qdd, lo, hi, True, ops_i, ops_f, jet, M, Kt, Kt2, Lt, gi, gi, gf, 1.0,
              g1, g2, g3, g2, g1, g1, piv, res, lane_f, lane_i, n_angles, stored, o_jet,
              o_rate, o_diag, o_status, o_fail)


# The entry points run without the GIL, so that Python threads can share a sweep's samples.
# Each comes twice: for any number of inputs M, and with M = 1 compiled in as a constant
# (the common case), which lets the loops over inputs unroll.  They take D designs of one
# plan at once: design d has its own numbers (ops_f[d], const_values[d] ...) and its own
# samples, the rows starts[d]:starts[d + 1] of q and of the outputs; one design is D = 1.

@_jit()
def _closed_form_designs(q, qd, qdd, starts, d0, d1, ops_i, ops_f, const_items, const_values,
                         n_items, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, M):
    for d in range(d0, d1):
        _closed_form(q, qd, qdd, starts[d], starts[d + 1], ops_i, ops_f[d], const_items,
                     const_values[d], n_items, n_angles, stored, o_jet, o_rate, o_diag,
                     o_status, o_fail, M)


@_jit(nogil=True)
def run_closed_form(q, qd, qdd, starts, d0, d1, ops_i, ops_f, const_items, const_values,
                    n_items, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, M):
    """Evaluate designs d0:d1 of a plan without Newton groups (samples are independent).

    ops_f (D, n_ops, 8) and const_values (D, n_const) per design; o_jet (N, len(stored),
    1 + M + M*M) and o_rate (N, len(stored), 2) for the items listed in ``stored``; o_diag
    (N, 2): det, measure; o_fail (N, 2): gap, failed operation (only where the status is not
    ST_OK); M = q.shape[1].
    """
    _closed_form_designs(q, qd, qdd, starts, d0, d1, ops_i, ops_f, const_items, const_values,
                         n_items, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, M)


@_jit(nogil=True)
def run_closed_form_one_input(q, qd, qdd, starts, d0, d1, ops_i, ops_f, const_items,
                              const_values, n_items, n_angles, stored, o_jet, o_rate, o_diag,
                              o_status, o_fail):
    """:func:`run_closed_form` for one input."""
    _closed_form_designs(q, qd, qdd, starts, d0, d1, ops_i, ops_f, const_items, const_values,
                         n_items, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, 1)


@_jit()
def run_small_one_input(q, qd, qdd, limit, ops_i, ops_f, const_items, const_values, n_items,
                        n_angles, stored, tol, o_q, o_jet, o_rate, o_diag, o_status, o_fail,
                        o_assembled, o_singular):
    """A sweep of one input at constant rates on the calling thread, as ``analyze`` takes
    most: the inputs q (N,) checked (each within ``limit`` in size; else nothing more is
    done, and the caller checks them in full) and copied to o_q (N, 1), the samples run
    (:func:`_closed_form`, as :func:`run_closed_form_one_input` runs them) into the outputs
    o_jet ... o_fail, and the samples that assemble and those below the singularity measure
    ``tol`` marked (o_assembled, o_singular, (N,) bool).  Returns (inputs checked, how many
    samples do not assemble, how many are singular)."""
    N = q.shape[0]
    for i in range(N):
        o_q[i, 0] = q[i]
        if not abs(q[i]) <= limit:             # NaN too
            return False, 0, 0
    qd2 = np.full((1, 1), qd)
    qdd2 = np.full((1, 1), qdd)
    _closed_form(o_q, qd2, qdd2, 0, N, ops_i, ops_f, const_items, const_values, n_items,
                 n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail, 1)
    failed = 0
    flagged = 0
    for i in range(N):
        ok = o_status[i] == ST_OK
        o_assembled[i] = ok
        o_singular[i] = ok and o_diag[i, 1] < tol
        failed += not ok
        flagged += o_singular[i]
    return True, failed, flagged


@njit(cache=True, error_model="numpy")     # no contraction: numpy's arithmetic, to the bit
def driven_angles(q, m, sign, out):
    """The angles of a link turned by input m from the ground with the sign ``sign``:
    ``out[i] = solvers.wrap_angle(q[i, m] * sign)`` to the bit, in numpy's steps (an angle
    in (-pi, pi] as it is, else ``np.remainder(t + pi, 2 pi) - pi``, -pi written pi; a
    float's ``%`` is that remainder: fmod's, with the divisor added where the signs
    differ, +0 for 0).  Within a turn either way the remainder takes one subtraction or
    addition, as ``solvers.wrapped_angles`` takes it (fmod's loop is slow)."""
    two_pi = 2.0 * math.pi
    for i in range(q.shape[0]):
        t = q[i, m] * sign
        if -math.pi < t <= math.pi:
            out[i] = t
            continue
        x = t + math.pi
        if 0.0 <= x < two_pi:
            r = x
        elif two_pi <= x < 2.0 * two_pi:
            r = x - two_pi                         # exact, as fmod is
        elif -two_pi < x < 0.0:
            r = x + two_pi
        else:
            r = x % two_pi
        w = r - math.pi
        out[i] = math.pi if w == -math.pi else w
    return out


@_jit()
def one_sample_scratch(plan_i, plan_f, M):
    """What :func:`evaluate_one_sample` needs of a plan packed by :func:`pack_plan` (views of
    plan_i and plan_f) and the scratch space of its samples: made once for a run of samples
    one at a time, so that each sample allocates nothing."""
    n_items, n_angles, n_ops, wi, wf, nc, ns = plan_i[0], plan_i[1], plan_i[2], plan_i[3], \
        plan_i[4], plan_i[5], plan_i[6]
    a = HEADER + n_ops * wi
    ops_i = plan_i[HEADER:a].reshape((n_ops, wi))
    const_items = plan_i[a:a + nc]
    stored = plan_i[a + nc:a + nc + ns]
    ops_f = plan_f[:n_ops * wf].reshape((n_ops, wf))
    const_values = plan_f[n_ops * wf:n_ops * wf + nc]
    jet = _new_jet(1, n_items, M, const_items, const_values)
    return (ops_i, ops_f, stored, n_angles, jet, np.zeros(M), np.zeros(M), np.zeros((M, M)),
            np.zeros(4), np.zeros((3, 1)), np.zeros((2, 1), np.int64),
            np.zeros((1, 8), np.int64), np.zeros((1, 8)), np.zeros(1), np.zeros((1, M)),
            np.zeros((1, M, M)), np.zeros(1, np.int64), np.zeros(1, np.int8))


@_jit(inline="always")
def evaluate_one_sample(x, scratch, out, M):
    """Evaluate one sample of a plan without Newton groups: x (3, M) holds q, q' and q'';
    ``scratch`` comes from :func:`one_sample_scratch`, ``out`` is laid out as
    :func:`one_sample_layout` says.  Returns the status."""
    (ops_i, ops_f, stored, n_angles, jet, Kt, Kt2, Lt, res, lane_f, lane_i, gi, gf, g1, g2, g3,
     piv, o_status) = scratch
    ns = stored.shape[0]
    w = 1 + M + M * M
    r = ns * w
    o_jet = out[:r].reshape((1, ns, w))
    o_rate = out[r:r + 2 * ns].reshape((1, ns, 2))
    o_diag = out[r + 2 * ns:r + 2 * ns + 2].reshape((1, 2))
    o_fail = out[r + 2 * ns + 2:r + 2 * ns + 4].reshape((1, 2))
    st = _evaluate(x[0:1], x[1:2], x[2:3], 0, 1, True, ops_i, ops_f, jet, M, Kt, Kt2, Lt, gi,
                   gi, gf, 1.0, g1, g2, g3, g2, g1, g1, piv, res, lane_f, lane_i, n_angles,
                   stored, o_jet, o_rate, o_diag, o_status, o_fail)
    out[r + 2 * ns + 4] = st
    return st


# A tracker (``_tracker.py``) asks for one sample at a time, each call a few microseconds:
# its plan is packed with the scratch space of its samples (``_codes.pack_tracked``), in
# two 2-D arrays whose blocks the kernel takes by slicing (a reshape costs a call), so that
# a call allocates nothing; its one input comes as three numbers.  These entry points hold
# the GIL: two threads cannot share that space.

@_jit(inline="always")
def _tracked(ints, floats, out, M):
    """Evaluate the sample in the scratch space's x (3, M) of a plan packed by
    ``_codes.pack_tracked``; ``out`` is laid out as ``_codes.tracked_layout`` says.
    Returns the singularity measure, or -1.0 where the sample does not assemble."""
    n_items, n_angles, n_ops, wi, wf, ns = ints[0, 0], ints[0, 1], ints[0, 2], ints[0, 3], \
        ints[0, 4], ints[0, 5]
    w = 1 + M + M * M
    ops_i = ints[1:1 + n_ops, 0:wi]
    stored = ints[1 + n_ops, 0:ns]
    lane_i = ints[2 + n_ops:4 + n_ops, 0:1]
    o_status = ints[4 + n_ops, 0:1]
    ops_f = floats[0:n_ops, 0:wf]
    jet = floats[n_ops:n_ops + n_items, 0:w][None]
    r = n_ops + n_items                     # then res, lane_f (3, 1), Kt, Kt2, Lt (M, M), x (3, M)
    res = floats[r, 0:4]
    lane_f = floats[r + 1:r + 4, 0:1]
    Kt = floats[r + 4, 0:M]
    Kt2 = floats[r + 5, 0:M]
    Lt = floats[r + 6:r + 6 + M, 0:M]
    x = floats[r + 6 + M:r + 9 + M, 0:M]
    o = out.reshape((2 * ns + 2, w))
    o_jet = o[0:ns][None]
    o_rate = o[ns:2 * ns, 0:2][None]
    o_diag = o[2 * ns:2 * ns + 1, 0:2]
    o_fail = o[2 * ns + 1:2 * ns + 2, 0:2]
    # the arrays of Newton groups, which a closed-form plan never touches, stand in as arrays
    # of their kinds already at hand: each view made here costs the call its reference count
    st = _evaluate(x, x[1:2], x[2:3], 0, 1, True, ops_i, ops_f, jet, M, Kt, Kt2, Lt, ints,
                   ints, floats, 1.0, out, floats, jet, floats, out, out, stored, res, lane_f,
                   lane_i, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail)
    o[2 * ns + 1, 2] = st
    return o[2 * ns, 1] if st == ST_OK else -1.0


@_jit()
def run_tracked_one_input(q, qd, qdd, ints, floats, out):
    """One sample of a plan without Newton groups and with one input, packed with its
    scratch space by ``_codes.pack_tracked``: the input q, its rates qd and qdd.  ``out`` is
    laid out as ``_codes.tracked_layout`` says.  Returns the singularity measure, or -1.0
    where the sample does not assemble."""
    r = ints[0, 2] + ints[0, 0] + 7                    # x, after the scratch (see _tracked)
    floats[r, 0] = q
    floats[r + 1, 0] = qd
    floats[r + 2, 0] = qdd
    return _tracked(ints, floats, out, 1)


@_jit()
def run_tracked(x, ints, floats, out):
    """:func:`run_tracked_one_input` for M inputs: x (3, M) holds q, q' and q''."""
    M = x.shape[1]
    r = ints[0, 2] + ints[0, 0] + 6 + M
    floats[r:r + 3, 0:M] = x
    return _tracked(ints, floats, out, M)


@_jit()
def _continuation(q, qd, qdd, q_start, q_unit, ops_i, ops_f, const_items, const_values,
                  n_items, n_angles, stored, groups_i, con_i, con_f, grp_x0, scale,
                  o_jet, o_rate, o_diag, o_status, o_fail, o_state, M):
    """Evaluate a plan with Newton groups, following the samples in order from a start.

    The start is the groups' state ``grp_x0`` at input ``q_start`` (the sketch, or where an
    earlier run ended).  Each step from the previous input to the next is split so that no
    step exceeds CONTINUATION_STEP (Euclidean, each input in its unit ``q_unit``: rad, or the
    mechanism's size for a slide), and halved again while a Newton
    group fails to converge or jumps (its correction is large against the predicted step).
    On return ``o_state`` holds the groups' state and the input where the run ended.
    """
    N = q.shape[0]
    ng = groups_i.shape[0]
    nx = grp_x0.shape[0]
    nmax = 1
    for g in range(ng):
        nmax = max(nmax, 3 * groups_i[g, 1])
    jet = _new_jet(1, n_items, M, const_items, const_values)     # one sample at a time
    Kt = np.zeros(M)
    Kt2 = np.zeros(M)
    Lt = np.zeros((M, M))
    res = np.zeros(4)
    lane_f = np.zeros((3, 1))
    lane_i = np.zeros((2, 1), np.int64)
    # the groups' state (gx, gK, gL, gq, gdet: see ``_newton_group``), as views of one array
    # that is copied whole: the last state and the one before it, whose input is NaN (none)
    size = 2 * nx * (1 + M + M * M) + 2 * ng * M + ng
    state = np.zeros(size)
    gx = state[:2 * nx]
    gK = state[2 * nx:2 * nx * (1 + M)].reshape((2 * nx, M))
    gL = state[2 * nx * (1 + M):2 * nx * (1 + M + M * M)].reshape((2 * nx, M, M))
    gq = state[2 * nx * (1 + M + M * M):size - ng].reshape((2 * ng, M))
    gdet = state[size - ng:]
    gx[:nx] = grp_x0
    gq[:, :] = np.nan
    before = state.copy()       # before a step, to go back to should it fail
    clear = state.copy()        # on the current sample's path, well clear of it
    work = np.zeros(nmax * nmax + 3 * nmax + nmax * M + nmax * M * M + 5 * nmax)
    piv = np.zeros(nmax, np.int64)
    jet_b = np.empty_like(jet)
    for g in range(ng):
        for m in range(M):
            gq[g, m] = q_start[m]
    qt = q_start.copy().reshape((1, M))
    qprev = q_start.copy()
    # the sketch itself: the groups converge at once and get their K and L
    st0 = _evaluate(qt, qd, qdd, 0, 1, False, ops_i, ops_f, jet, M, Kt, Kt2, Lt, groups_i,
                    con_i, con_f, scale, gx, gK, gL, gq, gdet, work, piv, res, lane_f, lane_i,
                    n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail)
    if st0 != ST_OK:
        for i in range(N):
            _write_status(i, st0, res[0], res[1], o_diag, o_status)
            _write_failure(i, res[2], res[3], o_fail)
        o_state[:nx] = grp_x0
        o_state[nx:] = q_start
        return
    max_step = CONTINUATION_STEP
    for i in range(N):
        dist = 0.0
        for m in range(M):
            dist += ((q[i, m] - qprev[m]) / q_unit[m]) ** 2
        dist = math.sqrt(dist)
        h = 1.0
        if dist > max_step:
            h = max_step / dist
        t = 0.0
        st = ST_OK
        clear[:] = state
        while t < 1.0:
            tt = min(1.0, t + h)
            for m in range(M):
                qt[0, m] = qprev[m] + tt * (q[i, m] - qprev[m])
            before[:] = state
            st = _evaluate(qt, qd, qdd, 0, 1, False, ops_i, ops_f, jet, M, Kt, Kt2, Lt, groups_i,
                           con_i, con_f, scale, gx, gK, gL, gq, gdet, work, piv, res, lane_f,
                           lane_i, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail)
            if st == ST_OK:
                t = tt
                h = min(2.0 * h, max_step / dist) if dist > 0.0 else 1.0
                if (1.0 - t) * dist >= 10.0 * NODE_STEP * max_step:
                    clear[:] = state    # still well clear of the sample: a state to place
                                        # it from, should it sit on a singular configuration
            else:
                state[:] = before
                if st == ST_NO_ASSEMBLY or h < 1e-9:
                    break
                h *= 0.5
        if st != ST_OK and dist > 0.0 and (1.0 - t) * dist <= 0.1 * NODE_STEP * max_step:
            # stopped right at the sample: a singular configuration the motion passes.  Its
            # place comes from either side, predicted from a state well clear of it (those
            # next to it are too near the singularity to predict from)
            state[:] = clear
            eps = NODE_STEP * max_step / dist
            if _place_between(q, i, qprev, eps, qt, jet, jet_b, qd, qdd, ops_i, ops_f, M, Kt,
                              Kt2, Lt, groups_i, con_i, con_f, scale, gx, gK, gL, gq, gdet,
                              work, piv, res, lane_f, lane_i, n_angles, stored, o_jet, o_rate,
                              o_diag, o_status, o_fail):
                st = ST_OK
                t = 1.0
                res[0] = 0.0
                res[1] = 0.0
        _write_status(i, st, res[0], res[1], o_diag, o_status)
        if st == ST_OK:
            _write_sample(i, qd, qdd, M, n_angles, stored, jet, 0, o_jet, o_rate)
        else:
            _write_failure(i, res[2], res[3], o_fail)
        # the next sample starts where the mechanism last assembled
        for m in range(M):
            qprev[m] = qprev[m] + t * (q[i, m] - qprev[m])
    o_state[:nx] = gx[:nx]
    o_state[nx:] = qprev


@_jit()
def _place_between(q, i, qprev, eps, qt, jet, jet_b, qd, qdd, ops_i, ops_f, M, Kt, Kt2, Lt,
                   groups_i, con_i, con_f, scale, gx, gK, gL, gq, gdet, work, piv, res, lane_f,
                   lane_i, n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail):
    """Place sample i, on a singular configuration that the motion passes (where Newton's
    method cannot converge), from the motion a little before and after it: the mean of the
    second-order predictions S + K dq + 1/2 dq L dq from both sides (their errors in dq**3
    cancel), angles averaged across their wrap.  Returns whether both sides were solved;
    then jet (lane 0) holds the sample's values (its K and L mean nothing: it is singular)."""
    ni = jet.shape[1]
    for side in range(2):
        sgn = -1.0 if side == 0 else 1.0
        for m in range(M):
            qt[0, m] = q[i, m] + sgn * eps * (q[i, m] - qprev[m])
        st = _evaluate(qt, qd, qdd, 0, 1, False, ops_i, ops_f, jet, M, Kt, Kt2, Lt, groups_i,
                       con_i, con_f, scale, gx, gK, gL, gq, gdet, work, piv, res, lane_f, lane_i,
                       n_angles, stored, o_jet, o_rate, o_diag, o_status, o_fail)
        if st != ST_OK:
            return False
        for it in range(ni):            # predict to the sample from this side
            v = jet[0, it, 0]
            for m in range(M):
                dm = q[i, m] - qt[0, m]
                v += jet[0, it, 1 + m] * dm
                for k in range(M):
                    v += 0.5 * jet[0, it, 1 + M + m * M + k] * dm * (q[i, k] - qt[0, k])
            if side == 0:
                jet_b[0, it, 0] = v
            else:
                before = jet_b[0, it, 0]
                if it < n_angles:
                    v = before + _wrapped(v - before)
                jet[0, it, 0] = 0.5 * (before + v)
    return True


@_jit()
def _continuation_designs(q, qd, qdd, starts, q_start, q_unit, ops_i, ops_f, const_items,
                          const_values, n_items, n_angles, stored, groups_i, con_i, con_f,
                          grp_x0, scale, o_jet, o_rate, o_diag, o_status, o_fail, o_state, M):
    for d in range(starts.shape[0] - 1):
        lo = starts[d]
        hi = starts[d + 1]
        _continuation(q[lo:hi], qd if qd.shape[0] == 1 else qd[lo:hi],
                      qdd if qdd.shape[0] == 1 else qdd[lo:hi], q_start[d], q_unit[d], ops_i,
                      ops_f[d], const_items, const_values[d], n_items, n_angles, stored,
                      groups_i, con_i, con_f[d], grp_x0[d], scale[d], o_jet[lo:hi],
                      o_rate[lo:hi], o_diag[lo:hi], o_status[lo:hi], o_fail[lo:hi], o_state[d],
                      M)


@_jit(nogil=True)
def run_continuation(q, qd, qdd, starts, q_start, q_unit, ops_i, ops_f, const_items,
                     const_values, n_items, n_angles, stored, groups_i, con_i, con_f, grp_x0,
                     scale, o_jet, o_rate, o_diag, o_status, o_fail, o_state, M):
    """Evaluate the designs of a plan with Newton groups along their samples (see
    ``_continuation``): design d from its own start (q_start[d], grp_x0[d]) with its own
    numbers (ops_f[d], const_values[d], con_f[d], scale[d], its inputs' units q_unit[d]);
    its end state goes to o_state[d]."""
    _continuation_designs(q, qd, qdd, starts, q_start, q_unit, ops_i, ops_f, const_items,
                          const_values, n_items, n_angles, stored, groups_i, con_i, con_f,
                          grp_x0, scale, o_jet, o_rate, o_diag, o_status, o_fail, o_state, M)


@_jit(nogil=True)
def run_continuation_one_input(q, qd, qdd, starts, q_start, q_unit, ops_i, ops_f, const_items,
                               const_values, n_items, n_angles, stored, groups_i, con_i, con_f,
                               grp_x0, scale, o_jet, o_rate, o_diag, o_status, o_fail, o_state):
    """:func:`run_continuation` for one input."""
    _continuation_designs(q, qd, qdd, starts, q_start, q_unit, ops_i, ops_f, const_items,
                          const_values, n_items, n_angles, stored, groups_i, con_i, con_f,
                          grp_x0, scale, o_jet, o_rate, o_diag, o_status, o_fail, o_state, 1)
