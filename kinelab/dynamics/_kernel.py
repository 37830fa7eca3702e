"""The compiled forward dynamics: Kane's equations of a closed-form plan, integrated by
Dormand and Prince's 8(5,3) method one run after another, without Python in the loop.

The right-hand side of one run at (t, q, q') runs the kinematics kernel on the plan
(``evaluate_one_sample``: every item's value, K and the velocity terms ``q'^T L q'``), forms
the mass matrix ``sum w K^T K`` and the bias ``sum w K^T (q'^T L q')`` over the
coordinates with inertia, adds the generalised forces of gravity, point forces, torques,
springs and dampers (``K^T F``), evaluates the actuator laws, and solves for q''.  Laws
given as expressions run as programs of a small stack machine (see
:func:`kinelab._expressions.to_program`), so one compiled kernel serves every model.

The integrator is scipy's DOP853 (the same tableau, read from
:class:`scipy.integrate.DOP853`, the same initial step, step control and dense output),
with the error measured on q and q' only: the work of the actuators and loads and the
dampers' losses are carried as quadratures that do not steer the steps.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853

from kinelab import _expressions as ex
from kinelab.dynamics._codes import (FAIL_ASSEMBLY, FAIL_BUDGET, FAIL_DIVERGED,  # noqa: F401
                                     FAIL_LAW, FAIL_MASS, FAIL_PACE, FAIL_SINGULAR, FAIL_SPRING,
                                     FAIL_STEP, PACE_CHECK, PACE_MARGIN, RUN_FINISHED,
                                     RUN_SINGULAR)
from kinelab.kinematics import _kernel as kin
from kinelab.kinematics._codes import HEADER, OP_SLIDE_POINT, SINGULAR_TOL
from kinelab.kinematics._kernel import (_jit, _lu_factor, _lu_solve, evaluate_one_sample,
                                        one_sample_scratch)

# numba's cache of this file knows its text only: the digest of the files whose constants and
# functions it compiles in (kinelab._compiled.compiled_from; a test keeps it true)
COMPILED_FROM = "dc37dcd54de40a4d"

_A = np.ascontiguousarray(DOP853.A, dtype=np.float64)
_B = np.ascontiguousarray(DOP853.B, dtype=np.float64)
_C = np.ascontiguousarray(DOP853.C, dtype=np.float64)
_E3 = np.ascontiguousarray(DOP853.E3, dtype=np.float64)
_E5 = np.ascontiguousarray(DOP853.E5, dtype=np.float64)
_D = np.ascontiguousarray(DOP853.D, dtype=np.float64)
_A_EXTRA = np.ascontiguousarray(DOP853.A_EXTRA, dtype=np.float64)
_C_EXTRA = np.ascontiguousarray(DOP853.C_EXTRA, dtype=np.float64)
_STAGES = DOP853.n_stages                           # 12
_ERROR_EXPONENT = -1.0 / (DOP853.error_estimator_order + 1)
_SAFETY, _MIN_FACTOR, _MAX_FACTOR = 0.9, 0.2, 10.0  # scipy's step control

# the functions of a program, by their index in PROGRAM_FUNCTIONS
_FN = {name: i for i, name in enumerate(ex.PROGRAM_FUNCTIONS)}
(F_SIN, F_COS, F_TAN, F_ASIN, F_ACOS, F_ATAN, F_ATAN2, F_SINH, F_COSH, F_TANH, F_EXP, F_LOG,
 F_LOG10, F_SQRT, F_ABS, F_SIGN, F_FLOOR, F_CEIL, F_MIN, F_MAX, F_HYPOT, F_CLIP) = (
    _FN[n] for n in ("sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
                     "exp", "log", "log10", "sqrt", "abs", "sign", "floor", "ceil", "min", "max",
                     "hypot", "clip"))
OP_CONST, OP_T, OP_Q, OP_QD = ex.OP_CONST, ex.OP_T, ex.OP_Q, ex.OP_QD
OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_MOD = (ex.OP_ADD, ex.OP_SUB, ex.OP_MUL, ex.OP_DIV,
                                                  ex.OP_POW, ex.OP_MOD)
OP_NEG, OP_NOT, OP_AND, OP_OR = ex.OP_NEG, ex.OP_NOT, ex.OP_AND, ex.OP_OR
OP_LT, OP_LE, OP_GT, OP_GE, OP_EQ, OP_NE = ex.OP_LT, ex.OP_LE, ex.OP_GT, ex.OP_GE, ex.OP_EQ, ex.OP_NE
OP_WHERE, OP_FUNCTION = ex.OP_WHERE, ex.OP_FUNCTION


@_jit()
def _pair(a, b):
    """numpy's minimum / maximum propagate a NaN."""
    return a != a or b != b


