#!/usr/bin/env python3
"""Blind test set 21 for the BRFD model-discrepancy tool (master seed 21021).

Regenerates everything deterministically:
    python3 gen.py [--out DIR]          (default DIR = /work/blind21)
writes DIR/cases/tNN/{A,B}.json and DIR/key.json.

Standard library only.  Units: kip, in, s.

Base model (reproduced from the black box `hybridsim damper predict --no-fit` with the config
/work/runs/brfd-semiactive.yaml, see NOTES.md):
  * drum velocity v = central differences of the displacement column (one-sided at the two
    ends), then a 15-sample centred moving average whose half-width shrinks symmetrically
    near the ends (the file's velocity column is ~1/125 of dx/dt and is NOT used);
  * Fc(x1,x2,v) of Eq. 4 with b = fc_fwd / fc_bwd, Table 1/2 slopes and scalings, x' = the
    first row's actuator positions, clipped below at 0.05 kip; v >= 0 is forward;
  * g(v) = Fc + (Fs_d - Fc) exp(-(v/vs)^2) (Eq. 5), Fs_d per direction;
  * LuGre z' = v - s0 |v| z / g, F = s0 z + s1 z' + s2 v with s1 = 0;
  * z(0) = F_file[0] / s0; step i-1 -> i integrates with v[i], Fc[i] held constant over the
    step, exactly: z_i = zs + (z_{i-1} - zs) exp(-a dt), a = s0|v|/g, zs = v/a.
"""
import hashlib
import json
import math
import os
import random
import struct
import sys

SRC_DIR = '/work/shared/data/brfd/semiactive'
SRC_FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
             'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
             'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
MASTER_SEED = 21021
DT = 0.0009765625
FS_HZ = 1024

# ---- base model parameters (brfd-semiactive.yaml) ----
S0 = 15.36
S1 = 0.0
S2 = 0.500
FS_FWD = 7.116
FS_BWD = 3.760
B_FWD = 2.648
B_BWD = 1.253
VS = 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FC_FLOOR = 0.05
# Eq. 4 coefficients (kip/in)
KF1 = C[0] * M[0] + C[1] * M[2]
KF2 = C[0] * M[1] + C[1] * M[3]
KB1 = C[2] * M[4] + C[3] * M[6]
KB2 = C[2] * M[5] + C[3] * M[7]

# ---- quantisation of the measured files ----
Q_F = 0.00080088            # friction force (kip), offset 0
Q_X = 5.89423e-05           # drum displacement (in)
OFF_X = -1.9873e-05
Q_A = 1.0 / 409600.0        # actuator position (in), stored as float32
Q_F1, OFF_F1 = 0.317938148, 0.0221   # actuator 1 force (lb)
Q_F2, OFF_F2 = 0.39989985, 0.1321    # actuator 2 force (lb)
VEL_COL_FACTOR = 125.4      # quirk: velocity column = (dx/dt) / ~125

HEADER_KEYS = [('dt', DT), ('sampling freq', FS_HZ), ('displacement units', 'in'),
               ('time units', 's'), ('friction force units', 'kip'), ('actuator force units', 'lb')]


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


def qround(v, q, off=0.0):
    return round((v - off) / q) * q + off


# =====================================================================================
# velocity and base model
# =====================================================================================
def drum_velocity(x):
    """Central differences (one-sided at the ends) + 15-sample centred moving average,
    half-width shrinking symmetrically at the ends (matches the black box)."""
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / DT
    d[n - 1] = (x[n - 1] - x[n - 2]) / DT
    inv2 = 1.0 / (2 * DT)
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) * inv2
    ps = [0.0] * (n + 1)
    s = 0.0
    for i in range(n):
        s += d[i]
        ps[i + 1] = s
    v = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        v[i] = (ps[i + k + 1] - ps[i - k]) / (2 * k + 1)
    return v


class Rec(object):
    """Precomputed inputs of one record."""

    def __init__(self, x, x1, x2, f0):
        self.n = len(x)
        self.x = x
        self.x1 = x1
        self.x2 = x2
        self.f0 = f0
        self.z0 = f0 / S0
        self.V = drum_velocity(x)
        self.u1 = [a - x1[0] for a in x1]
        self.u2 = [a - x2[0] for a in x2]
        self.fwd = [v >= 0.0 for v in self.V]
        self.gauss = [math.exp(-(v / VS) ** 2) for v in self.V]
        self.fc = self.fc_from(self.u1, self.u2)
        self.g = self.g_from(self.fc)

    def dfc(self, u1, u2):
        """actuator part of Eq. 4 for the direction of each sample"""
        return [(KF1 * a + KF2 * b) if f else (KB1 * a + KB2 * b)
                for a, b, f in zip(u1, u2, self.fwd)]

    def fc_from(self, u1, u2, bf=B_FWD, bb=B_BWD):
        out = []
        for a, b, f in zip(u1, u2, self.fwd):
            c = (bf + KF1 * a + KF2 * b) if f else (bb + KB1 * a + KB2 * b)
            out.append(c if c > FC_FLOOR else FC_FLOOR)
        return out

    def g_from(self, fc, gauss=None):
        gauss = self.gauss if gauss is None else gauss
        return [c + ((FS_FWD if f else FS_BWD) - c) * e for c, f, e in zip(fc, self.fwd, gauss)]


def sim_lin(rec, g, z0=None, extra_c=None, extra_a=None, exact=True):
    """z' = (v + extra_c) - (s0|v|/g + extra_a) z with v, g held over each step.
    Returns the z history.  Exact exponential step (what the black box does: it agrees
    to < 1e-7 kip, whereas one RK4 step per sample drifts by ~1e-5 kip where Fc is at its
    floor and s0|v|/g is large); exact=False: closed-form RK4."""
    V = rec.V
    n = rec.n
    z = rec.z0 if z0 is None else z0
    Z = [0.0] * n
    Z[0] = z
    dt = DT
    for i in range(1, n):
        v = V[i]
        a = S0 * abs(v) / g[i]
        c = v
        if extra_a is not None:
            a += extra_a[i]
        if extra_c is not None:
            c += extra_c[i]
        h = a * dt
        if h > 0.5 or (exact and h > 0.0):
            zs = c / a
            z = zs + (z - zs) * math.exp(-h)
        else:
            z += dt * (c - a * z) * (1.0 - h * 0.5 + h * h / 6.0 - h * h * h / 24.0)
        Z[i] = z
    return Z


def force_from_z(rec, Z, s2f=S2, s2b=S2):
    if s2f == s2b:
        return [S0 * z + s2f * v for z, v in zip(Z, rec.V)]
    return [S0 * z + (s2f if f else s2b) * v for z, v, f in zip(Z, rec.V, rec.fwd)]


def base_force(rec):
    return force_from_z(rec, sim_lin(rec, rec.g))


