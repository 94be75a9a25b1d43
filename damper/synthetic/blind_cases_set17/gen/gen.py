#!/usr/bin/env python3
"""Blind test set 17 for the semi-active BRFD model: generator.

Deterministic (master seed 17017), Python standard library only.

Reads the six measured semi-active tests from $BRFD_SEMIACTIVE_DIR (default
/work/shared/data/brfd/semiactive), cuts their drum and electric-actuator motion into
half-stroke "units", chains time-scaled / mirrored units into new records, simulates the
force with a hidden model discrepancy (or none), adds white Gaussian noise and writes

    ../cases/tNN/A.json, ../cases/tNN/B.json   (30 trials x 2 records, measured-file format)
    ../key.json                                 (the answer key, flat dict tNN -> {...})

The base model (`base_model`) reproduces `hybridsim damper predict --no-fit` with
/work/runs/brfd-semiactive.yaml (checked by verify.py):
  * drum velocity from the DISPLACEMENT column (the velocity column of the semi-active
    files is ~1/125.4 of d(displacement)/dt, a known quirk): central differences
    (one-sided at both ends), then a centred 15-sample moving average whose window shrinks
    symmetrically at the ends;
  * x'_1, x'_2 = actuator positions of the first row;
  * z(0) = F_measured(0) / sigma0;
  * step k -> k+1 holds v = v[k+1] and F_c(x1[k+1], x2[k+1], v[k+1]) constant and uses the
    exact solution of Eq. (1) for frozen v: z <- z_ss + (z - z_ss) exp(-sigma0 |v| dt / g);
  * F = sigma0 z + sigma1 zdot + sigma2 v.
"""
import json
import math
import os
import random
import struct
import sys
import time

SEED = 17017
DT = 1.0 / 1024.0
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DATA_DIR = os.environ.get("BRFD_SEMIACTIVE_DIR", "/work/shared/data/brfd/semiactive")
TESTS = ["harmonic0.015backward.json", "harmonic0.015forward.json",
         "harmonic0.03ea1backward.json", "harmonic0.03ea1forward.json",
         "harmonic0.03ea2backward.json", "harmonic0.03ea2forward.json"]

# ---------------------------------------------------------------- base model parameters
# /work/runs/brfd-semiactive.yaml (kip, in, s)
S0 = 15.36      # sigma0
S1 = 0.0        # sigma1
S2 = 0.500      # sigma2
FSF, FSB = 7.116, 3.760
BF, BB = 2.648, 1.253
VS = 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FLOOR = 0.05
K1F = C[0] * M[0] + C[1] * M[2]   # forward,  x1
K2F = C[0] * M[1] + C[1] * M[3]   # forward,  x2
K1B = C[2] * M[4] + C[3] * M[6]   # backward, x1
K2B = C[2] * M[5] + C[3] * M[7]   # backward, x2
VEL_COLUMN_FACTOR = 125.4          # measured velocity column = d(disp)/dt / 125.4 (quirk)

exp = math.exp
fabs = math.fabs


# ---------------------------------------------------------------- base model
def drum_velocity(x):
    """Velocity as `damper predict` derives it from the displacement column."""
    n = len(x)
    d = [0.0] * n
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    d[0] = (x[1] - x[0]) / DT
    d[n - 1] = (x[n - 1] - x[n - 2]) / DT
    # prefix sums (this reproduces predict's rounding: exact zeros come out as ~1e-14)
    P = [0.0] * (n + 1)
    for i in range(n):
        P[i + 1] = P[i] + d[i]
    v = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        v[i] = (P[i + k + 1] - P[i - k]) / (2 * k + 1)
    return v


def fc_arrays(a1, a2, a1p, a2p):
    """Eq. (4) for both directions, clipped at the floor."""
    fcf = [0.0] * len(a1)
    fcb = [0.0] * len(a1)
    for i in range(len(a1)):
        d1 = a1[i] - a1p
        d2 = a2[i] - a2p
        f = BF + K1F * d1 + K2F * d2
        b = BB + K1B * d1 + K2B * d2
        fcf[i] = f if f > FLOOR else FLOOR
        fcb[i] = b if b > FLOOR else FLOOR
    return fcf, fcb


def lugre_exact(v, fcf, fcb, z0, vsf=VS, vsb=VS, s2f=S2, s2b=S2):
    """Semi-active LuGre with the predict conventions (exact step for frozen v)."""
    n = len(v)
    F = [0.0] * n
    z = z0
    F[0] = S0 * z + (s2f if v[0] >= 0 else s2b) * v[0]
    for k in range(1, n):
        vn = v[k]
        if vn >= 0:
            fc = fcf[k]
            g = fc + (FSF - fc) * exp(-(vn / vsf) ** 2)
            s2 = s2f
        else:
            fc = fcb[k]
            g = fc + (FSB - fc) * exp(-(vn / vsb) ** 2)
            s2 = s2b
        if vn != 0.0:
            zs = g / S0 if vn > 0 else -g / S0
            z = zs + (z - zs) * exp(-S0 * fabs(vn) * DT / g)
        F[k] = S0 * z + s2 * vn   # sigma1 = 0
    return F


def base_model(rows):
    """Return (velocity, kinetic friction Fc(v), predicted force) for measured-format rows."""
    x = [r[1] for r in rows]
    a1 = [r[4] for r in rows]
    a2 = [r[5] for r in rows]
    v = drum_velocity(x)
    fcf, fcb = fc_arrays(a1, a2, a1[0], a2[0])
    F = lugre_exact(v, fcf, fcb, rows[0][2] / S0)
    fc = [fcf[i] if v[i] >= 0 else fcb[i] for i in range(len(v))]
    return v, fc, F