@_jit()
def run_law(code, constants, lo, hi, t, q, qd, stack):
    """Value of the program ``code[lo:hi]`` at (t, q, q'), numpy's arithmetic."""
    sp = 0
    for i in range(lo, hi):
        op = code[i, 0]
        arg = code[i, 1]
        if op == OP_CONST:
            stack[sp] = constants[arg]
            sp += 1
            continue
        if op == OP_T:
            stack[sp] = t
            sp += 1
            continue
        if op == OP_Q:
            stack[sp] = q[arg]
            sp += 1
            continue
        if op == OP_QD:
            stack[sp] = qd[arg]
            sp += 1
            continue
        if op == OP_NEG:
            stack[sp - 1] = -stack[sp - 1]
            continue
        if op == OP_NOT:
            stack[sp - 1] = 1.0 if stack[sp - 1] == 0.0 else 0.0
            continue
        if op == OP_WHERE:
            sp -= 2
            stack[sp - 1] = stack[sp] if stack[sp - 1] != 0.0 else stack[sp + 1]
            continue
        if op == OP_FUNCTION:
            x = stack[sp - 1]
            if arg == F_SIN:
                v = np.sin(x)
            elif arg == F_COS:
                v = np.cos(x)
            elif arg == F_TAN:
                v = np.tan(x)
            elif arg == F_ASIN:
                v = np.arcsin(x)
            elif arg == F_ACOS:
                v = np.arccos(x)
            elif arg == F_ATAN:
                v = np.arctan(x)
            elif arg == F_SINH:
                v = np.sinh(x)
            elif arg == F_COSH:
                v = np.cosh(x)
            elif arg == F_TANH:
                v = np.tanh(x)
            elif arg == F_EXP:
                v = np.exp(x)
            elif arg == F_LOG:
                v = np.log(x)
            elif arg == F_LOG10:
                v = np.log10(x)
            elif arg == F_SQRT:
                v = np.sqrt(x)
            elif arg == F_ABS:
                v = np.abs(x)
            elif arg == F_SIGN:
                v = np.sign(x)
            elif arg == F_FLOOR:
                v = np.floor(x)
            elif arg == F_CEIL:
                v = np.ceil(x)
            elif arg == F_CLIP:           # clip(x, lo, hi): minimum(maximum(x, lo), hi)
                sp -= 2
                a, lo_, hi_ = stack[sp - 1], stack[sp], stack[sp + 1]
                m = np.nan if _pair(a, lo_) else max(a, lo_)
                v = np.nan if _pair(m, hi_) else min(m, hi_)
            else:                         # two arguments
                sp -= 1
                a, b = stack[sp - 1], stack[sp]
                if arg == F_ATAN2:
                    v = np.arctan2(a, b)
                elif arg == F_HYPOT:
                    v = np.hypot(a, b)
                elif arg == F_MIN:
                    v = np.nan if _pair(a, b) else min(a, b)
                else:
                    v = np.nan if _pair(a, b) else max(a, b)
            stack[sp - 1] = v
            continue
        sp -= 1                           # a binary operator
        a, b = stack[sp - 1], stack[sp]
        if op == OP_ADD:
            v = a + b
        elif op == OP_SUB:
            v = a - b
        elif op == OP_MUL:
            v = a * b
        elif op == OP_DIV:
            v = a / b
        elif op == OP_POW:
            v = np.power(a, b)
        elif op == OP_MOD:
            v = np.mod(a, b)
        elif op == OP_AND:
            v = 1.0 if (a != 0.0 and b != 0.0) else 0.0
        elif op == OP_OR:
            v = 1.0 if (a != 0.0 or b != 0.0) else 0.0
        elif op == OP_LT:
            v = 1.0 if a < b else 0.0
        elif op == OP_LE:
            v = 1.0 if a <= b else 0.0
        elif op == OP_GT:
            v = 1.0 if a > b else 0.0
        elif op == OP_GE:
            v = 1.0 if a >= b else 0.0
        elif op == OP_EQ:
            v = 1.0 if a == b else 0.0
        else:
            v = 1.0 if a != b else 0.0
        stack[sp - 1] = v
    return stack[0]