# =====================================================================================
# helper signals for the effects
# =====================================================================================
def reversal_travel(rec, eps=0.01):
    """drum travel since the last reversal (hysteresis eps in); before the first reversal
    the travel is 'large' (bands engaged), the initial load direction is the sign of z0."""
    x = rec.x
    d = 1 if rec.z0 >= 0 else -1
    xt = x[0]          # last turning point
    xe = x[0]          # running extreme in direction d
    big = 1e9
    s = [big] * rec.n
    engaged = True
    for i in range(rec.n):
        xi = x[i]
        if d > 0:
            if xi > xe:
                xe = xi
            elif xi < xe - eps:
                d = -1; xt = xe; xe = xi; engaged = False
        else:
            if xi < xe:
                xe = xi
            elif xi > xe + eps:
                d = 1; xt = xe; xe = xi; engaged = False
        s[i] = big if engaged else abs(xi - xt)
    return s


def rest_weight(rec, vr=0.03):
    return [math.exp(-(v / vr) ** 2) for v in rec.V]


def cum_travel(rec):
    out = [0.0] * rec.n
    s = 0.0
    x = rec.x
    for i in range(1, rec.n):
        s += abs(x[i] - x[i - 1])
        out[i] = s
    return out


def lag1(sig, tau):
    """first-order lag, exact discretisation for piecewise-constant input"""
    if tau <= 0:
        return list(sig)
    al = math.exp(-DT / tau)
    y = sig[0]
    out = [0.0] * len(sig)
    for i, s in enumerate(sig):
        y = s + (y - s) * al
        out[i] = y
    return out


def delay(sig, tau):
    k = tau / DT
    n = len(sig)
    out = [0.0] * n
    for i in range(n):
        t = i - k
        if t <= 0:
            out[i] = sig[0]
        else:
            j = int(t)
            fr = t - j
            out[i] = sig[j] * (1 - fr) + sig[min(j + 1, n - 1)] * fr
    return out


def second_order(sig, T, zeta):
    """y'' + 2 zeta wn y' + wn^2 (y - u) = 0, wn = 1/T, RK4 with u held over the step"""
    wn = 1.0 / T
    y = sig[0]
    yd = 0.0
    out = [0.0] * len(sig)
    dt = DT
    a1 = 2 * zeta * wn
    a0 = wn * wn
    ns = 1 + int(DT * wn / 0.1)
    dt = DT / ns
    for i, u in enumerate(sig):
        if i > 0:
            def f(y_, yd_):
                return yd_, -a1 * yd_ - a0 * (y_ - u)
            for _ in range(ns):
                k1 = f(y, yd)
                k2 = f(y + 0.5 * dt * k1[0], yd + 0.5 * dt * k1[1])
                k3 = f(y + 0.5 * dt * k2[0], yd + 0.5 * dt * k2[1])
                k4 = f(y + dt * k3[0], yd + dt * k3[1])
                y += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
                yd += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        out[i] = y
    return out


def rate_limit(sig, rmax):
    y = sig[0]
    out = [0.0] * len(sig)
    st = rmax * DT
    for i, u in enumerate(sig):
        dlt = u - y
        if dlt > st:
            dlt = st
        elif dlt < -st:
            dlt = -st
        y += dlt
        out[i] = y
    return out


def rk4_scalar(rec, g, z0, fz):
    """generic RK4 for z' = fz(z, v, g) with v, g held over each step"""
    V = rec.V
    z = z0
    Z = [0.0] * rec.n
    Z[0] = z
    for i in range(1, rec.n):
        v = V[i]
        gi = g[i]
        # sub-steps keep s0|v|/g * dt below 0.05
        ns = 1 + int(S0 * abs(v) / gi * DT / 0.05)
        dt = DT / ns
        for _ in range(ns):
            k1 = fz(z, v, gi)
            k2 = fz(z + 0.5 * dt * k1, v, gi)
            k3 = fz(z + 0.5 * dt * k2, v, gi)
            k4 = fz(z + dt * k3, v, gi)
            z += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        Z[i] = z
    return Z


# =====================================================================================
# the 24 shapes: truth(rec, p, prm) -> force history
# =====================================================================================
MU_THETA = 1.65   # capstan mu*theta of a 270 deg wrap with mu = 0.35


def t_bl_deadzone(rec, p, prm):
    d = p

    def e_of(w):
        if w > d:
            return w - d
        if w < -d:
            return w + d
        return 0.0

    def fz(w, v, g):
        return v - S0 * abs(v) * e_of(w) / g
    z0 = rec.z0
    w0 = z0 + (d if z0 >= 0 else -d)
    W = rk4_scalar(rec, rec.g, w0, fz)
    return [S0 * e_of(w) + S2 * v for w, v in zip(W, rec.V)]


def t_bl_capstan(rec, p, prm):
    s = prm['_s_rev'] if '_s_rev' in prm else reversal_travel(rec)
    k = MU_THETA
    den = math.exp(k) - 1.0
    cmin = prm['c_min']
    g = []
    for gi, si in zip(rec.g, s):
        fr = si / p if p > 0 else 1.0
        if fr >= 1.0:
            c = 1.0
        else:
            c = (math.exp(k * fr) - 1.0) / den
            if c < cmin:
                c = cmin
        g.append(gi * c)
    return force_from_z(rec, sim_lin(rec, g, exact=True))


def t_bl_smooth(rec, p, prm):
    d2 = p * p

    def e_of(w):
        w2 = w * w
        return w * w2 / (w2 + d2)

    def fz(w, v, g):
        return v - S0 * abs(v) * e_of(w) / g
    z0 = rec.z0
    # invert e(w) = z0
    w = z0 + (p if z0 >= 0 else -p)
    for _ in range(60):
        w2 = w * w
        fv = w * w2 / (w2 + d2) - z0
        dv = (w2 * w2 + 3 * w2 * d2) / (w2 + d2) ** 2
        if dv < 1e-12:
            w += 1e-6
            continue
        w -= fv / dv
    W = rk4_scalar(rec, rec.g, w, fz)
    return [S0 * e_of(w) + S2 * v for w, v in zip(W, rec.V)]


def t_rs_zener(rec, p, prm):
    a = p
    tau = prm['tau_s']
    V = rec.V
    g = rec.g
    z = rec.z0 / (1.0 - a)
    q = z
    out = [0.0] * rec.n
    out[0] = S0 * (z - a * q) + S2 * V[0]
    for i in range(1, rec.n):
        v = V[i]
        av = S0 * abs(v) / g[i]
        ns = 1 + int(av * DT / 0.05)
        dt = DT / ns

        def f(z_, q_):
            return v - av * (z_ - a * q_), (z_ - q_) / tau
        for _ in range(ns):
            k1 = f(z, q)
            k2 = f(z + 0.5 * dt * k1[0], q + 0.5 * dt * k1[1])
            k3 = f(z + 0.5 * dt * k2[0], q + 0.5 * dt * k2[1])
            k4 = f(z + dt * k3[0], q + dt * k3[1])
            z += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            q += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        out[i] = S0 * (z - a * q) + S2 * v
    return out