# ---------------------------------------------------------------- hidden-effect models
# Every shape reduces exactly to the base model at p = 0 (simulate() then calls it).

SHAPES = {
    "backlash": ["bl_clearance_deadzone", "bl_load_released_slack", "bl_progressive_wrap"],
    "residual_static": ["rs_sls_relaxation", "rs_log_creep", "rs_kww_settling"],
    "actuator_lag": ["al_transport_delay", "al_rate_limit", "al_second_order"],
    "asymmetry": ["as_band_stiffness", "as_stribeck_velocity", "as_viscous"],
    "velocity": ["ve_log_strengthening", "ve_speed_fade", "ve_frictional_lag"],
    "pretension": ["pt_wrap_angle_actuator_law", "pt_wear_loosening", "pt_thermal_fade"],
    "self_energizing": ["se_capstan_wrap_rotation", "se_band_stretch_storage", "se_self_servo"],
    "transition_shape": ["tr_dahl_exponent", "tr_elastoplastic", "tr_distributed_slip"],
}
SHAPE_CATEGORY = {s: c for c, l in SHAPES.items() for s in l}

# p ranges for the strength search (start guess, hard cap)
P_GUESS = {
    "bl_clearance_deadzone": (0.03, 3.0), "bl_load_released_slack": (0.01, 1.0),
    "bl_progressive_wrap": (0.05, 3.0),
    "rs_sls_relaxation": (0.5, 200.0), "rs_log_creep": (0.05, 2.0), "rs_kww_settling": (0.5, 200.0),
    "al_transport_delay": (0.05, 3.0), "al_rate_limit": (3.0, 1e4), "al_second_order": (0.03, 3.0),
    "as_band_stiffness": (0.3, 50.0), "as_stribeck_velocity": (0.3, 6.0), "as_viscous": (0.3, 60.0),
    "ve_log_strengthening": (0.1, 10.0), "ve_speed_fade": (0.1, 0.95), "ve_frictional_lag": (0.02, 3.0),
    "pt_wrap_angle_actuator_law": (0.5, 40.0), "pt_wear_loosening": (0.1, 0.95),
    "pt_thermal_fade": (0.005, 5.0),
    "se_capstan_wrap_rotation": (0.1, 3.0), "se_band_stretch_storage": (0.3, 20.0),
    "se_self_servo": (0.05, 0.9),
    "tr_dahl_exponent": (0.5, 60.0), "tr_elastoplastic": (0.2, 0.95), "tr_distributed_slip": (0.3, 8.0),
}


def draw_params(shape, rng):
    """Shape parameters other than the strength p (drawn once per trial)."""
    u = rng.uniform
    if shape == "bl_load_released_slack":
        return {"kappa": round(u(0.08, 0.3), 4)}
    if shape == "rs_sls_relaxation":
        return {"rho": round(u(0.05, 0.45), 4), "v_rest": 0.03, "t_settle": 0.05}
    if shape == "rs_log_creep":
        return {"t_c": round(u(0.05, 0.3), 4), "v_rest": 0.03, "t_settle": 0.05}
    if shape == "rs_kww_settling":
        return {"beta": round(u(0.4, 0.75), 4), "F_res": round(rng.choice([-1, 1, 1]) * u(0.2, 1.0), 4),
                "v_rest": 0.03, "t_settle": 0.05}
    if shape == "al_second_order":
        return {"zeta": round(u(0.25, 0.6), 4)}
    if shape in ("as_band_stiffness", "as_stribeck_velocity", "as_viscous"):
        prm = {"band": rng.choice(["forward", "backward"])}
        if shape == "as_band_stiffness":
            prm["sense"] = rng.choice(["softer", "stiffer"])
        if shape == "as_stribeck_velocity":
            prm["sense"] = rng.choice(["slower", "faster"])
        return prm
    if shape == "ve_log_strengthening":
        return {"v0": round(u(0.05, 0.3), 4)}
    if shape == "ve_speed_fade":
        return {"v_f": round(u(1.5, 4.0), 4)}
    if shape == "pt_wear_loosening":
        return {"S0_in": round(u(10.0, 40.0), 3)}
    if shape == "pt_thermal_fade":
        return {"tau_th": round(u(3.0, 10.0), 3)}
    if shape == "se_band_stretch_storage":
        return {"x_s": round(u(0.6, 1.2), 4)}
    if shape == "tr_distributed_slip":
        return {"N": 8}
    return {}


def _rk4(f, z, h, nsub):
    hs = h / nsub
    for _ in range(nsub):
        k1 = f(z)
        k2 = f(z + 0.5 * hs * k1)
        k3 = f(z + 0.5 * hs * k2)
        k4 = f(z + hs * k3)
        z += hs * (k1 + 2 * k2 + 2 * k3 + k4) / 6.0
    return z


def _g(vn, fcf_k, fcb_k):
    if vn >= 0:
        return fcf_k + (FSF - fcf_k) * exp(-(vn / VS) ** 2)
    return fcb_k + (FSB - fcb_k) * exp(-(vn / VS) ** 2)