@_jit()
def _law(code, constants, starts, k, t, q, qd, stack, info):
    """Law k of a system's programs (0.0 for k < 0); a value that is not finite fails the
    run.  (The programs come as three arrays, not in the system's tuple: each array passed
    costs the call its reference counting.)"""
    if k < 0:
        return 0.0
    v = run_law(code, constants, starts[k], starts[k + 1], t, q, qd, stack)
    if not np.isfinite(v):
        info[1] = k
    return v


@_jit()
def _rhs(t, y, dy, M, system, work, sample, info):
    """dy/dt of one run at (t, y), y = (q, q', actuator work, applied work, dissipated);
    returns a status (0: fine).  ``info[0]`` gets the singularity measure.  ``sample`` is
    the kinematics' scratch (``one_sample_scratch``), made once per run."""
    (_, _, ns, scale, mass_rows, mass_w, mass_g, force_rows, force_laws, torque_rows,
     torque_laws, spring_rows, spring_k, spring_l0, spring_c, code, constants, starts,
     actuator_laws) = system
    x, out, MM, piv, b, stack = work
    for m in range(2 * M):
        if not np.isfinite(y[m]):
            return FAIL_DIVERGED
    for m in range(M):
        x[0, m] = y[m]
        x[1, m] = y[M + m]
        x[2, m] = 0.0
    status = evaluate_one_sample(x, sample, out, M)
    w = 1 + M + M * M
    r = ns * w                                      # rates start here, then diag
    info[0] = out[r + 2 * ns + 1]
    if status != kin.ST_OK:
        return FAIL_ASSEMBLY
    if out[r + 2 * ns + 1] < SINGULAR_TOL:      # what analyze flags singular
        return FAIL_SINGULAR
    q = y[:M]
    qd = y[M:2 * M]
    # M q'' = tau + Q - h: inertia of every coordinate with mass or inertia, and its weight
    for i in range(M):
        b[i] = 0.0
        for j in range(M):
            MM[i, j] = 0.0
    for c in range(mass_rows.shape[0]):
        row = mass_rows[c]
        bias = out[r + 2 * row + 1]                 # acceleration at q'' = 0: q'^T L q'
        for i in range(M):
            Ki = out[row * w + 1 + i]
            b[i] += Ki * (mass_g[c] - mass_w[c] * bias)
            for j in range(M):
                MM[i, j] += mass_w[c] * Ki * out[row * w + 1 + j]
    power = 0.0
    info[1] = -1.0
    for f in range(force_rows.shape[0]):
        row = force_rows[f]
        for d in range(2):
            F = _law(code, constants, starts, force_laws[f, d], t, q, qd, stack, info)
            power += F * out[r + 2 * (row + d)]
            for i in range(M):
                b[i] += F * out[(row + d) * w + 1 + i]
    for k in range(torque_rows.shape[0]):
        T = _law(code, constants, starts, torque_laws[k], t, q, qd, stack, info)
        own, other = torque_rows[k, 0], torque_rows[k, 1]
        power += T * out[r + 2 * own]
        for i in range(M):
            b[i] += T * out[own * w + 1 + i]
        if other >= 0:
            power -= T * out[r + 2 * other]
            for i in range(M):
                b[i] -= T * out[other * w + 1 + i]
    lost = 0.0
    for s in range(spring_rows.shape[0]):
        ra, rb = spring_rows[s, 0], spring_rows[s, 1]
        dx = out[rb * w] - out[ra * w]
        dyy = out[(rb + 1) * w] - out[(ra + 1) * w]
        length = np.sqrt(dx * dx + dyy * dyy)
        if length <= 1e-12 * scale:
            return FAIL_SPRING
        ex_, ey = dx / length, dyy / length
        rate = (ex_ * (out[r + 2 * rb] - out[r + 2 * ra])
                + ey * (out[r + 2 * (rb + 1)] - out[r + 2 * (ra + 1)]))
        tension = spring_k[s] * (length - spring_l0[s]) + spring_c[s] * rate
        lost += spring_c[s] * rate * rate
        for i in range(M):
            dl = (ex_ * (out[rb * w + 1 + i] - out[ra * w + 1 + i])
                  + ey * (out[(rb + 1) * w + 1 + i] - out[(ra + 1) * w + 1 + i]))
            b[i] -= tension * dl
    actuator_power = 0.0
    for i in range(M):
        tau = _law(code, constants, starts, actuator_laws[i], t, q, qd, stack, info)
        b[i] += tau
        actuator_power += tau * qd[i]
    if info[1] >= 0:
        return FAIL_LAW
    if _lu_factor(MM, piv, M) == 0.0:
        return FAIL_MASS
    _lu_solve(MM, piv, b, M)
    for i in range(M):
        dy[i] = qd[i]
        dy[M + i] = b[i]
    dy[2 * M] = actuator_power
    dy[2 * M + 1] = power
    dy[2 * M + 2] = lost
    return 0