def t_rs_log(rec, p, prm):
    """log-time relaxation of the held force while the drum rests"""
    beta = p
    t0 = prm['t0_s']
    floor = prm['floor']
    w = prm['_w_rest'] if '_w_rest' in prm else rest_weight(rec)
    V = rec.V
    g = rec.g
    z = rec.z0
    tr = 1e3          # the initial residual force is treated as long settled
    zh = z
    resting = True
    Z = [0.0] * rec.n
    Z[0] = z
    dt = DT
    for i in range(1, rec.n):
        v = V[i]
        wi = w[i]
        if wi > 0.5:
            if not resting:
                resting = True
                tr = 0.0
                zh = z
            tr += dt
        else:
            resting = False
        a = S0 * abs(v) / g[i]
        c = v
        # relaxation rate of the held deflection, stops at floor * zh
        if resting and abs(z) > floor * abs(zh):
            c -= wi * beta * zh / (t0 + tr)
        h = a * dt
        if h > 0.0:
            zs = c / a
            z = zs + (z - zs) * math.exp(-h)
        else:
            z += c * dt
        Z[i] = z
    return force_from_z(rec, Z)


def t_rs_settle(rec, p, prm):
    k = p
    zr = prm['F_res_kip'] / S0
    w = prm['_w_rest'] if '_w_rest' in prm else rest_weight(rec)
    ea = [k * wi for wi in w]
    ec = [k * wi * zr for wi in w]
    return force_from_z(rec, sim_lin(rec, rec.g, extra_c=ec, extra_a=ea, exact=True))


def t_ts_dahl(rec, p, prm):
    n_ = 1.0 + p

    def fz(z, v, g):
        y = 1.0 - (S0 * z / g if v >= 0 else -S0 * z / g)
        if y >= 0:
            return v * y ** n_
        return v * y          # beyond the sliding level: LuGre-like relaxation
    return force_from_z(rec, rk4_scalar(rec, rec.g, rec.z0, fz))


def t_ts_gms(rec, p, prm):
    al = p
    kap = prm['kappa']
    if '_z2' in prm:
        z1, z2 = prm['_z1'], prm['_z2']
    else:
        z1 = sim_lin(rec, rec.g, exact=True)
        z2 = sim_lin(rec, [gi * kap for gi in rec.g], z0=rec.z0 * kap, exact=True)
    return [S0 * ((1 - al) * a + al * b / kap) + S2 * v for a, b, v in zip(z1, z2, rec.V)]


def t_ts_elastoplastic(rec, p, prm):
    bl = p
    zb = prm['z_ba_frac']

    def fz(z, v, g):
        zss = g / S0
        sv = 1.0 if v >= 0 else -1.0
        zz = z * sv           # deflection measured in the sliding direction
        if zz <= 0:
            alpha = 0.0
        elif zz >= zss:
            alpha = 1.0
        elif zz <= zb * zss:
            alpha = 0.0
        else:
            alpha = 0.5 * math.sin(math.pi * (zz - 0.5 * (zss + zb * zss)) / (zss - zb * zss)) + 0.5
        A = (1.0 - bl) + bl * alpha
        return v * (1.0 - A * zz / zss)
    return force_from_z(rec, rk4_scalar(rec, rec.g, rec.z0, fz))


def t_v_log(rec, p, prm):
    v0 = prm['v0']
    fc = [c * (1.0 + p * math.log(1.0 + abs(v) / v0)) for c, v in zip(rec.fc, rec.V)]
    return force_from_z(rec, sim_lin(rec, rec.g_from(fc), exact=True))


def t_v_lag(rec, p, prm):
    sl = lag1([abs(v) for v in rec.V], p)
    gauss = [math.exp(-(s / VS) ** 2) for s in sl]
    return force_from_z(rec, sim_lin(rec, rec.g_from(rec.fc, gauss), exact=True))


def t_v_weaken(rec, p, prm):
    vr = prm['v_ref']
    fl = prm['floor']
    fc = [c * max(fl, 1.0 - p * abs(v) / vr) for c, v in zip(rec.fc, rec.V)]
    return force_from_z(rec, sim_lin(rec, rec.g_from(fc), exact=True))


def _fc_eff(rec, u1, u2):
    return rec.fc_from(u1, u2)


def t_al_delay(rec, p, prm):
    fc = _fc_eff(rec, delay(rec.u1, p), delay(rec.u2, p))
    return force_from_z(rec, sim_lin(rec, rec.g_from(fc), exact=True))


def t_al_second(rec, p, prm):
    z = prm['zeta']
    fc = _fc_eff(rec, second_order(rec.u1, p, z), second_order(rec.u2, p, z))
    return force_from_z(rec, sim_lin(rec, rec.g_from(fc), exact=True))


def t_al_rate(rec, p, prm):
    r = 1.0 / p if p > 0 else 1e9
    fc = _fc_eff(rec, rate_limit(rec.u1, r), rate_limit(rec.u2, r))
    return force_from_z(rec, sim_lin(rec, rec.g_from(fc), exact=True))


def _load_amp(rec, p, prm, kind):
    fref = prm['F_ref_kip']
    cap = prm['cap']
    k = MU_THETA
    ef = math.exp(k) - 1.0
    eb = 1.0 - math.exp(-k)

    def amp(z, v):
        sv = 1.0 if v >= 0 else -1.0
        L = S0 * z * sv / fref
        if L < 0:
            L = 0.0
        if kind == 'capstan':
            if v >= 0:
                A = (math.exp(k * (1.0 + p * L)) - 1.0) / ef
            else:
                A = (1.0 - math.exp(-k * (1.0 + p * L))) / eb
        else:  # leading / trailing shoe factor
            if v >= 0:
                dd = 1.0 - p * L
                A = 1.0 / (dd if dd > cap else cap)
            else:
                A = 1.0 / (1.0 + p * L)
        return A if A < 4.0 else 4.0

    def fz(z, v, g):
        return v - S0 * abs(v) * z / (g * amp(z, v))
    return force_from_z(rec, rk4_scalar(rec, rec.g, rec.z0, fz))


def t_se_capstan(rec, p, prm):
    return _load_amp(rec, p, prm, 'capstan')


def t_se_shoe(rec, p, prm):
    return _load_amp(rec, p, prm, 'shoe')