def simulate(rec, shape, p, prm):
    """Force of the true (effect) model on record `rec` (dict from make_rec)."""
    v, a1, a2, a1p, a2p, F0 = rec["v"], rec["a1"], rec["a2"], rec["a1p"], rec["a2p"], rec["F0"]
    n = len(v)
    if shape == "none" or p == 0:
        fcf, fcb = fc_arrays(a1, a2, a1p, a2p)
        return lugre_exact(v, fcf, fcb, F0 / S0)

    # ---- actuator dynamics: Eq. (4) fed with filtered actuator positions
    if shape.startswith("al_"):
        e1 = actuator_dynamics(a1, shape, p, prm)
        e2 = actuator_dynamics(a2, shape, p, prm)
        fcf, fcb = fc_arrays(e1, e2, a1p, a2p)
        return lugre_exact(v, fcf, fcb, F0 / S0)

    if shape == "pt_wrap_angle_actuator_law":
        # actuator retraction changes the band wrap (Euler-Eytelwein, exponential in the wrap
        # angle): dFc = L0 (exp(p L / L0) - 1) / p, L = Eq. (4) linear term, L0 = 1 kip
        fcf = [0.0] * n
        fcb = [0.0] * n
        for i in range(n):
            d1 = a1[i] - a1p
            d2 = a2[i] - a2p
            f = BF + math.expm1(p * (K1F * d1 + K2F * d2)) / p
            b = BB + math.expm1(p * (K1B * d1 + K2B * d2)) / p
            fcf[i] = f if f > FLOOR else FLOOR
            fcb[i] = b if b > FLOOR else FLOOR
        return lugre_exact(v, fcf, fcb, F0 / S0)

    fcf, fcb = fc_arrays(a1, a2, a1p, a2p)

    if shape == "as_stribeck_velocity":
        fac = (1 + p) if prm["sense"] == "slower" else 1.0 / (1 + p)
        vsf = VS * fac if prm["band"] == "forward" else VS
        vsb = VS * fac if prm["band"] == "backward" else VS
        return lugre_exact(v, fcf, fcb, F0 / S0, vsf=vsf, vsb=vsb)
    if shape == "as_viscous":
        s2f = S2 * (1 + p) if prm["band"] == "forward" else S2
        s2b = S2 * (1 + p) if prm["band"] == "backward" else S2
        return lugre_exact(v, fcf, fcb, F0 / S0, s2f=s2f, s2b=s2b)

    if shape == "tr_distributed_slip":
        N = prm["N"]
        cs = [-1 + 2 * i / (N - 1) for i in range(N)]
        ws = [exp(p * c) for c in cs]
        mw = sum(ws) / N
        ws = [w / mw for w in ws]
        zs_ = [F0 / S0] * N
        F = [0.0] * n
        F[0] = F0 + S2 * v[0]
        for k in range(1, n):
            vn = v[k]
            if vn != 0.0:
                g = _g(vn, fcf[k], fcb[k])
                sg = 1.0 if vn > 0 else -1.0
                for i in range(N):
                    gi = g * ws[i]
                    zss = sg * gi / S0
                    zs_[i] = zss + (zs_[i] - zss) * exp(-S0 * fabs(vn) * DT / gi)
            F[k] = S0 * sum(zs_) / N + S2 * vn
        return F

    if shape in ("bl_clearance_deadzone", "bl_load_released_slack", "bl_progressive_wrap",
                 "as_band_stiffness", "tr_dahl_exponent", "tr_elastoplastic", "se_self_servo"):
        return _simulate_nonlinear(rec, shape, p, prm, fcf, fcb)

    return _simulate_state(rec, shape, p, prm, fcf, fcb)


def actuator_dynamics(a, shape, p, prm):
    """Band-clamping position actually seen by Eq. (4), from the measured position a."""
    n = len(a)
    e = [0.0] * n
    e[0] = a[0]
    if shape == "al_transport_delay":
        # e(t) = a(t - p), linear interpolation, a(t<0) = a(0)
        sh = p / DT
        for k in range(1, n):
            t = k - sh
            if t <= 0:
                e[k] = a[0]
            else:
                i = int(t)
                fr = t - i
                e[k] = a[i] + fr * (a[i + 1] - a[i]) if i + 1 < n else a[n - 1]
        return e
    if shape == "al_rate_limit":
        # |de/dt| <= 1/p (in/s); p in s/in
        r = DT / p
        x = a[0]
        for k in range(1, n):
            d = a[k] - x
            if d > r:
                d = r
            elif d < -r:
                d = -r
            x += d
            e[k] = x
        return e
    if shape == "al_second_order":
        # e'' + 2 zeta wn e' + wn^2 (e - a) = 0, wn = 1/p, exact step for held a[k]
        wn = 1.0 / p
        zt = prm["zeta"]
        wd = wn * math.sqrt(1 - zt * zt)
        ed = math.exp(-zt * wn * DT)
        c, s = math.cos(wd * DT), math.sin(wd * DT)
        x, xd = a[0], 0.0
        for k in range(1, n):
            u = a[k]
            y0, yd0 = x - u, xd
            y = ed * (y0 * c + (yd0 + zt * wn * y0) / wd * s)
            yd = ed * (yd0 * c - (wn * wn * y0 + zt * wn * yd0) / wd * s)
            x, xd = y + u, yd
            e[k] = x
        return e
    raise ValueError(shape)


def _integrated_position(v):
    xi = [0.0] * len(v)
    for k in range(1, len(v)):
        xi[k] = xi[k - 1] + v[k] * DT
    return xi