@_jit()
def _rms(v, scale, nq):
    s = 0.0
    for i in range(nq):
        e = v[i] / scale[i]
        s += e * e
    return np.sqrt(s / nq)


@_jit()
def _dense(F, y_old, t_old, h, t, out):
    """DOP853's interpolant of a step at time t (scipy's Dop853DenseOutput)."""
    xx = (t - t_old) / h
    n = y_old.shape[0]
    for j in range(n):
        v = 0.0
        for i in range(F.shape[0]):
            v += F[F.shape[0] - 1 - i, j]
            if i % 2 == 0:
                v *= xx
            else:
                v *= 1.0 - xx
        out[j] = v + y_old[j]


@_jit()
def _stage(K, s, a, h, y, out):
    """out = y + h * sum_j a[j] K[j] over the first s stages (scipy's np.dot(K[:s].T, a[:s]) * h)."""
    for j in range(y.shape[0]):
        acc = 0.0
        for i in range(s):
            acc += K[i, j] * a[i]
        out[j] = y[j] + acc * h


@_jit()
def _state_units(plan_i, scale, M):
    """The unit of each of q and q' in which atol is given: 1 for an angle input (rad,
    rad/s), the mechanism's size for a slide (found as the plan's driven slide of input m),
    so that the tolerance does not depend on the unit the mechanism is drawn in."""
    unit = np.ones(2 * M)
    n_ops = plan_i[2]
    wi = plan_i[3]
    for k in range(n_ops):
        row = HEADER + k * wi
        if plan_i[row] == OP_SLIDE_POINT:
            m = plan_i[row + 4]
            unit[m] = scale
            unit[M + m] = scale
    return unit