def t_se_wrap(rec, p, prm):
    xr = prm['x_ref_in']
    g = []
    for gi, x, v in zip(rec.g, rec.x, rec.V):
        A = 1.0 + p * (x if v >= 0 else -x) / xr
        A = 0.25 if A < 0.25 else (4.0 if A > 4.0 else A)
        g.append(gi * A)
    return force_from_z(rec, sim_lin(rec, g, exact=True))


def t_pt_stiffen(rec, p, prm):
    ur = prm['u_ref_in']
    out = []
    for a, b, f in zip(rec.u1, rec.u2, rec.fwd):
        fa = max(0.0, 1.0 - p * a / ur)
        fb = max(0.0, 1.0 - p * b / ur)
        if f:
            c = B_FWD + KF1 * a * fa + KF2 * b * fb
        else:
            c = B_BWD + KB1 * a * fa + KB2 * b * fb
        out.append(c if c > FC_FLOOR else FC_FLOOR)
    return force_from_z(rec, sim_lin(rec, rec.g_from(out), exact=True))


def t_pt_loosen(rec, p, prm):
    S = prm['_cum'] if '_cum' in prm else cum_travel(rec)
    s0 = prm['S0_in']
    g = []
    for a, b, f, s, e in zip(rec.u1, rec.u2, rec.fwd, S, rec.gauss):
        loss = 1.0 - p * (1.0 - math.exp(-s / s0))
        if f:
            c = B_FWD * loss + KF1 * a + KF2 * b
        else:
            c = B_BWD * loss + KB1 * a + KB2 * b
        c = c if c > FC_FLOOR else FC_FLOOR
        # the static level follows the lost clamping as well
        fs = (FS_FWD if f else FS_BWD) * loss
        if fs < c:
            fs = c
        g.append(c + (fs - c) * e)
    return force_from_z(rec, sim_lin(rec, g, exact=True))


def t_pt_coupling(rec, p, prm):
    out = []
    for a, b, f in zip(rec.u1, rec.u2, rec.fwd):
        if f:
            c = B_FWD + KF1 * a + KF2 * b + p * a * b
        else:
            c = B_BWD + KB1 * a + KB2 * b + p * a * b
        out.append(c if c > FC_FLOOR else FC_FLOOR)
    return force_from_z(rec, sim_lin(rec, rec.g_from(out), exact=True))


def t_as_stiffness(rec, p, prm):
    kp = S0 * (1.0 + p)
    km = S0 / (1.0 + p)
    V = rec.V
    g = rec.g
    # state: band deflection z; stiffness of the loaded band depends on the load sign
    z = rec.z0 * S0 / (kp if rec.z0 >= 0 else km)
    out = [0.0] * rec.n
    out[0] = (kp if z >= 0 else km) * z + S2 * V[0]
    dt = DT
    for i in range(1, rec.n):
        v = V[i]
        k = kp if z >= 0 else km
        a = k * abs(v) / g[i]
        h = a * dt
        if h > 0:
            zs = v / a
            znew = zs + (z - zs) * math.exp(-h)
        else:
            znew = z + v * dt
        if (znew >= 0) != (z >= 0):
            # crossing zero load: finish the step with the other band's stiffness
            k2 = kp if znew >= 0 else km
            a2 = k2 * abs(v) / g[i]
            # time to reach zero with the first stiffness (z' ~ v near z = 0)
            tc = min(dt, abs(z / v)) if v != 0 else dt
            rem = dt - tc
            z0_ = 0.0
            if a2 * rem > 0:
                zs2 = v / a2
                znew = zs2 + (z0_ - zs2) * math.exp(-a2 * rem)
            else:
                znew = v * rem
        z = znew
        out[i] = (kp if z >= 0 else km) * z + S2 * v
    return out


def t_as_viscous(rec, p, prm):
    Z = prm['_zb'] if '_zb' in prm else sim_lin(rec, rec.g)
    return force_from_z(rec, Z, S2 * math.exp(p), S2 * math.exp(-p))


def t_as_stribeck(rec, p, prm):
    vb = VS * (1.0 + p)
    gauss = [e if f else math.exp(-(v / vb) ** 2) for e, f, v in zip(rec.gauss, rec.fwd, rec.V)]
    return force_from_z(rec, sim_lin(rec, rec.g_from(rec.fc, gauss), exact=True))


# category -> shape -> (function, p_meaning, p_lo, p_hi, p_start, strong_ok)
SHAPES = {
    'backlash': {
        'deadzone_clearance': (t_bl_deadzone, 'half clearance delta of the dead zone in series with the band stiffness (in)', 1e-4, 1.5, 0.02),
        'capstan_wrap_engagement': (t_bl_capstan, 'drum travel d after a reversal over which the band wrap re-engages (in)', 1e-3, 3.0, 0.1),
        'smooth_slack_takeup': (t_bl_smooth, 'slack length delta of the cubic take-up law e = w^3/(w^2+delta^2) (in)', 1e-4, 1.5, 0.03),
    },
    'residual_static': {
        'zener_relaxation': (t_rs_zener, 'relaxed fraction a of a held band force (standard linear solid)', 1e-4, 0.9, 0.2),
        'log_time_relaxation': (t_rs_log, 'beta of F_hold (1 - beta ln(1 + t/t0)) while the drum rests', 1e-4, 2.0, 0.05),
        'settle_to_residual': (t_rs_settle, 'settling rate k (1/s) of the held force toward the residual level F_r', 1e-3, 200.0, 0.5),
    },
    'transition_shape': {
        'dahl_exponent': (t_ts_dahl, 'n - 1, Dahl exponent minus one in z\' = v (1 - s0 z sgn(v)/g)^n on the loading side', 1e-4, 6.0, 0.3),
        'two_element_maxwell_slip': (t_ts_gms, 'force fraction alpha carried by the slow (compliant) Maxwell-slip element', 1e-4, 1.0, 0.3),
        'elastoplastic_breakaway': (t_ts_elastoplastic, 'blend weight of the Dupont elasto-plastic slip function (0 = LuGre, 1 = full)', 1e-4, 1.0, 0.5),
    },
    'velocity': {
        'log_rate_strengthening': (t_v_log, 'coefficient c of Fc (1 + c ln(1 + |v|/v0))', 1e-4, 3.0, 0.05),
        'frictional_memory_lag': (t_v_lag, 'time lag tau_L (s) of the speed seen by the Stribeck curve', 1e-4, 3.0, 0.05),
        'load_proportional_weakening': (t_v_weaken, 'slope c of Fc max(floor, 1 - c |v|/v_ref)', 1e-4, 6.0, 0.1),
    },
    'actuator_lag': {
        'transport_delay': (t_al_delay, 'transport delay tau (s) between actuator position and band clamping', 1e-4, 2.0, 0.05),
        'second_order_band': (t_al_second, 'T = 1/omega_n (s) of the second-order clamping response', 3e-3, 2.0, 0.05),
        'rate_limited_clamping': (t_al_rate, '1/R (s/in), R = maximum rate of the clamping travel (in/s)', 1e-3, 500.0, 10.0),
    },
    'self_energizing': {
        'capstan_load_wrap': (t_se_capstan, 'kappa: wrap-angle growth per unit band load (L = F/F_ref) in the capstan factor', 1e-4, 20.0, 0.1),
        'rotation_wrap_energizing': (t_se_wrap, 'coefficient c of g (1 + c sgn(v) x / x_ref)', 1e-4, 5.0, 0.05),
        'leading_trailing_shoe': (t_se_shoe, 'servo gain k of 1/(1 - k L) forward, 1/(1 + k L) backward', 1e-4, 20.0, 0.1),
    },
    'pretension': {
        'stiffening_band_law': (t_pt_stiffen, 'stiffening coefficient c: each actuator term scaled by max(0, 1 - c u/u_ref)', 1e-4, 30.0, 0.3),
        'progressive_loosening': (t_pt_loosen, 'fraction of the pre-tension clamping (b and Fs) lost after long sliding', 1e-4, 0.85, 0.1),
        'actuator_coupling': (t_pt_coupling, 'bilinear coupling coefficient c (kip/in^2) of the term c u1 u2', 1e-2, 1e6, 500.0),
    },
    'asymmetry': {
        'band_compliance_asymmetry': (t_as_stiffness, 'p: loaded-band stiffness s0 (1+p) forward-loaded, s0/(1+p) backward-loaded', 1e-4, 20.0, 0.3),
        'directional_viscous': (t_as_viscous, 'p: viscous coefficient s2 e^p forward, s2 e^-p backward', 1e-4, 5.0, 0.2),
        'directional_stribeck_velocity': (t_as_stribeck, 'p: backward Stribeck velocity vs (1 + p)', 1e-4, 30.0, 0.3),
    },
}