def _simulate_state(rec, shape, p, prm, fcf, fcb):
    """Linear band spring (exact exponential step) with extra states / modified g."""
    v, F0 = rec["v"], rec["F0"]
    n = len(v)
    xi = rec.get("xi") or _integrated_position(v)
    F = [0.0] * n
    z = F0 / S0
    F[0] = F0 + S2 * v[0]
    # state for the individual shapes
    vL = v[0]
    cum = 0.0      # sliding distance (in)
    th = 0.0       # stored frictional heat (kip in)
    t_still = 0.0
    z_hold = z
    if shape == "ve_frictional_lag":
        aL = 1 - exp(-DT / p)
    if shape == "pt_thermal_fade":
        tau = prm["tau_th"]
        eth = exp(-DT / tau)
    rest = shape.startswith("rs_")
    if rest:
        v_rest, t_settle = prm["v_rest"], prm["t_settle"]
        if shape == "rs_sls_relaxation":
            erel = exp(-p * DT)
            rho = prm["rho"]
        elif shape == "rs_log_creep":
            tc = prm["t_c"]
        else:
            beta = prm["beta"]
            z_res = prm["F_res"] / S0
    for k in range(1, n):
        vn = v[k]
        if vn >= 0:
            fc, fs = fcf[k], FSF
        else:
            fc, fs = fcb[k], FSB
        extra = 0.0
        if shape == "ve_log_strengthening":
            g = fc + (fs - fc) * exp(-(vn / VS) ** 2) + p * math.log(1 + fabs(vn) / prm["v0"])
        elif shape == "ve_speed_fade":
            fce = fc * (1 - p * (1 - exp(-fabs(vn) / prm["v_f"])))
            g = fce + (fs - fce) * exp(-(vn / VS) ** 2)
        elif shape == "ve_frictional_lag":
            vL += (vn - vL) * aL
            g = _g(vL, fcf[k], fcb[k])
        elif shape == "pt_wear_loosening":
            cum += fabs(vn) * DT
            psi = 1 - p * cum / (cum + prm["S0_in"])
            b = BF if vn >= 0 else BB
            fce = psi * b + (fc - b)
            if fce < FLOOR:
                fce = FLOOR
            fse = psi * fs
            g = fce + (fse - fce) * exp(-(vn / VS) ** 2)
        elif shape == "pt_thermal_fade":
            pw = fabs(S0 * z * vn)
            th = th * eth + pw * tau * (1 - eth)
            g = (fc + (fs - fc) * exp(-(vn / VS) ** 2)) / (1 + p * th)
        elif shape == "se_capstan_wrap_rotation":
            g = fc + (fs - fc) * exp(-(vn / VS) ** 2)
            g *= exp(p * xi[k] * (1.0 if vn >= 0 else -1.0))
        elif shape == "se_band_stretch_storage":
            g = fc + (fs - fc) * exp(-(vn / VS) ** 2)
            xs = prm["x_s"]
            extra = p * xs * math.sinh(xi[k] / xs)
        else:
            g = fc + (fs - fc) * exp(-(vn / VS) ** 2)
        if vn != 0.0:
            zs = g / S0 if vn > 0 else -g / S0
            z = zs + (z - zs) * exp(-S0 * fabs(vn) * DT / g)
        if rest:
            if fabs(vn) < v_rest:
                t_still += DT
            else:
                t_still = 0.0
            tr = t_still - t_settle
            if tr > 0:
                if tr <= DT:          # rest onset
                    z_hold = z
                if shape == "rs_sls_relaxation":
                    zi = rho * z_hold
                    z = zi + (z - zi) * erel
                elif shape == "rs_log_creep":
                    ph0 = max(0.02, 1 - p * math.log(1 + (tr - DT) / tc))
                    ph1 = max(0.02, 1 - p * math.log(1 + tr / tc))
                    z *= ph1 / ph0
                else:
                    ps0 = exp(-(p * max(tr - DT, 0.0)) ** beta)
                    ps1 = exp(-(p * tr) ** beta)
                    z = z_res + (z - z_res) * ps1 / ps0
        F[k] = S0 * z + S2 * vn + extra
    return F


def _simulate_nonlinear(rec, shape, p, prm, fcf, fcb):
    """Nonlinear band spring / slip law, RK4 (2 substeps per sample, v held)."""
    v, F0 = rec["v"], rec["F0"]
    n = len(v)
    F = [0.0] * n
    nsub = 2
    # band spring S(z) and its inverse
    st = {"w": 0.0}
    if shape == "bl_clearance_deadzone":
        def S(z):
            a = fabs(z) - p
            return 0.0 if a <= 0 else math.copysign(S0 * a, z)

        def Sinv(f):
            return 0.0 if f == 0 else math.copysign(fabs(f) / S0 + p, f)
    elif shape == "bl_load_released_slack":
        kap = prm["kappa"]

        def S(z):
            w = st["w"]
            a = fabs(z)
            if a <= w:
                return S0 * kap * z
            return math.copysign(S0 * (kap * w + a - w), z)

        def Sinv(f):
            w = st["w"]
            a = fabs(f) / S0
            if a <= kap * w:
                return f / (S0 * kap)
            return math.copysign(a - kap * w + w, f)
    elif shape == "bl_progressive_wrap":
        def S(z):
            return S0 * (z - p * math.tanh(z / p))

        def Sinv(f):
            t = f / S0
            z = t + math.copysign(p, t) if t != 0 else 0.0
            for _ in range(60):
                th = math.tanh(z / p)
                r = z - p * th - t
                d = th * th
                if d < 1e-12:
                    d = 1e-12
                z -= r / d
                if fabs(r) < 1e-15:
                    break
            return z
    elif shape == "as_band_stiffness":
        kf = (1 + p) if prm["sense"] == "stiffer" else 1.0 / (1 + p)
        side = 1.0 if prm["band"] == "forward" else -1.0

        def S(z):
            return S0 * kf * z if z * side > 0 else S0 * z

        def Sinv(f):
            return f / (S0 * kf) if f * side > 0 else f / S0
    else:
        def S(z):
            return S0 * z

        def Sinv(f):
            return f / S0

    if shape == "bl_load_released_slack":
        st["w"] = p * fabs(F0)
    z = Sinv(F0)
    F[0] = S(z) + S2 * v[0]
    # reversal tracking (bl_load_released_slack)
    eps = 0.003
    xi = 0.0
    xe = 0.0
    dirn = 0
    alpha = 1 + p
    for k in range(1, n):
        vn = v[k]
        if shape == "bl_load_released_slack":
            xi += vn * DT
            if dirn == 0:
                if fabs(xi - xe) > eps:
                    dirn = 1 if xi > xe else -1
                    xe = xi
            elif dirn * (xi - xe) > 0:
                xe = xi
            elif dirn * (xe - xi) > eps:
                f_now = S(z)
                st["w"] = p * fabs(f_now)
                z = Sinv(f_now)
                dirn = -dirn
                xe = xi
        if vn != 0.0:
            g = _g(vn, fcf[k], fcb[k])
            av = fabs(vn)
            sg = 1.0 if vn > 0 else -1.0
            if shape == "tr_dahl_exponent":
                def f(zz):
                    r = 1 - sg * S0 * zz / g
                    return vn * math.copysign(fabs(r) ** alpha, r)
            elif shape == "tr_elastoplastic":
                beta = p

                def f(zz):
                    if zz * vn > 0:
                        rr = S0 * fabs(zz) / g
                        if rr <= beta:
                            a = 0.0
                        elif rr >= 2 * beta or rr >= 1.0:
                            a = 1.0
                        else:
                            top = min(2 * beta, 1.0)
                            a = 0.5 - 0.5 * math.cos(math.pi * (rr - beta) / (top - beta))
                        return vn - a * av * S0 * zz / g
                    return vn - av * S0 * zz / g
            elif shape == "se_self_servo":
                def f(zz):
                    return vn - av * S0 * zz / (g + p * S0 * fabs(zz))
            else:
                def f(zz):
                    return vn - av * S(zz) / g
            z = _rk4(f, z, DT, nsub)
        F[k] = S(z) + S2 * vn
    return F