@_jit()
def integrate_run(y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, M, system, work):
    """One run from y0 at t0 to t1 (or to a stop) in at most ``budget`` evaluations: the
    outputs at t_eval (every step when t_eval is empty).

    Returns status, nfev, info (t, law, q...), the output times and states (n_out rows).
    """
    n = y0.shape[0]
    nq = 2 * M
    info = np.zeros(2 + n)
    sample = one_sample_scratch(system[0], system[1], M)
    unit = _state_units(system[0], system[3], M)
    K = np.zeros((_STAGES + 4, n))
    y = y0.copy()
    f = np.zeros(n)
    y_new = np.zeros(n)
    ys = np.zeros(n)
    scale = np.zeros(n)
    F = np.zeros((7, n))
    every_step = t_eval.shape[0] == 0
    cap = 64 if every_step else t_eval.shape[0]
    o_t = np.zeros(cap)
    o_y = np.zeros((cap, n))
    n_out = 0
    if every_step:
        o_t[0] = t0
        o_y[0] = y0
        n_out = 1
    st = _rhs(t0, y, f, M, system, work, sample, info)
    nfev = 1
    if st != 0:
        info[0] = t0
        info[2:] = y
        return st, nfev, info, o_t[:n_out], o_y[:n_out]
    g_old = info[0] - stop
    # the first step (scipy's select_initial_step, Hairer, Norsett and Wanner II.4)
    span = t1 - t0
    for i in range(nq):
        scale[i] = atol * unit[i] + abs(y0[i]) * rtol
    d0 = _rms(y0, scale, nq)
    d1 = _rms(f, scale, nq)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    if not 0.0 < h0 < np.inf:               # both sizes beyond float64 (a tiny atol)
        h0 = 1e-6
    h0 = min(h0, span)
    for j in range(n):
        ys[j] = y0[j] + h0 * f[j]
    st = _rhs(t0 + h0, ys, K[1], M, system, work, sample, info)
    nfev += 1
    if st != 0:
        info[0] = t0 + h0
        info[2:] = ys
        return st, nfev, info, o_t[:n_out], o_y[:n_out]
    for j in range(n):
        K[2, j] = K[1, j] - f[j]
    d2 = _rms(K[2], scale, nq) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** -_ERROR_EXPONENT
    h_abs = min(100 * h0, h1, span, max_step)
    if h_abs != h_abs:                      # NaN from sizes beyond float64
        h_abs = h0
    t = t0
    i_eval = 0
    status = RUN_FINISHED
    paced = False
    while t < t1:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs > max_step:
            h_abs = max_step
        elif h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if nfev >= budget:
                info[0] = t
                info[2:] = y
                return FAIL_BUDGET, nfev, info, o_t[:n_out], o_y[:n_out]
            if not paced and nfev >= PACE_CHECK:     # at this pace, can it reach t1?
                paced = True
                if (t - t0) * PACE_MARGIN * budget < nfev * (t1 - t0):
                    info[0] = t
                    info[2:] = y
                    return FAIL_PACE, nfev, info, o_t[:n_out], o_y[:n_out]
            if h_abs < min_step:
                info[0] = t
                info[2:] = y
                return FAIL_STEP, nfev, info, o_t[:n_out], o_y[:n_out]
            t_new = t + h_abs
            if t_new - t1 > 0:
                t_new = t1
            h = t_new - t
            h_abs = abs(h)
            # one step (scipy's rk_step): K[0] = f, stages 1..11, then f at the new point
            for j in range(n):
                K[0, j] = f[j]
            for s in range(1, _STAGES):
                _stage(K, s, _A[s], h, y, ys)
                st = _rhs(t + _C[s] * h, ys, K[s], M, system, work, sample, info)
                nfev += 1
                if st != 0:
                    info[0] = t + _C[s] * h
                    info[2:] = ys
                    return st, nfev, info, o_t[:n_out], o_y[:n_out]
            _stage(K, _STAGES, _B, h, y, y_new)
            st = _rhs(t + h, y_new, K[_STAGES], M, system, work, sample, info)
            nfev += 1
            if st != 0:
                info[0] = t + h
                info[2:] = y_new
                return st, nfev, info, o_t[:n_out], o_y[:n_out]
            # the error of q and q' only (scipy's DOP853._estimate_error_norm)
            e5 = 0.0
            e3 = 0.0
            for j in range(nq):
                sc = atol * unit[j] + max(abs(y[j]), abs(y_new[j])) * rtol
                a5 = 0.0
                a3 = 0.0
                for i in range(_STAGES + 1):
                    a5 += K[i, j] * _E5[i]
                    a3 += K[i, j] * _E3[i]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            if e5 == 0.0 and e3 == 0.0:
                err = 0.0
            else:
                err = h_abs * e5 / np.sqrt((e5 + 0.01 * e3) * nq)
            if err < 1:
                if err == 0:
                    factor = _MAX_FACTOR
                else:
                    factor = min(_MAX_FACTOR, _SAFETY * err ** _ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            factor = _SAFETY * err ** _ERROR_EXPONENT
            h_abs *= factor if factor > _MIN_FACTOR else _MIN_FACTOR    # NaN: the smallest
            rejected = True
        singularity = info[0]
        g_new = singularity - stop
        event = stop > 0 and g_old >= 0 and g_new <= 0
        t_end = t_new
        need = event or every_step or (i_eval < t_eval.shape[0] and t_eval[i_eval] <= t_new)
        if need and not every_step or event:
            # the interpolant (scipy's _dense_output_impl): three more stages
            for s in range(_STAGES + 1, _STAGES + 4):
                _stage(K, s, _A_EXTRA[s - _STAGES - 1], h, y, ys)
                st = _rhs(t + _C_EXTRA[s - _STAGES - 1] * h, ys, K[s], M, system, work, sample,
                          info)
                nfev += 1
                if st != 0:
                    info[0] = t + _C_EXTRA[s - _STAGES - 1] * h
                    info[2:] = ys
                    return st, nfev, info, o_t[:n_out], o_y[:n_out]
            for j in range(n):
                dlt = y_new[j] - y[j]
                F[0, j] = dlt
                F[1, j] = h * K[0, j] - dlt
                F[2, j] = 2 * dlt - h * (K[_STAGES, j] + K[0, j])
                for i in range(4):
                    acc = 0.0
                    for l in range(_STAGES + 4):
                        acc += _D[i, l] * K[l, j]
                    F[3 + i, j] = h * acc
            if event:
                # where the singularity measure meets the stop: bisection on the interpolant
                lo, hi = t, t_new
                for _ in range(200):
                    mid = 0.5 * (lo + hi)
                    if mid <= lo or mid >= hi:
                        break
                    _dense(F, y, t, h, mid, ys)
                    st = _rhs(mid, ys, K[_STAGES + 3], M, system, work, sample, info)
                    if st != FAIL_ASSEMBLY and info[0] - stop > 0:
                        lo = mid
                    else:
                        hi = mid
                t_end = hi
                status = RUN_SINGULAR
        if every_step:
            if n_out == cap:
                cap *= 2
                grown_t = np.zeros(cap)
                grown_y = np.zeros((cap, n))
                grown_t[:n_out] = o_t[:n_out]
                grown_y[:n_out] = o_y[:n_out]
                o_t, o_y = grown_t, grown_y
            o_t[n_out] = t_end
            if event:
                _dense(F, y, t, h, t_end, o_y[n_out])
            else:
                o_y[n_out] = y_new
            n_out += 1
        else:
            while i_eval < t_eval.shape[0] and t_eval[i_eval] <= t_end:
                o_t[n_out] = t_eval[i_eval]
                _dense(F, y, t, h, t_eval[i_eval], o_y[n_out])
                n_out += 1
                i_eval += 1
        if event:
            info[0] = t_end
            return status, nfev, info, o_t[:n_out], o_y[:n_out]
        g_old = g_new
        t = t_new
        for j in range(n):
            y[j] = y_new[j]
            f[j] = K[_STAGES, j]
    return status, nfev, info, o_t[:n_out], o_y[:n_out]


@_jit(nogil=True)
def integrate_runs(Y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, M, system, per_run, lo,
                   hi, o_y, o_status, o_nfev, o_info, o_count, stack_size):
    """Runs lo:hi of a batch (rows of Y0), each by :func:`integrate_run`: outputs at
    t_eval into o_y (B, N, n), its status, evaluations, info and number of outputs.

    ``per_run`` holds the numbers that may differ between the runs' models and laws (the
    entries ``PER_RUN`` of ``system``), a row per run, or one row that every run shares.
    """
    plan_f, scale, mass_w, mass_g, spring_k, spring_l0, spring_c, constants = per_run
    ns = system[2]
    w = 1 + M + M * M
    for r in range(lo, hi):
        k = 0 if plan_f.shape[0] == 1 else r
        own = (system[0], plan_f[k], ns, scale[k], system[4], mass_w[k], mass_g[k], system[7],
               system[8], system[9], system[10], system[11], spring_k[k], spring_l0[k],
               spring_c[k], system[15], constants[k], system[17], system[18])
        work = (np.zeros((3, M)), np.zeros(ns * w + 2 * ns + 5), np.zeros((M, M)),
                np.zeros(M, np.int64), np.zeros(M), np.zeros(stack_size))
        st, nfev, info, _, ys = integrate_run(Y0[r], t0, t1, t_eval, rtol, atol, max_step, stop,
                                              budget, M, own, work)
        o_y[r, :ys.shape[0]] = ys
        o_status[r] = st
        o_nfev[r] = nfev
        o_info[r] = info
        o_count[r] = ys.shape[0]


# Each entry point comes twice, as in the kinematics kernel: for any number of inputs M, and
# with M = 1 compiled in as a constant (the common case), which lets the loops over inputs
# unroll (about a fifth of an evaluation).

@_jit(nogil=True)
def integrate_run_one_input(y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, system, work):
    """:func:`integrate_run` for one input."""
    return integrate_run(y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, 1, system, work)


@_jit(nogil=True)
def integrate_runs_one_input(Y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, system,
                             per_run, lo, hi, o_y, o_status, o_nfev, o_info, o_count, stack_size):
    """:func:`integrate_runs` for one input."""
    integrate_runs(Y0, t0, t1, t_eval, rtol, atol, max_step, stop, budget, 1, system, per_run, lo,
                   hi, o_y, o_status, o_nfev, o_info, o_count, stack_size)