def shape_params(cat, shape, rng):
    """per-trial fixed parameters of a shape (drawn)"""
    if shape == 'capstan_wrap_engagement':
        return {'mu_theta': MU_THETA, 'c_min': 0.03, 'eps_rev_in': 0.01}
    if shape == 'zener_relaxation':
        return {'tau_s': round(rng.uniform(0.25, 0.7), 4)}
    if shape == 'log_time_relaxation':
        return {'t0_s': round(rng.uniform(0.03, 0.12), 4), 'floor': 0.05, 'v_rest_in_per_s': 0.03}
    if shape == 'settle_to_residual':
        sgn = 1 if rng.random() < 0.5 else -1
        return {'F_res_kip': round(sgn * rng.uniform(0.3, 1.0), 4), 'v_rest_in_per_s': 0.03}
    if shape == 'two_element_maxwell_slip':
        return {'kappa': round(rng.uniform(4.0, 8.0), 4)}
    if shape == 'elastoplastic_breakaway':
        return {'z_ba_frac': round(rng.uniform(0.6, 0.85), 4)}
    if shape == 'log_rate_strengthening':
        return {'v0': 0.2}
    if shape == 'load_proportional_weakening':
        return {'v_ref': 3.0, 'floor': 0.1}
    if shape == 'second_order_band':
        return {'zeta': round(rng.uniform(0.25, 0.45), 4)}
    if shape == 'capstan_load_wrap':
        return {'mu_theta': MU_THETA, 'F_ref_kip': 5.0, 'cap': 4.0}
    if shape == 'leading_trailing_shoe':
        return {'F_ref_kip': 5.0, 'cap': 0.3}
    if shape == 'rotation_wrap_energizing':
        return {'x_ref_in': 1.0}
    if shape == 'stiffening_band_law':
        return {'u_ref_in': 0.03}
    if shape == 'progressive_loosening':
        return {'S0_in': round(rng.uniform(3.0, 10.0), 4)}
    return {}


def prepare_cache(shape, rec, prm):
    """p-independent signals (speeds up the amplitude search)"""
    c = dict(prm)
    if shape == 'capstan_wrap_engagement':
        c['_s_rev'] = reversal_travel(rec, prm['eps_rev_in'])
    if shape in ('log_time_relaxation', 'settle_to_residual'):
        c['_w_rest'] = rest_weight(rec, prm['v_rest_in_per_s'])
    if shape == 'two_element_maxwell_slip':
        kap = prm['kappa']
        c['_z1'] = sim_lin(rec, rec.g, exact=True)
        c['_z2'] = sim_lin(rec, [gi * kap for gi in rec.g], z0=rec.z0 * kap, exact=True)
    if shape == 'progressive_loosening':
        c['_cum'] = cum_travel(rec)
    if shape == 'directional_viscous':
        c['_zb'] = sim_lin(rec, rec.g)
    return c


def truth_force(cat, shape, p, rec, prm):
    if cat == 'none':
        return base_force(rec)
    return SHAPES[cat][shape][0](rec, p, prm)


# =====================================================================================
# source library: strokes, start / end pieces, actuator events
# =====================================================================================
def hyst_extrema(xs, thr=0.05):
    """turning points of a smoothed displacement (hysteresis thr in)"""
    ext = []
    d = 0
    ie = 0
    for i, v in enumerate(xs):
        if d == 0:
            if v > xs[0] + thr:
                d = 1; ie = i
            elif v < xs[0] - thr:
                d = -1; ie = i
        elif d == 1:
            if v > xs[ie]:
                ie = i
            elif v < xs[ie] - thr:
                ext.append(('max', ie)); d = -1; ie = i
        else:
            if v < xs[ie]:
                ie = i
            elif v > xs[ie] + thr:
                ext.append(('min', ie)); d = 1; ie = i
    return ext


def smooth(x, h):
    n = len(x)
    ps = [0.0] * (n + 1)
    for i in range(n):
        ps[i + 1] = ps[i] + x[i]
    return [(ps[min(n, i + h + 1)] - ps[max(0, i - h)]) / (min(n, i + h + 1) - max(0, i - h)) for i in range(n)]