# ---------------------------------------------------------------- measured data -> units
def smooth(a, w):
    """Centred moving average, window w (odd), shrinking symmetrically at the ends."""
    n = len(a)
    h = w // 2
    P = [0.0] * (n + 1)
    for i in range(n):
        P[i + 1] = P[i] + a[i]
    out = [0.0] * n
    for i in range(n):
        k = min(h, i, n - 1 - i)
        out[i] = (P[i + k + 1] - P[i - k]) / (2 * k + 1)
    return out


def end_correct(d, nw):
    """Remove the residual actuator offset at both unit ends by local quadratic tapers."""
    m = len(d) - 1
    rs, re = d[0], d[-1]
    out = list(d)
    for i in range(m + 1):
        u0 = i / nw
        u1 = (m - i) / nw
        c = 0.0
        if u0 < 1:
            c += rs * (1 - u0) ** 2
        if u1 < 1:
            c += re * (1 - u1) ** 2
        out[i] = d[i] - c
    return out


def extract_units(path):
    src = json.load(open(path))
    rows = src["data"]
    name = os.path.basename(path)
    n = len(rows)
    x = [r[1] for r in rows]
    xs = smooth(smooth(x, 21), 21)
    a1p, a2p = rows[0][4], rows[0][5]
    d1 = smooth([r[4] - a1p for r in rows], 9)
    d2 = smooth([r[5] - a2p for r in rows], 9)
    x0 = sum(xs[:100]) / 100
    x1 = sum(xs[-300:]) / 300
    im = next(i for i in range(n) if fabs(xs[i] - x0) > 0.004)
    i0 = im
    while i0 > 0 and fabs(xs[i0] - x0) > 0.0005:
        i0 -= 1
    ie = max(i for i in range(n) if fabs(xs[i] - x1) > 0.004)
    i1 = ie
    while i1 < n - 1 and fabs(xs[i1] - x1) > 0.0005:
        i1 += 1
    cuts = [i0]
    dirn = 1 if xs[im] > x0 else -1
    ext = i0
    for i in range(i0, i1 + 1):
        if dirn > 0:
            if xs[i] > xs[ext]:
                ext = i
            elif xs[ext] - xs[i] > 0.02:
                cuts.append(ext)
                dirn = -1
                ext = i
        else:
            if xs[i] < xs[ext]:
                ext = i
            elif xs[i] - xs[ext] > 0.02:
                cuts.append(ext)
                dirn = 1
                ext = i
    if i1 - cuts[-1] > 50:
        cuts.append(i1)
    units = []
    nw = int(0.15 / DT)
    for j in range(len(cuts) - 1):
        ia, ib = cuts[j], cuts[j + 1]
        seg = [xs[i] - xs[ia] for i in range(ia, ib + 1)]
        L = seg[-1]
        if fabs(L) < 0.05:
            continue
        u1 = end_correct(d1[ia:ib + 1], nw)
        u2 = end_correct(d2[ia:ib + 1], nw)
        amp = max(max(fabs(q) for q in u1), max(fabs(q) for q in u2))
        kind = "start" if ia == i0 else ("end" if ib == i1 else "mid")
        active = amp > 0.006
        if not active:       # only the tail of a neighbouring actuator cycle: hold still
            u1 = [0.0] * len(seg)
            u2 = [0.0] * len(seg)
        units.append({"src": name, "i0": ia, "i1": ib, "x": seg, "d1": u1, "d2": u2,
                      "L": L, "active": active, "kind": kind})
    return units


# ---------------------------------------------------------------- record construction
def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def resample(a, m):
    """Linear resampling of a (len N+1) onto m+1 points, endpoints kept."""
    N = len(a) - 1
    out = [0.0] * (m + 1)
    for j in range(m + 1):
        t = j * N / m
        i = int(t)
        if i >= N:
            out[j] = a[N]
        else:
            fr = t - i
            out[j] = a[i] + fr * (a[i + 1] - a[i])
    return out


def first_motion_time(d, thr=0.0025):
    for i, q in enumerate(d):
        if fabs(q) > thr:
            return i * DT
    return None


def build_motion(rng, units, early):
    """Chain units into clean drum position and actuator offsets. Returns dict."""
    act = [u for u in units if u["active"]]
    pas = [u for u in units if not u["active"]]
    T_target = rng.uniform(6.5, 24.5)
    r0 = rng.uniform(0.3, 0.62) if early else rng.uniform(0.3, 0.9)
    r1 = rng.uniform(1.5, 2.5)
    act_frac = rng.uniform(0.3, 0.6)
    x_c = [0.0] * (int(round(r0 / DT)) + 1)
    d1_c = [0.0] * len(x_c)
    d2_c = [0.0] * len(x_c)
    pos = lo = hi = 0.0
    dirn = rng.choice([-1, 1])
    log = []
    n_act = 0
    first = True
    while True:
        t_now = (len(x_c) - 1) * DT
        room = min(T_target, 25.0) - r1 - t_now
        if room < 0.45:
            break
        if first:
            want_act = early
        elif not early and t_now < 1.1:
            want_act = False
        else:
            want_act = rng.random() < act_frac
            if n_act == 0 and room < 4.0:
                want_act = True
        pool = act if want_act else pas
        if first and not early and rng.random() < 0.6:
            pool = [u for u in pas if u["kind"] == "start"] or pas
        pools = [pool]
        if not first and not (not early and t_now < 1.1):
            pools.append(pas if want_act else act)   # fall back to a unit that fits
        cands = []
        for _ in range(40 * len(pools)):
            u = rng.choice(pools[0] if _ < 40 else pools[1])
            s = math.exp(rng.uniform(math.log(0.6), math.log(1.7)))
            dur = (len(u["x"]) - 1) * DT * s
            if dur > room:
                continue
            newpos = pos + dirn * fabs(u["L"])
            if max(hi, newpos) - min(lo, newpos) > 2.15:
                continue
            if first and early:
                swap = rng.random() < 0.35
                d = u["d2"] if swap else u["d1"]
                dd = u["d1"] if swap else u["d2"]
                tm = [first_motion_time(d), first_motion_time(dd)]
                tm = [q for q in tm if q is not None]
                if not tm or r0 + min(tm) * s > 0.92:
                    continue
                cands.append((u, s, swap))
            else:
                cands.append((u, s, rng.random() < 0.35))
            break
        if not cands:
            if first:
                return None
            t_now = (len(x_c) - 1) * DT
            if min(T_target, 25.0) - r1 - t_now > 2.0:
                # still pause, then go the other way
                k = int(round(rng.uniform(0.3, 0.8) / DT))
                x_c.extend([x_c[-1]] * k)
                d1_c.extend([0.0] * k)
                d2_c.extend([0.0] * k)
                log.append({"pause_s": round(k * DT, 4), "t_start": round(t_now, 4), "why": "turn"})
                dirn = -dirn
                continue
            break
        u, s, swap = cands[0]
        m = int(round((len(u["x"]) - 1) * s))
        sgn = dirn * (1 if u["L"] > 0 else -1)
        flip = -1.0 if rng.random() < 0.25 else 1.0
        xu = resample(u["x"], m)
        da = resample(u["d2"] if swap else u["d1"], m)
        db = resample(u["d1"] if swap else u["d2"], m)
        base = x_c[-1]
        for j in range(1, m + 1):
            x_c.append(base + sgn * xu[j])
            d1_c.append(flip * da[j])
            d2_c.append(flip * db[j])
        pos += dirn * fabs(u["L"])
        lo, hi = min(lo, pos), max(hi, pos)
        n_act += 1 if u["active"] else 0
        log.append({"src": u["src"], "samples": [u["i0"], u["i1"]], "time_scale": round(s, 4),
                    "mirrored": sgn < 0 if u["L"] > 0 else sgn > 0, "actuators_swapped": swap,
                    "actuator_sign": flip, "active": u["active"],
                    "t_start": round((len(x_c) - 1 - m) * DT, 4)})
        first = False
        dirn = -dirn
        # occasional still pause
        t_now = (len(x_c) - 1) * DT
        if rng.random() < 0.08 and min(T_target, 25.0) - r1 - t_now > 2.0:
            pd = rng.uniform(0.3, 1.3)
            k = int(round(pd / DT))
            x_c.extend([x_c[-1]] * k)
            d1_c.extend([0.0] * k)
            d2_c.extend([0.0] * k)
            log.append({"pause_s": round(k * DT, 4), "t_start": round(t_now, 4), "why": "random"})
            mid = 0.5 * (lo + hi)
            if fabs(pos - mid) > 0.4:
                dirn = -1 if pos > mid else 1
            else:
                dirn = rng.choice([-1, 1])
    if n_act == 0 or (len(x_c) - 1) * DT + r1 < 6.5:
        return None
    k = int(round(r1 / DT))
    x_c.extend([x_c[-1]] * k)
    d1_c.extend([0.0] * k)
    d2_c.extend([0.0] * k)
    mid = 0.5 * (lo + hi)
    x_c = [q - mid for q in x_c]
    return {"x": x_c, "d1": d1_c, "d2": d2_c, "units": log, "n_active": n_act,
            "rest0": round(r0, 4), "rest_end": round(k * DT, 4)}