def load_library():
    lib = {'strokes': [], 'starts': [], 'ends': [], 'events': [], 'x0': []}
    for fn in SRC_FILES:
        with open(os.path.join(SRC_DIR, fn)) as fh:
            rows = json.load(fh)['data']
        x = [r[1] for r in rows]
        x1 = [r[4] for r in rows]
        x2 = [r[5] for r in rows]
        lib['x0'].append((x1[0], x2[0]))
        xs = smooth(x, 50)
        ext = [e for e in hyst_extrema(xs) if e[1] > 300]
        # snap extremum indices to the raw-signal extremum nearby
        idx = [i for _, i in ext]
        for a, b in zip(idx[:-1], idx[1:]):
            seg = x[a:b + 1]
            lib['strokes'].append({'src': fn, 'i0': a, 'x': seg,
                                   'amp': abs(seg[-1] - seg[0]), 'dir': 1 if seg[-1] > seg[0] else -1})
        # start piece: from the initial rest to the first extremum
        V = drum_velocity(xs)
        i_mv = next(i for i in range(len(V)) if abs(V[i]) > 0.02)
        i_st = max(0, i_mv - 60)
        lib['starts'].append({'src': fn, 'i0': i_st, 'x': x[i_st:idx[0] + 1]})
        # end piece: from the last extremum until the drum stops
        j_mv = max(i for i in range(len(V)) if abs(V[i]) > 0.02)
        lib['ends'].append({'src': fn, 'i0': idx[-1], 'x': x[idx[-1]:min(len(x), j_mv + 60)]})
        # actuator events
        d1 = [a - x1[0] for a in x1]
        d2 = [a - x2[0] for a in x2]
        act = [i for i in range(len(x)) if abs(d1[i]) > 0.001 or abs(d2[i]) > 0.001]
        wins = []
        for i in act:
            if wins and i - wins[-1][1] < 200:
                wins[-1][1] = i
            else:
                wins.append([i, i])
        for a, b in wins:
            a -= 80
            b += 80
            e1 = [v - d1[a] for v in d1[a:b + 1]]
            e2 = [v - d2[a] for v in d2[a:b + 1]]
            prev = min(idx, key=lambda i: abs(i - a))
            kind = 'both' if '0.015' in fn else ('1' if 'ea1' in fn else '2')
            lib['events'].append({'src': fn, 'i0': a, 'd1': e1, 'd2': e2, 'offset': a - prev, 'kind': kind})
    return lib


# =====================================================================================
# record construction
# =====================================================================================
def build_record(lib, rng, early, min_events, need_both):
    info = {'pieces': [], 'rests_s': [], 'events': []}
    T = rng.uniform(6.5, 25.0)
    n_target = int(T * FS_HZ)
    n_fr = int(rng.uniform(1.6, 3.0) * FS_HZ)
    xs = []
    rest_mask = []

    def add_rest(nr, xv):
        xs.extend([xv] * nr)
        rest_mask.extend([True] * nr)

    def add_piece(seg):
        xs.extend(seg)
        rest_mask.extend([False] * len(seg))

    use_end = rng.random() < 0.3
    ep = rng.choice(lib['ends']) if use_end else None
    reserve = len(ep['x']) if use_end else 0
    xc = rng.uniform(-0.5, 0.5)
    n_ir = int((rng.uniform(0.05, 0.35) if early else rng.uniform(0.1, 0.9)) * FS_HZ)
    add_rest(n_ir, xc)
    info['rests_s'].append(round(n_ir / FS_HZ, 4))
    stroke_starts = []
    d = 1 if rng.random() < 0.5 else -1
    if rng.random() < 0.3:
        sp = rng.choice(lib['starts'])
        s = rng.uniform(0.6, 1.3)
        m = d
        base = sp['x'][0]
        seg = [xc + m * s * (v - base) for v in sp['x'][1:]]
        stroke_starts.append((len(xs), m))
        add_piece(seg)
        xc = seg[-1]
        d = -m
        info['pieces'].append({'kind': 'start', 'src': sp['src'], 'src_t0': round(sp['i0'] * DT, 4),
                               'scale': round(s, 4), 'mirror': m})
    while True:
        st = rng.choice(lib['strokes'])
        L = st['amp']
        if len(xs) + len(st['x']) + n_fr + reserve > n_target:
            break
        s = rng.uniform(0.35, 1.2)
        smax = (1.25 - d * xc) / L
        if s > smax:
            s = smax * rng.uniform(0.85, 1.0)
        base = st['x'][0]
        seg = [xc + d * st['dir'] * s * (v - base) for v in st['x'][1:]]
        stroke_starts.append((len(xs), d))
        add_piece(seg)
        info['pieces'].append({'kind': 'stroke', 'src': st['src'], 'src_t0': round(st['i0'] * DT, 4),
                               'scale': round(s, 4), 'mirror': d * st['dir']})
        xc = seg[-1]
        d = -d
        if rng.random() < 0.3:
            nr = int(rng.uniform(0.25, 1.8) * FS_HZ)
            if len(xs) + nr + n_fr + reserve < n_target:
                add_rest(nr, xc)
                info['rests_s'].append(round(nr / FS_HZ, 4))
    if use_end:
        amp = max(abs(v - ep['x'][0]) for v in ep['x'])
        s = rng.uniform(0.5, 1.2)
        if abs(xc + d * s * amp) > 1.25:
            s = (1.25 - d * xc) / amp * 0.9
        base = ep['x'][0]
        seg = [xc + d * s * (v - base) for v in ep['x'][1:]]
        add_piece(seg)
        info['pieces'].append({'kind': 'end', 'src': ep['src'], 'src_t0': round(ep['i0'] * DT, 4),
                               'scale': round(s, 4), 'mirror': d})
        xc = seg[-1]
    n_fr = max(n_fr, n_target - len(xs))
    add_rest(n_fr, xc)
    info['rests_s'].append(round(n_fr / FS_HZ, 4))
    n = len(xs)
    # sensor flicker on the rests, then quantisation
    x = []
    for v, r in zip(xs, rest_mask):
        if r:
            v += rng.gauss(0.0, 0.3 * Q_X)
        x.append(f32(qround(v, Q_X, OFF_X)))

    # ---- actuators ----
    x1p, x2p = rng.choice(lib['x0'])
    sh1 = round(rng.uniform(-0.01, 0.01) / Q_A) * Q_A
    sh2 = round(rng.uniform(-0.01, 0.01) / Q_A) * Q_A
    x1p = f32(x1p + sh1)
    x2p = f32(x2p + sh2)
    u1 = [0.0] * n
    u2 = [0.0] * n
    busy_until = -1
    i_free_end = n - n_fr + int(0.5 * FS_HZ)

    def place(ev, i0, s_a, m1, m2, swap):
        e1, e2 = (ev['d2'], ev['d1']) if swap else (ev['d1'], ev['d2'])
        for k in range(len(e1)):
            j = i0 + k
            if j >= n:
                break
            u1[j] += m1 * s_a * e1[k]
            u2[j] += m2 * s_a * e2[k]
        kind = ev['kind']
        if swap and kind != 'both':
            kind = '2' if kind == '1' else '1'
        info['events'].append({'t0_s': round(i0 * DT, 4), 'dur_s': round(len(e1) * DT, 4), 'src': ev['src'],
                               'src_t0': round(ev['i0'] * DT, 4), 'scale': round(s_a, 4),
                               'mirror': [m1, m2], 'swap': swap, 'moves': kind})
        return i0 + len(e1)

    def draw_event(force_both=False):
        pool = [e for e in lib['events'] if e['kind'] == 'both'] if force_both else lib['events']
        ev = rng.choice(pool)
        s_a = rng.uniform(0.5, 1.7)
        m1 = 1 if rng.random() < 0.5 else -1
        m2 = m1 if rng.random() < 0.7 else -m1
        swap = rng.random() < 0.3
        return ev, s_a, m1, m2, swap

    n_both = 0
    if early:
        ev, s_a, m1, m2, swap = draw_event(need_both)
        s_a = max(s_a, 0.8)
        i0 = int(rng.uniform(0.0, 0.45) * FS_HZ)
        busy_until = place(ev, i0, s_a, m1, m2, swap) + int(0.1 * FS_HZ)
        n_both += ev['kind'] == 'both'
    p_ev = 0.8 if min_events >= 2 else 0.4
    cands = [(i, dd) for i, dd in stroke_starts]
    placed = len(info['events'])
    for i, dd in cands:
        if rng.random() >= p_ev:
            continue
        want_both = need_both and n_both < 2
        ev, s_a, m1, m2, swap = draw_event(want_both)
        i0 = i + ev['offset']
        if i0 < busy_until or i0 < int(1.0 * FS_HZ) or i0 + len(ev['d1']) > i_free_end:
            continue
        busy_until = place(ev, i0, s_a, m1, m2, swap) + int(0.1 * FS_HZ)
        n_both += ev['kind'] == 'both'
        placed += 1
    # top up to the minimum number of events
    tries = 0
    need = min_events if (min_events > 0) else (1 if rng.random() < 0.85 else 0)
    while (placed < need or (need_both and n_both < 2)) and tries < 200:
        tries += 1
        i, dd = rng.choice(cands)
        want_both = need_both and n_both < 2
        ev, s_a, m1, m2, swap = draw_event(want_both)
        i0 = i + ev['offset']
        if i0 < int(1.0 * FS_HZ) or i0 + len(ev['d1']) > i_free_end:
            continue
        clash = False
        for e in info['events']:
            a0 = int(round(e['t0_s'] * FS_HZ))
            a1 = a0 + int(round(e['dur_s'] * FS_HZ)) + int(0.1 * FS_HZ)
            if not (i0 + len(ev['d1']) + int(0.1 * FS_HZ) <= a0 or i0 >= a1):
                clash = True
        if clash:
            continue
        place(ev, i0, s_a, m1, m2, swap)
        n_both += ev['kind'] == 'both'
        placed += 1
    info['events'].sort(key=lambda e: e['t0_s'])
    x1 = [f32(x1p + round(a / Q_A) * Q_A) for a in u1]
    x2 = [f32(x2p + round(b / Q_A) * Q_A) for b in u2]
    x1[0] = x1p
    x2[0] = x2p
    first_move = next((i for i in range(n) if abs(x1[i] - x1p) > 0.002 or abs(x2[i] - x2p) > 0.002), None)
    info['first_actuator_motion_s'] = None if first_move is None else round(first_move * DT, 4)
    info['duration_s'] = round((n - 1) * DT, 4)
    info['n_samples'] = n
    info['final_rest_s'] = round(n_fr / FS_HZ, 4)
    info['x_prime_in'] = [x1p, x2p]
    return x, x1, x2, info