# sensor resolutions, read off the measured files (differences of neighbouring levels)
QX = 5.894906632602215e-05     # displacement (in)
QF = 0.0008008862894773483     # friction force (kip)
QA = 2.443790435791016e-06     # actuator position (in)
QL1, QL2 = 0.3179162741303253, 0.3999471664428711   # actuator load cells (lb)


def quant(x, q, off):
    return (math.floor(x / q - off + 0.5) + off) * q


def make_sensors(rng, mo):
    """Measured-style columns except the friction force."""
    n = len(mo["x"])
    x0 = rng.uniform(-0.15, 0.15)
    ox, oa1, oa2 = rng.random(), rng.random(), rng.random()
    a1p = 0.655 + rng.uniform(-0.004, 0.004)
    a2p = 0.8559 + rng.uniform(-0.004, 0.004)
    x = [quant(x0 + mo["x"][i] + rng.gauss(0, 2.6e-5), QX, ox) for i in range(n)]
    a1 = [f32(quant(a1p + mo["d1"][i] + rng.gauss(0, 0.7e-6), QA, oa1)) for i in range(n)]
    a2 = [f32(quant(a2p + mo["d2"][i] + rng.gauss(0, 0.7e-6), QA, oa2)) for i in range(n)]
    # velocity column: smoothed derivative of the true motion, /125.4, ~7 samples late (quirk)
    vt = smooth([0.0] + [(mo["x"][i + 1] - mo["x"][i - 1]) / (2 * DT) for i in range(1, n - 1)] + [0.0], 15)
    vcol = [f32(vt[max(0, i - 7)] / VEL_COLUMN_FACTOR + rng.gauss(0, 1.5e-5)) for i in range(n)]
    return {"x": x, "a1": a1, "a2": a2, "vcol": vcol}


def actuator_forces(rng, F):
    """Load-cell forces (lb) consistent with the friction force (taut/slack scaling)."""
    t1 = rng.uniform(60, 110)
    t2 = rng.uniform(70, 140)
    o1, o2 = rng.random(), rng.random()
    f1, f2 = [], []
    for Fk in F:
        Fp = Fk if Fk > 0 else 0.0
        Fn = -Fk if Fk < 0 else 0.0
        base = exp(-fabs(Fk) / 0.4)
        a = 1000 * (Fn / 2.0 + Fp / C[0]) + t1 * base + 22 * (1 - base) + rng.gauss(0, 1.2 + 0.004 * 1000 * Fn / 2.0)
        b = 1000 * (Fp / 1.9 + Fn / C[3]) + t2 * base + 22 * (1 - base) + rng.gauss(0, 1.2 + 0.004 * 1000 * Fp / 1.9)
        f1.append(quant(max(a, 5.0), QL1, o1))
        f2.append(quant(max(b, 5.0), QL2, o2))
    return f1, f2


def make_rec(sen, F0):
    v = drum_velocity(sen["x"])
    return {"v": v, "a1": sen["a1"], "a2": sen["a2"], "a1p": sen["a1"][0], "a2p": sen["a2"][0],
            "F0": F0, "xi": _integrated_position(v)}


def rec_from_rows(rows):
    v = drum_velocity([r[1] for r in rows])
    return {"v": v, "a1": [r[4] for r in rows], "a2": [r[5] for r in rows], "a1p": rows[0][4],
            "a2p": rows[0][5], "F0": rows[0][2], "xi": _integrated_position(v)}


def write_record(path, meta, sen, F, f1, f2):
    n = len(F)
    rows = []
    for k in range(n):
        t = k // 1024 if k % 1024 == 0 else k * DT
        rows.append([t, sen["x"][k], F[k], sen["vcol"][k], sen["a1"][k], sen["a2"][k], f1[k], f2[k]])
    out = {"data": rows}
    for key, val in meta.items():
        out[key] = val
    with open(path, "w") as fh:
        fh.write(json.dumps(out))


# ---------------------------------------------------------------- strength search
def rms_ratio(Fe_list, Fb_list, sd):
    s = 0.0
    m = 0
    for Fe, Fb in zip(Fe_list, Fb_list):
        for a, b in zip(Fe, Fb):
            s += (a - b) ** 2
        m += len(Fe)
    return math.sqrt(s / m) / sd


def find_p(recs, Fb, shape, prm, sd, target):
    g0, cap = P_GUESS[shape]

    def ratio(p):
        return rms_ratio([simulate(r, shape, p, prm) for r in recs], Fb, sd)

    evals = []
    p_lo, r_lo = 0.0, 0.0
    p_hi = g0
    r_hi = ratio(p_hi)
    evals.append((p_hi, r_hi))
    while r_hi < target:
        if p_hi >= cap:
            return None, evals
        p_lo, r_lo = p_hi, r_hi
        p_hi = min(cap, p_hi * 2.5)
        r_hi = ratio(p_hi)
        evals.append((p_hi, r_hi))
    # bracket [p_lo, p_hi]; shrink with secant in log-log where possible, else bisection
    for it in range(40):
        if p_lo > 0 and r_lo > 0:
            lp = math.log(p_lo) + (math.log(target) - math.log(r_lo)) * \
                (math.log(p_hi) - math.log(p_lo)) / (math.log(r_hi) - math.log(r_lo))
            pm = math.exp(lp)
            if not (p_lo < pm < p_hi) or it % 3 == 2:
                pm = math.sqrt(p_lo * p_hi)
        else:
            pm = p_hi * (target / r_hi) if r_hi > 0 else 0.5 * p_hi
            if not (p_lo < pm < p_hi):
                pm = 0.5 * (p_lo + p_hi)
        rm = ratio(pm)
        evals.append((pm, rm))
        if fabs(rm / target - 1) < 0.004:
            return pm, evals
        if rm < target:
            p_lo, r_lo = pm, rm
        else:
            p_hi, r_hi = pm, rm
    return pm, evals