# =====================================================================================
# file writing
# =====================================================================================
def _num(v):
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def write_record(path, x, F, vcol, x1, x2, f1, f2):
    parts = []
    for i in range(len(x)):
        t = i * DT
        parts.append('[' + ', '.join(_num(a) for a in (t, x[i], F[i], vcol[i], x1[i], x2[i], f1[i], f2[i])) + ']')
    hdr = ', '.join('%s: %s' % (json.dumps(k), json.dumps(v)) for k, v in HEADER_KEYS)
    with open(path, 'w') as fh:
        fh.write('{"data": [' + ', '.join(parts) + '], ' + hdr + '}')


def read_record(path):
    with open(path) as fh:
        d = json.load(fh)
    rows = d['data']
    return d, rows


def rec_from_file(path):
    d, rows = read_record(path)
    x = [float(r[1]) for r in rows]
    x1 = [float(r[4]) for r in rows]
    x2 = [float(r[5]) for r in rows]
    F = [float(r[2]) for r in rows]
    return Rec(x, x1, x2, F[0]), F, rows


# =====================================================================================
# amplitude search
# =====================================================================================
def ratio_of(cat, shape, p, recs, caches, fbs, sd):
    num = 0.0
    n = 0
    for rec, c, fb in zip(recs, caches, fbs):
        ft = truth_force(cat, shape, p, rec, c)
        num += sum((a - b) ** 2 for a, b in zip(ft, fb))
        n += rec.n
    return math.sqrt(num / n) / sd


def solve_p(cat, shape, recs, caches, fbs, sd, target, log):
    fn, meaning, lo, hi, p0 = SHAPES[cat][shape]
    cache = {}

    def R(p):
        if p not in cache:
            cache[p] = ratio_of(cat, shape, p, recs, caches, fbs, sd)
        return cache[p]
    # bracket in log space, stepping at most x2 per try (some ratios are not monotone
    # over the whole range: the rising branch from small p is the one used)
    p = p0
    r = R(p)
    pl = rl = ph = rh = None
    for _ in range(80):
        if r < target:
            pl, rl = p, r
            if p >= hi:
                return None, r
            f = (target / r) if r > 0 else 2.0
            p = min(hi, p * min(2.0, max(1.05, f)))
        else:
            ph, rh = p, r
            if pl is not None:
                break
            if p <= lo:
                return lo, r
            p = max(lo, p * max(0.2, min(0.9, target / r)))
        if ph is not None and pl is not None:
            break
        r = R(p)
    if pl is None:
        return ph, rh
    if ph is None:
        return None, rl
    # safeguarded secant on (log p, log r)
    for _ in range(40):
        lpl, lph = math.log(pl), math.log(ph)
        if rl > 0 and rh > 0:
            lt = math.log(target)
            a, b = math.log(rl), math.log(rh)
            if b != a:
                lp = lpl + (lt - a) * (lph - lpl) / (b - a)
            else:
                lp = 0.5 * (lpl + lph)
            w = (lp - lpl) / (lph - lpl)
            if not (0.05 < w < 0.95):
                lp = 0.5 * (lpl + lph)
        else:
            lp = 0.5 * (lpl + lph)
        p = math.exp(lp)
        r = R(p)
        if abs(r / target - 1.0) < 0.002:
            return p, r
        if r < target:
            pl, rl = p, r
        else:
            ph, rh = p, r
        if ph / pl < 1.0 + 1e-9:
            return p, r
    return p, r