# ---------------------------------------------------------------- main
WEAK = (2.7, 3.8)
STRONG = (8.5, 11.5)


def plan_trials(rng):
    cats = list(SHAPES)
    pattern = ["WWS"] * 4 + ["WSS"] * 4
    rng.shuffle(pattern)
    trials = []
    for c, pat in zip(cats, pattern):
        lvls = list(pat)
        rng.shuffle(lvls)
        for s, l in zip(SHAPES[c], lvls):
            trials.append({"category": c, "shape": s, "strength": "weak" if l == "W" else "strong"})
    for _ in range(6):
        trials.append({"category": "none", "shape": "none", "strength": "none"})
    rng.shuffle(trials)
    early = [True] * 20 + [False] * 40
    rng.shuffle(early)
    for i, t in enumerate(trials):
        t["early"] = early[2 * i:2 * i + 2]
        t["seed"] = rng.randrange(1 << 30)
    return trials


def main():
    t_start = time.time()
    only = set(sys.argv[1:])
    meta = None
    units = []
    for name in TESTS:
        path = os.path.join(DATA_DIR, name)
        if meta is None:
            src = json.load(open(path))
            meta = {k: v for k, v in src.items() if k != "data"}
        units.extend(extract_units(path))
    print("units: %d (%d with actuator motion)" % (len(units), sum(u["active"] for u in units)))
    master = random.Random(SEED)
    trials = plan_trials(master)
    key_path = os.path.join(ROOT, "key.json")
    key = {}
    if only and os.path.exists(key_path):
        key = json.load(open(key_path))
    for i, tr in enumerate(trials):
        tid = "t%02d" % (i + 1)
        if only and tid not in only:
            continue
        t0 = time.time()
        rng = random.Random(tr["seed"])
        shape = tr["shape"]
        sd = rng.uniform(0.02, 0.06)
        prm = draw_params(shape, rng) if shape != "none" else {}
        if tr["strength"] == "weak":
            target = rng.uniform(*WEAK)
        elif tr["strength"] == "strong":
            target = rng.uniform(*STRONG)
        else:
            target = 0.0
        for attempt in range(12):
            recs, sens, motions, noises, F0s = [], [], [], [], []
            for j in range(2):
                mo = None
                while mo is None:
                    mo = build_motion(rng, units, tr["early"][j])
                sen = make_sensors(rng, mo)
                n = len(sen["x"])
                noise = [rng.gauss(0, sd) for _ in range(n)]
                R = rng.choice([-1, 1, 1]) * rng.uniform(0.25, 2.5)
                F0 = quant(R + noise[0], QF, 0.37)
                motions.append(mo)
                sens.append(sen)
                noises.append(noise)
                F0s.append(F0)
                recs.append(make_rec(sen, F0))
            Fb = [simulate(r, "none", 0, {}) for r in recs]
            if shape == "none":
                p, evals = 0.0, []
                break
            p, evals = find_p(recs, Fb, shape, prm, sd, target)
            if p is not None:
                break
            print("  %s %s: target %.2f not reachable (max %.2f), new records" %
                  (tid, shape, target, max(e[1] for e in evals)))
        else:
            raise RuntimeError("cannot reach ratio for " + tid)
        Fe = [simulate(r, shape, p, prm) for r in recs]
        ratio = rms_ratio(Fe, Fb, sd)
        d = os.path.join(ROOT, "cases", tid)
        os.makedirs(d, exist_ok=True)
        recinfo = {}
        for j, lab in enumerate("AB"):
            Fr = [F0s[j]] + [quant(Fe[j][k] + noises[j][k], QF, 0.37) for k in range(1, len(Fe[j]))]
            f1, f2 = actuator_forces(rng, Fe[j])
            write_record(os.path.join(d, lab + ".json"), meta, sens[j], Fr, f1, f2)
            mo = motions[j]
            a_t = None
            for k in range(len(sens[j]["a1"])):
                if fabs(sens[j]["a1"][k] - sens[j]["a1"][0]) > 0.002 or \
                        fabs(sens[j]["a2"][k] - sens[j]["a2"][0]) > 0.002:
                    a_t = k * DT
                    break
            recinfo[lab] = {"duration_s": round((len(Fr) - 1) * DT, 4), "rest0_s": mo["rest0"],
                            "rest_end_s": mo["rest_end"], "initial_force_kip": F0s[j],
                            "first_actuator_motion_s": a_t, "actuators_early": tr["early"][j],
                            "n_units": sum(1 for u in mo["units"] if "src" in u),
                            "n_active_units": mo["n_active"], "units": mo["units"]}
        key[tid] = {"category": tr["category"], "shape": shape, "strength": tr["strength"],
                    "p": p, "noise_kip": sd, "ratio": ratio, "target_ratio": target,
                    "band": list(WEAK) if tr["strength"] == "weak" else (list(STRONG) if tr["strength"] == "strong" else None),
                    "params": prm, "seed": tr["seed"], "record_attempts": attempt + 1,
                    "strength_search": [[a, b] for a, b in evals], "records": recinfo}
        print("%s %-17s %-28s %-6s p=%-10.5g sd=%.4f ratio=%.3f (%.1fs, %d evals)" %
              (tid, tr["category"], shape, tr["strength"], p, sd, ratio, time.time() - t0, len(evals)))
        sys.stdout.flush()
    with open(key_path, "w") as fh:
        json.dump(dict(sorted(key.items())), fh, indent=1)
    print("wrote %s and %d trials in %.1f s" % (key_path, len(key), time.time() - t_start))


if __name__ == "__main__":
    main()