# =====================================================================================
# trial generation
# =====================================================================================
def plan(master_seed=MASTER_SEED):
    rng = random.Random(master_seed)
    slots = []
    for cat in SHAPES:
        for shape in SHAPES[cat]:
            slots.append((cat, shape))
    slots += [('none', 'none')] * 6
    rng.shuffle(slots)
    # strengths: 12 strong / 12 weak; shapes whose effect is confined to short windows
    # (transition corners) are kept weak so that the strong ratio is reachable.
    weak_only = {'elastoplastic_breakaway', 'second_order_band', 'rate_limited_clamping'}
    eff_idx = [i for i, s in enumerate(slots) if s[0] != 'none']
    cand = [i for i in eff_idx if slots[i][1] not in weak_only]
    strong = set(rng.sample(cand, 12))
    trials = []
    early_flags = [True] * 20 + [False] * 40
    rng.shuffle(early_flags)
    for k, (cat, shape) in enumerate(slots):
        tid = 't%02d' % (k + 1)
        if cat == 'none':
            strength = 'none'
            target = 0.0
        elif k in strong:
            strength = 'strong'
            target = rng.uniform(8.5, 11.5)
        else:
            strength = 'weak'
            target = rng.uniform(2.7, 3.8)
        sd = rng.uniform(0.02, 0.06)
        seed = rng.randrange(1, 2 ** 31)
        trials.append({'trial': tid, 'category': cat, 'shape': shape, 'strength': strength,
                       'target_ratio': target, 'noise_kip': sd, 'seed': seed,
                       'early': [early_flags[2 * k], early_flags[2 * k + 1]]})
    return trials


def make_trial(tr, out_dir, lib):
    cat, shape = tr['category'], tr['shape']
    sd = tr['noise_kip']
    for attempt in range(6):
        rng = random.Random(tr['seed'] + 7919 * attempt)
        prm = shape_params(cat, shape, rng) if cat != 'none' else {}
        min_ev = 3 if cat in ('actuator_lag', 'pretension') else 0
        need_both = shape == 'actuator_coupling'
        recs, infos, noises, acts = [], [], [], []
        for r in range(2):
            x, x1, x2, info = build_record(lib, rng, tr['early'][r], min_ev, need_both)
            n = len(x)
            noise = [rng.gauss(0.0, sd) for _ in range(n)]
            finit = rng.uniform(-1.0, 1.5)
            f0 = f32(qround(finit + noise[0], Q_F))
            rec = Rec(x, x1, x2, f0)
            info['F_init_kip'] = round(finit, 5)
            recs.append(rec)
            infos.append(info)
            noises.append(noise)
            acts.append((rng.random(), rng.random()))
        fbs = [base_force(rec) for rec in recs]
        if cat == 'none':
            p, ratio = 0.0, 0.0
            fts = fbs
            caches = [{} for _ in recs]
            break
        caches = [prepare_cache(shape, rec, prm) for rec in recs]
        p, ratio = solve_p(cat, shape, recs, caches, fbs, sd, tr['target_ratio'], None)
        if p is not None and abs(ratio / tr['target_ratio'] - 1) < 0.01:
            fts = [truth_force(cat, shape, p, rec, c) for rec, c in zip(recs, caches)]
            break
    else:
        raise RuntimeError('could not reach target for %s' % tr['trial'])
    # exact ratio of the final truth
    num = sum(sum((a - b) ** 2 for a, b in zip(ft, fb)) for ft, fb in zip(fts, fbs))
    ntot = sum(rec.n for rec in recs)
    ratio = math.sqrt(num / ntot) / sd
    tdir = os.path.join(out_dir, 'cases', tr['trial'])
    os.makedirs(tdir, exist_ok=True)
    rec_info = {}
    for name, rec, ft, noise, info, (a1, a2) in zip(('A', 'B'), recs, fts, noises, infos, acts):
        F = [rec.f0] + [f32(qround(ft[i] + noise[i], Q_F)) for i in range(1, rec.n)]
        rng2 = random.Random(tr['seed'] * 31 + (1 if name == 'A' else 2))
        vcol = [f32(v / VEL_COL_FACTOR + rng2.gauss(0.0, 1.2e-5)) for v in rec.V]
        f1, f2 = [], []
        s1 = 33.0 + 4.0 * a1
        s2 = 33.0 + 4.0 * a2
        for v in ft:
            f1.append(f32(qround(s1 + 1000.0 * max(-v, 0.0) / 2.01 + rng2.gauss(0, 0.6), Q_F1, OFF_F1)))
            f2.append(f32(qround(s2 + 1000.0 * max(v, 0.0) / 1.86 + rng2.gauss(0, 0.6), Q_F2, OFF_F2)))
        write_record(os.path.join(tdir, name + '.json'), rec.x, F, vcol, rec.x1, rec.x2, f1, f2)
        info['rms_dF_kip'] = math.sqrt(sum((a - b) ** 2 for a, b in zip(ft, fbs[0 if name == 'A' else 1])) / rec.n)
        rec_info[name] = info
    params = {k: v for k, v in prm.items() if not k.startswith('_')}
    meaning = SHAPES[cat][shape][1] if cat != 'none' else 'none (exact base model + noise)'
    return tr['trial'], {
        'category': cat, 'shape': shape, 'strength': tr['strength'], 'p': p, 'p_meaning': meaning,
        'noise_kip': sd, 'ratio': ratio, 'target_ratio': tr['target_ratio'], 'params': params,
        'seed': tr['seed'], 'attempt': attempt, 'records': rec_info}


_LIB = None


def _worker(args):
    global _LIB
    tr, out_dir = args
    if _LIB is None:
        _LIB = load_library()
    return make_trial(tr, out_dir, _LIB)


def main():
    import time
    t0 = time.time()
    out_dir = '/work/blind21'
    args = sys.argv[1:]
    if '--out' in args:
        out_dir = args[args.index('--out') + 1]
    jobs = 2
    if '--jobs' in args:
        jobs = int(args[args.index('--jobs') + 1])
    only = None
    if '--only' in args:
        only = args[args.index('--only') + 1].split(',')
    os.makedirs(os.path.join(out_dir, 'cases'), exist_ok=True)
    trials = plan()
    if only:
        trials = [t for t in trials if t['trial'] in only]
    # heavy trials first for load balance
    work = [(t, out_dir) for t in trials]
    if jobs > 1:
        import multiprocessing as mp
        with mp.Pool(jobs) as pool:
            res = pool.map(_worker, work, chunksize=1)
    else:
        res = [_worker(w) for w in work]
    key = {tid: v for tid, v in sorted(res)}
    if not only:
        with open(os.path.join(out_dir, 'key.json'), 'w') as fh:
            json.dump(key, fh, indent=1, sort_keys=True)
    else:
        with open(os.path.join(out_dir, 'key_partial.json'), 'w') as fh:
            json.dump(key, fh, indent=1, sort_keys=True)
    print('generated %d trials in %.1f s' % (len(res), time.time() - t0))


if __name__ == '__main__':
    main()
