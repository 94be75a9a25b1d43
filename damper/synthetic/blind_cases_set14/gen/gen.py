#!/usr/bin/env python3
"""Blind test set 14 for the BRFD semi-active model-discrepancy tool.

Deterministic generator (Python 3 standard library only, master seed 14014).

  python3 gen/gen.py            # writes cases/tNN/{A,B}.json, key.json under the blind14 root

Base model: semi-active LuGre model of Coble et al. (Eqs. 1-5, Tables 1-2) with the parameters of
/work/runs/brfd-semiactive.yaml, implemented with the conventions that reproduce
`hybridsim damper predict --no-fit` (see NOTES.md):
  * drum velocity from the DISPLACEMENT column (the file's velocity column is ~1/125.4 of in/s,
    a known quirk of the semi-active files): central differences (one-sided at the ends) followed
    by a 15-sample centred moving average whose window shrinks symmetrically at the ends;
  * z(0) = F(0)/sigma0 from the first force sample;
  * x'_1, x'_2 = actuator positions of the first row;
  * step k-1 -> k: exact exponential update of the linear-in-z ODE with v, x1, x2 held at their
    values of sample k (zero-order hold on the new sample);  F_k = sigma0 z_k + sigma1 zdot_k + sigma2 v_k.
Synthetic records are cut from the six measured semi-active tests (strokes between drum
reversals, actuator-active drum cycles kept whole), time-scaled, mirrored, re-chained with dwells,
start rest and final exact rest.  Effect shapes (8 categories x 3) are defined in SHAPES below.
"""
import json
import math
import os
import random
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SRC_DIR = os.environ.get("BRFD_SEMIACTIVE_DIR", "/work/shared/data/brfd/semiactive")
SRC_FILES = ["harmonic0.03ea1forward.json", "harmonic0.03ea1backward.json",
             "harmonic0.03ea2forward.json", "harmonic0.03ea2backward.json",
             "harmonic0.015forward.json", "harmonic0.015backward.json"]
MASTER_SEED = 14014
DT = 0.0009765625

# ---------------------------------------------------------------- base-model parameters (yaml)
S0 = 15.36      # sigma0 kip/in
S1 = 0.0        # sigma1 kip s/in
S2 = 0.500      # sigma2 kip s/in
FS_F, FS_B = 7.116, 3.760
FC_F, FC_B = 2.648, 1.253
VS = 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]   # m11 m12 m21 m22 m31 m32 m41 m42
C = [119.68, 2.10, 1.94, 123.31]
FC_FLOOR = 0.05
KF1 = C[0] * M[0] + C[1] * M[2]   # forward  d Fc / d x1
KF2 = C[0] * M[1] + C[1] * M[3]   # forward  d Fc / d x2
KB1 = C[2] * M[4] + C[3] * M[6]   # backward d Fc / d x1
KB2 = C[2] * M[5] + C[3] * M[7]   # backward d Fc / d x2

# velocity-column quirk of the semi-active files (column = in/s / 125.41, lagging ~8 samples)
VCOL_RATIO = 125.41
VCOL_LAG = 8

EXP = math.exp


# ---------------------------------------------------------------- base model
def velocity(D, dt=DT):
    """Drum velocity from displacement: central differences (one-sided at the two ends) and a
    15-sample centred moving average with a symmetric window shrinking at the ends."""
    n = len(D)
    raw = [0.0] * n
    raw[0] = (D[1] - D[0]) / dt
    raw[-1] = (D[-1] - D[-2]) / dt
    inv = 1.0 / (2.0 * dt)
    for i in range(1, n - 1):
        raw[i] = (D[i + 1] - D[i - 1]) * inv
    out = [0.0] * n
    for i in range(n):
        k = min(7, i, n - 1 - i)
        out[i] = sum(raw[i - k:i + k + 1]) / (2 * k + 1)
    return out


def lin_terms(X1, X2):
    """Eq. (4) actuator terms (kip), forward and backward, relative to the first row."""
    xp1, xp2 = X1[0], X2[0]
    LF = [KF1 * (a - xp1) + KF2 * (b - xp2) for a, b in zip(X1, X2)]
    LB = [KB1 * (a - xp1) + KB2 * (b - xp2) for a, b in zip(X1, X2)]
    return LF, LB


def fc_list(V, LF, LB):
    out = []
    for v, lf, lb in zip(V, LF, LB):
        f = FC_F + lf if v >= 0 else FC_B + lb
        out.append(f if f > FC_FLOOR else FC_FLOOR)
    return out


def g_list(V, FC, vs=VS):
    out = []
    for v, fc in zip(V, FC):
        fs = FS_F if v >= 0 else FS_B
        out.append(fc + (fs - fc) * EXP(-(v / vs) ** 2))
    return out


def lugre_core(V, G, F0, sig=S0, s2=S2, dt=DT):
    """Base LuGre (Fb = sigma0 z form).  Returns the friction force list."""
    n = len(V)
    out = [0.0] * n
    Fb = F0
    v = V[0]
    a = sig * abs(v) / G[0]
    out[0] = Fb + S1 * (sig * v - a * Fb) / sig + s2 * v
    for i in range(1, n):
        v = V[i]
        a = sig * abs(v) / G[i]
        if a * dt < 1e-12:
            Fb += sig * v * dt
        else:
            fs = sig * v / a
            Fb = fs + (Fb - fs) * EXP(-a * dt)
        out[i] = Fb + S1 * (sig * v - a * Fb) / sig + s2 * v
    return out


def prep(D, X1, X2, F0):
    """Precomputed inputs of one record."""
    V = velocity(D)
    LF, LB = lin_terms(X1, X2)
    FC = fc_list(V, LF, LB)
    G = g_list(V, FC)
    return {"D": D, "X1": X1, "X2": X2, "F0": F0, "V": V, "LF": LF, "LB": LB, "FC": FC, "G": G}


def base_force(D, X1, X2, F0):
    r = prep(D, X1, X2, F0)
    return lugre_core(r["V"], r["G"], F0)


def sgn(v):
    return 1.0 if v >= 0 else -1.0


# ---------------------------------------------------------------- effect shapes
# Every shape: f(rec, p, prm) -> list of friction force (kip).  p = 0 gives the base model exactly.

def _exp_step(Fb, tgt_num, a, dt=DT):
    """dFb/dt = tgt_num - a Fb over one step (exact for constant coefficients)."""
    if a * dt < 1e-12:
        return Fb + tgt_num * dt
    fs = tgt_num / a
    return fs + (Fb - fs) * EXP(-a * dt)


# --- backlash
def bl_drive_play(rec, p, prm):
    """Play (dead band, half-width p in) in the drive line between the measured displacement and the
    drum/band interface: y = play operator of D; the base model is driven by y."""
    D = rec["D"]
    y = [0.0] * len(D)
    yc = D[0]
    for i, d in enumerate(D):
        if yc < d - p:
            yc = d - p
        elif yc > d + p:
            yc = d + p
        y[i] = yc
    if p == 0:
        y = D
    r = prep(y, rec["X1"], rec["X2"], rec["F0"])
    return lugre_core(r["V"], r["G"], rec["F0"])


def bl_stiffness_dip(rec, p, prm):
    """Slack band: contact stiffness reduced near zero band force (clearance-type stiffness),
    sigma_eff = sigma0 (1 - p exp(-(Fb/fw)^2))."""
    V, G = rec["V"], rec["G"]
    fw2 = prm["fw_kip"] ** 2
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        sig = S0 * (1.0 - p * EXP(-Fb * Fb / fw2))
        a = sig * abs(v) / G[i]
        Fb = _exp_step(Fb, sig * v, a)
        out[i] = Fb + S2 * v
    return out


def reversal_travel(D, h):
    """Travel since the last drum reversal (turning points confirmed with hysteresis h, in)."""
    n = len(D)
    s = [0.0] * n
    tp = D[0]
    ext = D[0]
    dirn = 0
    for i in range(n):
        d = D[i]
        if dirn == 0:
            if abs(d - tp) > h:
                dirn = 1 if d > tp else -1
                ext = d
        elif dirn == 1:
            if d > ext:
                ext = d
            elif d < ext - h:
                tp = ext
                dirn = -1
                ext = d
        else:
            if d < ext:
                ext = d
            elif d > ext + h:
                tp = ext
                dirn = 1
                ext = d
        s[i] = abs(d - tp)
    return s


def bl_takeup_recovery(rec, p, prm):
    """Slack take-up after reversal: the kinetic level recovers with travel s since the reversal,
    g_eff = g (1 - p exp(-s/l))."""
    V, G = rec["V"], rec["G"]
    s = reversal_travel(rec["D"], prm["h_in"])
    ell = prm["l_in"]
    G2 = [g * (1.0 - p * EXP(-si / ell)) for g, si in zip(G, s)]
    return lugre_core(V, G2, rec["F0"])


# --- residual static force
def _rest_weight(v, vr):
    return EXP(-(v / vr) ** 2)


def rs_maxwell(rec, p, prm):
    """Maxwell relaxation of the held band force near rest: dFb/dt += -p w(v) Fb, w = exp(-(v/vr)^2)."""
    V, G = rec["V"], rec["G"]
    vr = prm["vr_in_s"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        a = S0 * abs(v) / G[i] + p * _rest_weight(v, vr)
        Fb = _exp_step(Fb, S0 * v, a)
        out[i] = Fb + S2 * v
    return out


def rs_powerlaw(rec, p, prm):
    """Power-law (log-time) creep relaxation of the held force during a dwell:
    Fb(t) = Fb(stop) (1 + t/t0)^-p, t = time at rest (|v| < vr)."""
    V, G = rec["V"], rec["G"]
    vr, t0 = prm["vr_in_s"], prm["t0_s"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    trest = 0.0
    for i in range(1, n):
        v = V[i]
        a = S0 * abs(v) / G[i]
        Fb = _exp_step(Fb, S0 * v, a)
        if abs(v) < vr:
            tn = trest + DT
            if p != 0:
                Fb *= ((1.0 + tn / t0) / (1.0 + trest / t0)) ** (-p)
            trest = tn
        else:
            trest = 0.0
        out[i] = Fb + S2 * v
    return out


def rs_threshold(rec, p, prm):
    """Creep of the held force down to a holding limit: the part of |Fb| above theta*Fc relaxes,
    dFb/dt += -p w(v) (Fb - theta Fc sgn Fb) when |Fb| > theta Fc."""
    V, G, LF, LB = rec["V"], rec["G"], rec["LF"], rec["LB"]
    vr, th = prm["vr_in_s"], prm["theta"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        a = S0 * abs(v) / G[i]
        if Fb >= 0:
            T = max(FC_F + LF[i], FC_FLOOR) * th
        else:
            T = -max(FC_B + LB[i], FC_FLOOR) * th
        if abs(Fb) > abs(T) and p != 0:
            k = p * _rest_weight(v, vr)
            Fb = _exp_step(Fb, S0 * v + k * T, a + k)
        else:
            Fb = _exp_step(Fb, S0 * v, a)
        out[i] = Fb + S2 * v
    return out


# --- actuator lag
def _with_actuators(rec, X1, X2):
    r = prep(rec["D"], X1, X2, rec["F0"])
    return lugre_core(r["V"], r["G"], rec["F0"])


def al_first_order(rec, p, prm):
    """Band clamping follows the commanded positions through a first-order lag, time constant p (s)."""
    if p == 0:
        return _with_actuators(rec, rec["X1"], rec["X2"])
    f = 1.0 - EXP(-DT / p)
    out = []
    for X in (rec["X1"], rec["X2"]):
        xe = X[0]
        Y = []
        for x in X:
            xe += (x - xe) * f
            Y.append(xe)
        Y[0] = X[0]
        out.append(Y)
    return _with_actuators(rec, out[0], out[1])


def al_delay(rec, p, prm):
    """Pure transport delay p (s) between commanded position and clamping."""
    if p == 0:
        return _with_actuators(rec, rec["X1"], rec["X2"])
    out = []
    sh = p / DT
    for X in (rec["X1"], rec["X2"]):
        n = len(X)
        Y = [0.0] * n
        for i in range(n):
            u = i - sh
            if u <= 0:
                Y[i] = X[0]
            else:
                j = int(u)
                w = u - j
                Y[i] = X[j] + (X[j + 1] - X[j]) * w if j + 1 < n else X[j]
        out.append(Y)
    return _with_actuators(rec, out[0], out[1])


def al_second_order(rec, p, prm):
    """Under-damped second-order servo/band dynamics: xe'' + 2 zeta wn xe' + wn^2 (xe - x) = 0,
    wn = 1/p (p in s), exact discretisation with x held over the step."""
    if p == 0:
        return _with_actuators(rec, rec["X1"], rec["X2"])
    z = prm["zeta"]
    wn = 1.0 / p
    wd = wn * math.sqrt(1.0 - z * z)
    ex = EXP(-z * wn * DT)
    c, s = math.cos(wd * DT), math.sin(wd * DT)
    out = []
    for X in (rec["X1"], rec["X2"]):
        xe, ve = X[0], 0.0
        Y = [X[0]]
        for x in X[1:]:
            e0 = xe - x
            e1 = ex * (e0 * c + (ve + z * wn * e0) / wd * s)
            ve = ex * (ve * c - (wn * wn * e0 + z * wn * ve) / wd * s)
            xe = x + e1
            Y.append(xe)
        out.append(Y)
    return _with_actuators(rec, out[0], out[1])


# --- asymmetry
def as_stiffness(rec, p, prm):
    """Direction-dependent aggregate stiffness: sigma0 (1+p) in the selected rotation direction."""
    V, G = rec["V"], rec["G"]
    d = prm["direction"]
    sf = S0 * (1.0 + p) if d == "forward" else S0
    sb = S0 * (1.0 + p) if d == "backward" else S0
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        sig = sf if v >= 0 else sb
        a = sig * abs(v) / G[i]
        Fb = _exp_step(Fb, sig * v, a)
        out[i] = Fb + S2 * v
    return out


def as_stribeck_velocity(rec, p, prm):
    """Direction-dependent Stribeck velocity: v_s exp(p) in the selected direction."""
    V, FC = rec["V"], rec["FC"]
    d = prm["direction"]
    vf = VS * EXP(p) if d == "forward" else VS
    vb = VS * EXP(p) if d == "backward" else VS
    G2 = []
    for v, fc in zip(V, FC):
        if v >= 0:
            G2.append(fc + (FS_F - fc) * EXP(-(v / vf) ** 2))
        else:
            G2.append(fc + (FS_B - fc) * EXP(-(v / vb) ** 2))
    return lugre_core(V, G2, rec["F0"])


def as_viscous(rec, p, prm):
    """Direction-dependent viscous coefficient: sigma2 + p (kip s/in) in the selected direction."""
    V = rec["V"]
    d = prm["direction"]
    F = lugre_core(V, rec["G"], rec["F0"])
    for i, v in enumerate(V):
        if (v >= 0) == (d == "forward"):
            F[i] += p * v
    return F


# --- velocity dependence
def ve_log_strengthening(rec, p, prm):
    """Rate-and-state steady-state velocity strengthening of the kinetic level:
    Fc_eff = Fc (1 + p ln(1 + |v|/v0))."""
    V, FC = rec["V"], rec["FC"]
    v0 = prm["v0_in_s"]
    G2 = []
    for v, fc in zip(V, FC):
        fce = fc * (1.0 + p * math.log(1.0 + abs(v) / v0))
        fs = FS_F if v >= 0 else FS_B
        G2.append(fce + (fs - fce) * EXP(-(v / VS) ** 2))
    return lugre_core(V, G2, rec["F0"])


def ve_power_viscous(rec, p, prm):
    """Non-linear viscous friction: sigma2 sgn(v) |v/vref|^(1+p) vref (replaces sigma2 v)."""
    V = rec["V"]
    vref = prm["vref_in_s"]
    F = lugre_core(V, rec["G"], rec["F0"], s2=0.0)
    e = 1.0 + p
    for i, v in enumerate(V):
        F[i] += S2 * math.copysign(vref * (abs(v) / vref) ** e, v) if v != 0 else 0.0
    return F


def ve_frictional_lag(rec, p, prm):
    """Frictional memory (Hess & Soom): the Stribeck term sees a lagged velocity, tau_L = p (s)."""
    V, FC = rec["V"], rec["FC"]
    if p == 0:
        VL = V
    else:
        f = 1.0 - EXP(-DT / p)
        VL = []
        vl = V[0]
        for v in V:
            vl += (v - vl) * f
            VL.append(vl)
        VL[0] = V[0]
    G2 = []
    for v, vl, fc in zip(V, VL, FC):
        fs = FS_F if v >= 0 else FS_B
        G2.append(fc + (fs - fc) * EXP(-(vl / VS) ** 2))
    return lugre_core(V, G2, rec["F0"])


# --- pretension / clamping law
def pt_kinetic_offset(rec, p, prm):
    """Band pretension differs from the identified one: the constant kinetic level b of Eq. (4) is
    shifted by p (kip) in both directions, Fc = b + p + L (static levels unchanged)."""
    V, LF, LB = rec["V"], rec["LF"], rec["LB"]
    FC2 = []
    for v, lf, lb in zip(V, LF, LB):
        f = FC_F + p + lf if v >= 0 else FC_B + p + lb
        FC2.append(f if f > FC_FLOOR else FC_FLOOR)
    return lugre_core(V, g_list(V, FC2), rec["F0"])


def pt_clamping_scale(rec, p, prm):
    """Normal (clamping) force differs by the factor (1+p): Fs, Fc and the actuator terms of Eq. (4),
    i.e. the whole g(v, x1, x2), scale with the band tension (Amontons)."""
    V = rec["V"]
    G2 = [g * (1.0 + p) for g in rec["G"]]
    return lugre_core(V, G2, rec["F0"])


def pt_energy_fade(rec, p, prm):
    """Clamping fade with dissipated energy: g scaled by 1/(1 + p E/Eref), E = int |Fb v| dt."""
    V, G = rec["V"], rec["G"]
    eref = prm["eref_kip_in"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    E = 0.0
    for i in range(1, n):
        v = V[i]
        E += abs(Fb * v) * DT
        g = G[i] / (1.0 + p * E / eref)
        a = S0 * abs(v) / g
        Fb = _exp_step(Fb, S0 * v, a)
        out[i] = Fb + S2 * v
    return out


# --- self-energizing
def se_capstan(rec, p, prm):
    """Capstan (Euler-Eytelwein) wrap: the taut band's wrap grows with drum rotation in the
    direction of motion, g_eff = g exp(p sgn(v) D) (p = mu dtheta/dx, 1/in)."""
    V, G, D = rec["V"], rec["G"], rec["D"]
    G2 = [g * EXP(p * sgn(v) * d) for g, v, d in zip(G, V, D)]
    return lugre_core(V, G2, rec["F0"])


def se_elastic_storage(rec, p, prm):
    """Energy stored by the bands as the drum rotates and returned on the way back:
    parallel elastic term F += p D (p in kip/in, D from the neutral drum position)."""
    D = rec["D"]
    F = lugre_core(rec["V"], rec["G"], rec["F0"] - p * D[0])
    F = [f + p * d for f, d in zip(F, D)]
    F[0] = rec["F0"] + S2 * rec["V"][0]     # same value, without the rounding of (F0 - p D0) + p D0
    return F


def se_servo(rec, p, prm):
    """Self-servo (duo-servo brake) action: clamping grows with the transmitted friction force,
    g_eff = g (1 + p |Fb| / Fref), factor limited to [0.3, 3]."""
    V, G = rec["V"], rec["G"]
    fref = prm["fref_kip"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        k = 1.0 + p * abs(Fb) / fref
        k = 0.3 if k < 0.3 else (3.0 if k > 3.0 else k)
        a = S0 * abs(v) / (G[i] * k)
        Fb = _exp_step(Fb, S0 * v, a)
        out[i] = Fb + S2 * v
    return out


# --- transition shape
def tr_dahl_exponent(rec, p, prm):
    """Dahl-type shape exponent: dFb/dt = sigma0 v sgn(u)|u|^(1+p), u = 1 - sgn(v) Fb/g
    (p = 0: LuGre), exponential-Euler integration."""
    V, G = rec["V"], rec["G"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        g = G[i]
        u = 1.0 - sgn(v) * Fb / g
        au = abs(u)
        if au < 1e-9:
            au = 1e-9
        aup = au ** p
        a = S0 * abs(v) / g * aup
        Fb = _exp_step(Fb, S0 * v * aup, a)
        out[i] = Fb + S2 * v
    return out


def tr_elastoplastic(rec, p, prm):
    """Elasto-plastic pre-sliding (Dupont et al. 2002): no slip while |Fb| < p g (loading branch),
    smooth onset of slip up to 2 p g; LuGre otherwise."""
    V, G = rec["V"], rec["G"]
    n = len(V)
    out = [0.0] * n
    Fb = rec["F0"]
    out[0] = Fb + S2 * V[0]
    for i in range(1, n):
        v = V[i]
        g = G[i]
        al = 1.0
        if p > 0 and Fb * v >= 0:
            r = abs(Fb) / g
            if r < p:
                al = 0.0
            elif r < 2.0 * p:
                al = 0.5 - 0.5 * math.cos(math.pi * (r - p) / p)
        a = al * S0 * abs(v) / g
        Fb = _exp_step(Fb, S0 * v, a)
        out[i] = Fb + S2 * v
    return out


def tr_maxwell_slip(rec, p, prm):
    """Two-element Maxwell-slip / GMS-type pre-sliding: a fraction p of the band force is carried by
    softer elements (stiffness kappa sigma0) with the same sliding level g."""
    V, G = rec["V"], rec["G"]
    kap = prm["kappa"]
    n = len(V)
    out = [0.0] * n
    F1 = F2 = rec["F0"]
    out[0] = F1 + S2 * V[0]
    s2 = S0 * kap
    for i in range(1, n):
        v = V[i]
        g = G[i]
        a1 = S0 * abs(v) / g
        a2 = s2 * abs(v) / g
        F1 = _exp_step(F1, S0 * v, a1)
        F2 = _exp_step(F2, s2 * v, a2)
        out[i] = (1.0 - p) * F1 + p * F2 + S2 * v if p != 0 else F1 + S2 * v
    return out


# name: (category, function, fixed params, p meaning, signs allowed, pmax, p guess)
SHAPES = {
    "drive_play": ("backlash", bl_drive_play, {}, "half-width of the play (in)", (1,), 0.35, 0.02),
    "slack_stiffness_dip": ("backlash", bl_stiffness_dip, {"fw_kip": 0.5},
                            "fractional stiffness loss at zero band force", (1,), 0.985, 0.3),
    "takeup_recovery": ("backlash", bl_takeup_recovery, {"h_in": 0.003, "l_in": 0.12},
                        "fractional kinetic-level loss right after reversal", (1,), 0.95, 0.2),
    "maxwell_relaxation": ("residual_static", rs_maxwell, {"vr_in_s": 0.05},
                           "relaxation rate at rest (1/s)", (1,), 40.0, 0.5),
    "powerlaw_creep": ("residual_static", rs_powerlaw, {"vr_in_s": 0.01, "t0_s": 0.05},
                       "power-law creep exponent", (1,), 3.0, 0.05),
    "threshold_creep": ("residual_static", rs_threshold, {"vr_in_s": 0.05, "theta": 0.5},
                        "creep rate of the excess over the holding limit (1/s)", (1,), 60.0, 1.0),
    "first_order_lag": ("actuator_lag", al_first_order, {}, "time constant (s)", (1,), 1.5, 0.05),
    "transport_delay": ("actuator_lag", al_delay, {}, "delay (s)", (1,), 1.0, 0.05),
    "second_order_servo": ("actuator_lag", al_second_order, {"zeta": 0.3},
                           "1/omega_n (s)", (1,), 0.6, 0.03),
    "dir_stiffness": ("asymmetry", as_stiffness, {}, "relative change of sigma0 in one direction",
                      (1, -1), 6.0, 0.2),
    "dir_stribeck_velocity": ("asymmetry", as_stribeck_velocity, {},
                              "log ratio of v_s in one direction", (1, -1), 3.0, 0.2),
    "dir_viscous": ("asymmetry", as_viscous, {}, "added viscous coefficient in one direction (kip s/in)",
                    (1, -1), 1.5, 0.05),
    "log_rate_strengthening": ("velocity", ve_log_strengthening, {"v0_in_s": 0.1},
                               "log-rate coefficient", (1, -1), 1.5, 0.03),
    "power_law_viscous": ("velocity", ve_power_viscous, {"vref_in_s": 1.0},
                          "change of the viscous exponent", (1, -1), 1.5, 0.1),
    "frictional_lag": ("velocity", ve_frictional_lag, {}, "frictional-memory time constant (s)",
                       (1,), 1.0, 0.02),
    "kinetic_offset": ("pretension", pt_kinetic_offset, {}, "shift of b in both directions (kip)",
                       (1, -1), 2.0, 0.05),
    "clamping_scale": ("pretension", pt_clamping_scale, {}, "relative change of the clamping force",
                       (1, -1), 1.0, 0.02),
    "energy_fade": ("pretension", pt_energy_fade, {"eref_kip_in": 100.0},
                    "fade coefficient per Eref of dissipated energy", (1,), 20.0, 0.1),
    "capstan_wrap": ("self_energizing", se_capstan, {}, "wrap coefficient (1/in)", (1, -1), 1.2, 0.05),
    "elastic_storage": ("self_energizing", se_elastic_storage, {}, "storage stiffness (kip/in)",
                        (1,), 3.0, 0.1),
    "servo_feedback": ("self_energizing", se_servo, {"fref_kip": 20.0}, "servo gain", (1,),
                       1.5, 0.1),
    "dahl_exponent": ("transition_shape", tr_dahl_exponent, {}, "exponent change alpha-1",
                      (1, -1), 4.0, 0.2),
    "elastoplastic_breakaway": ("transition_shape", tr_elastoplastic, {},
                                "breakaway fraction of g (elastic range)", (1,), 0.48, 0.1),
    "maxwell_slip_2": ("transition_shape", tr_maxwell_slip, {"kappa": 0.2},
                       "force fraction carried by the soft elements", (1,), 1.0, 0.2),
}
CATEGORIES = ["backlash", "residual_static", "actuator_lag", "asymmetry", "velocity", "pretension",
              "self_energizing", "transition_shape"]
PMIN_NEG = {"dir_stiffness": 0.85, "log_rate_strengthening": 0.2, "power_law_viscous": 0.6,
            "kinetic_offset": 1.0, "clamping_scale": 0.6, "dahl_exponent": 0.7,
            "dir_viscous": 0.45, "capstan_wrap": 1.2, "elastic_storage": 3.0,
            "dir_stribeck_velocity": 3.0}


def simulate(shape, rec, p, prm=None):
    cat, fn, prm0, *_ = SHAPES[shape]
    return fn(rec, p, prm0 if prm is None else prm)


# ---------------------------------------------------------------- source strokes
def turning_points(D, h=0.01):
    n = len(D)
    tps = [0]
    hi = lo = D[0]
    ihi = ilo = 0
    dirn = 0
    for i in range(1, n):
        x = D[i]
        if dirn == 0:
            if x > hi:
                hi, ihi = x, i
            if x < lo:
                lo, ilo = x, i
            if x > lo + h:
                dirn = 1
                hi, ihi = x, i
            elif x < hi - h:
                dirn = -1
                lo, ilo = x, i
        elif dirn == 1:
            if x > hi:
                hi, ihi = x, i
            elif x < hi - h:
                tps.append(ihi)
                dirn = -1
                lo, ilo = x, i
        else:
            if x < lo:
                lo, ilo = x, i
            elif x > lo + h:
                tps.append(ilo)
                dirn = 1
                hi, ihi = x, i
    tps.append(n - 1)
    return tps


def load_sources():
    src = {}
    units = []
    for fn in SRC_FILES:
        d = json.load(open(os.path.join(SRC_DIR, fn)))
        A = d["data"]
        D = [r[1] for r in A]
        X1 = [r[4] for r in A]
        X2 = [r[5] for r in A]
        src[fn] = (D, X1, X2)
        mode_name = "both" if "0.015" in fn else ("ea1" if "ea1" in fn else "ea2")
        tp = turning_points(D)
        strokes = list(zip(tp[1:-2], tp[2:-1]))     # full strokes between reversals
        k = 0
        while k < len(strokes):
            a, b = strokes[k]
            act = max(max(abs(X1[i] - X1[0]), abs(X2[i] - X2[0])) for i in range(a, b + 1)) > 0.002
            if act and k + 1 < len(strokes):
                b2 = strokes[k + 1][1]
                units.append({"src": fn, "a": a, "b": b2, "mid": b, "mode": mode_name,
                              "d1": D[b] - D[a], "d2": D[b2] - D[b]})
                k += 2
            else:
                units.append({"src": fn, "a": a, "b": b, "mid": None, "mode": "passive",
                              "d1": D[b] - D[a], "d2": 0.0})
                k += 1
    return src, units


# ---------------------------------------------------------------- record builder
DLIM = 1.3


def _unit_fits(u, mirror, dcur):
    s = -1.0 if mirror else 1.0
    e1 = dcur + s * u["d1"]
    e2 = e1 + s * u["d2"]
    return -DLIM <= e1 <= DLIM and -DLIM <= e2 <= DLIM


def build_record(rng, src, units, T):
    """Chain units into one record of duration ~T s.  Returns (D, X1, X2, meta).
    Each record holds at least one actuator-active drum cycle; direction alternates at every
    junction except that, after a dwell, the drum may go on in the same direction."""
    active = [u for u in units if u["mode"] != "passive"]
    passive = [u for u in units if u["mode"] == "passive"]
    final_min = 1.5
    while True:
        first_src = rng.choice(SRC_FILES)
        xb1, xb2 = src[first_src][1][0], src[first_src][2][0]
        t_start = rng.uniform(0.2, 0.8)
        n_start = int(round(t_start / DT))
        k_act = 0 if T < 10.0 else rng.randrange(3)
        plan = []
        t = t_start
        dcur = None
        last_dir = 0
        has_active = False
        while True:
            dwell = rng.uniform(0.1, 1.2) if (plan and rng.random() < 0.3) else 0.0
            scale = rng.uniform(0.7, 1.5)
            want_active = len(plan) == k_act or rng.random() < 0.42
            same_ok = dwell > 0 and rng.random() < 0.25
            cands = []
            for pool in ((active, passive) if want_active else (passive, active)):
                for u in pool:
                    if t + dwell + (u["b"] - u["a"]) * DT * scale + final_min + 0.02 > T:
                        continue
                    if dcur is None:
                        cands.append((u, rng.random() < 0.5))
                        continue
                    mirror = (u["d1"] > 0) != (-last_dir > 0)      # reverse the drum
                    if same_ok and _unit_fits(u, not mirror, dcur):
                        cands.append((u, not mirror))               # go on after the dwell
                    elif _unit_fits(u, mirror, dcur):
                        cands.append((u, mirror))
                if cands:
                    break
            if not cands:
                break
            u, mirror = rng.choice(cands)
            sg = -1.0 if mirror else 1.0
            if dcur is None:
                span = [0.0, sg * u["d1"], sg * (u["d1"] + u["d2"])]
                dcur = -0.5 * (max(span) + min(span)) + rng.uniform(-0.08, 0.08)
            last_dir = 1 if sg * (u["d2"] if u["mid"] is not None else u["d1"]) > 0 else -1
            plan.append({"unit": u, "mirror": mirror, "scale": scale, "dwell": dwell, "d0": dcur})
            dcur = dcur + sg * (u["d1"] + u["d2"])
            t += dwell + (u["b"] - u["a"]) * DT * scale
            if u["mode"] != "passive":
                has_active = True
        if has_active:
            break
    # assemble samples
    D = [plan[0]["d0"]] * n_start
    X1 = [xb1] * n_start
    X2 = [xb2] * n_start
    meta_units = []
    for it in plan:
        u = it["unit"]
        if it["dwell"] > 0:
            nd = int(round(it["dwell"] / DT))
            D += [D[-1]] * nd
            X1 += [X1[-1]] * nd
            X2 += [X2[-1]] * nd
        sD, sX1, sX2 = src[u["src"]]
        a, b = u["a"], u["b"]
        m = int(round((b - a) * it["scale"]))
        s = -1.0 if it["mirror"] else 1.0
        base = D[-1]
        x01, x02 = sX1[0], sX2[0]
        for j in range(1, m + 1):
            pos = a + j * (b - a) / m
            k = int(pos)
            w = pos - k
            if k >= b:
                k, w = b, 0.0
            def ip(arr):
                return arr[k] + (arr[k + 1] - arr[k]) * w if w > 0 else arr[k]
            D.append(base + s * (ip(sD) - sD[a]))
            X1.append(ip(sX1) - x01 + xb1)
            X2.append(ip(sX2) - x02 + xb2)
        meta_units.append({"src": u["src"], "t_src": [round(a * DT, 4), round(b * DT, 4)],
                           "actuators": u["mode"], "mirrored": it["mirror"],
                           "time_scale": round(it["scale"], 4), "dwell_before_s": round(it["dwell"], 4)})
    n_total = int(round(T / DT)) + 1
    n_fin = max(n_total - len(D), int(math.ceil(final_min / DT)) + 1)
    D += [D[-1]] * n_fin
    X1 += [X1[-1]] * n_fin
    X2 += [X2[-1]] * n_fin
    meta = {"start_rest_s": round(n_start * DT, 4), "final_rest_s": round((n_fin) * DT, 4),
            "units": meta_units}
    return D, X1, X2, meta


# ---------------------------------------------------------------- output files
def write_record(path, D, X1, X2, F, rng):
    V = velocity(D)
    n = len(D)
    rows = []
    for i in range(n):
        t = i * DT
        if t == int(t):
            t = int(t)
        vc = V[max(i - VCOL_LAG, 0)] / VCOL_RATIO + rng.gauss(0.0, 6.0e-5)
        f = F[i]
        a1 = 26.0 + 1000.0 * (max(-f, 0.0) / C[2] + max(f, 0.0) / C[0]) + rng.gauss(0.0, 1.5)
        a2 = 29.0 + 1000.0 * (max(f, 0.0) / C[1] + max(-f, 0.0) / C[3]) + rng.gauss(0.0, 1.5)
        rows.append([t, D[i], f, vc, X1[i], X2[i], a1, a2])
    obj = {"data": rows, "dt": DT, "sampling freq": 1024, "displacement units": "in",
           "time units": "s", "friction force units": "kip", "actuator force units": "lb"}
    with open(path, "w") as fh:
        fh.write(json.dumps(obj))


def rms(a):
    return math.sqrt(sum(x * x for x in a) / len(a))


def effect_ratio(shape, recs, bases, p, noise, prm):
    diff = []
    for rec, fb in zip(recs, bases):
        fe = simulate(shape, rec, p, prm)
        diff.extend(x - y for x, y in zip(fe, fb))
    return rms(diff) / noise


def find_p(shape, recs, bases, noise, target, sign, prm):
    """Bracket + bisection (Illinois on log-scale) for |p| so that ratio(p) = target (tol 0.3 %)."""
    cat, fn, _prm0, desc, signs, pmax, pguess = SHAPES[shape]
    if sign < 0:
        pmax = PMIN_NEG.get(shape, pmax)
    f = lambda m: effect_ratio(shape, recs, bases, sign * m, noise, prm)
    lo, rlo = 0.0, 0.0
    m = min(pguess, pmax)
    r = f(m)
    nev = 1
    while r < target:
        lo, rlo = m, r
        if m >= pmax:
            return None, r, nev
        m = min(m * 3.0, pmax)
        r = f(m)
        nev += 1
    hi, rhi = m, r
    if abs(rhi / target - 1) < 0.003:
        return sign * hi, rhi, nev
    while lo == 0.0:
        m = hi / 4.0
        r = f(m)
        nev += 1
        if abs(r / target - 1) < 0.003:
            return sign * m, r, nev
        if r < target:
            lo, rlo = m, r
        else:
            hi, rhi = m, r
    side = 0
    for _ in range(60):
        # secant in log-log space, safeguarded
        llo, lhi = math.log(lo), math.log(hi)
        flo = math.log(max(rlo, 1e-300)) - math.log(target)
        fhi = math.log(rhi) - math.log(target)
        if rlo > 0 and fhi != flo:
            wlo, whi = (0.5 if side == 1 else 1.0), (0.5 if side == -1 else 1.0)
            lm = (llo * fhi * whi - lhi * flo * wlo) / (fhi * whi - flo * wlo)
            if not (llo < lm < lhi):
                lm = 0.5 * (llo + lhi)
        else:
            lm = 0.5 * (llo + lhi)
        m = math.exp(lm)
        r = f(m)
        nev += 1
        if abs(r / target - 1) < 0.003:
            return sign * m, r, nev
        if r < target:
            lo, rlo = m, r
            side = -1 if side != -1 else -2
        else:
            hi, rhi = m, r
            side = 1 if side != 1 else 2
        if hi / lo < 1 + 1e-9:
            break
    return sign * m, r, nev


def plan_trials(rng):
    """Random order of the 30 trials; strengths stratified so that every category holds at least
    one strong and one weak trial (4 categories 2 strong + 1 weak, 4 categories 1 + 2; 12/12)."""
    cats = ["none"] * 6
    for c in CATEGORIES:
        cats += [c] * 3
    rng.shuffle(cats)
    order = list(CATEGORIES)
    rng.shuffle(order)
    two_strong = set(order[:4])
    shapes_by_cat = {}
    for s, v in SHAPES.items():
        shapes_by_cat.setdefault(v[0], []).append(s)
    queue = {}
    for c in CATEGORIES:
        shs = shapes_by_cat[c]
        rng.shuffle(shs)
        st = ["strong", "strong", "weak"] if c in two_strong else ["strong", "weak", "weak"]
        rng.shuffle(st)
        queue[c] = list(zip(shs, st))
    trials = []
    for i, c in enumerate(cats):
        tid = "t%02d" % (i + 1)
        if c == "none":
            trials.append({"id": tid, "category": "none", "shape": "none", "strength": "none"})
        else:
            sh, st = queue[c].pop()
            trials.append({"id": tid, "category": c, "shape": sh, "strength": st})
    return trials


def make_trial(tr, seed, src, units):
    rng = random.Random(seed)
    shape = tr["shape"]
    for attempt in range(12):
        noise = rng.uniform(0.02, 0.06)
        if tr["strength"] == "strong":
            target = rng.uniform(8.5, 11.5)
        elif tr["strength"] == "weak":
            target = rng.uniform(2.7, 3.8)
        else:
            target = 0.0
        recs, bases, metas = [], [], []
        modes = set()
        for name in ("A", "B"):
            T = rng.uniform(6.0, 26.0)
            D, X1, X2, meta = build_record(rng, src, units, T)
            F0 = rng.uniform(-1.0, 2.0)
            rec = prep(D, X1, X2, F0)
            recs.append(rec)
            bases.append(lugre_core(rec["V"], rec["G"], F0))
            meta["file"] = name + ".json"
            meta["F0_kip"] = F0
            meta["n"] = len(D)
            meta["duration_s"] = (len(D) - 1) * DT
            metas.append(meta)
            modes |= {u["actuators"] for u in meta["units"]}
        if not ({"both"} <= modes and ({"ea1", "ea2"} & modes)):
            continue
        if shape == "none":
            p, ratio, sign = 0.0, 0.0, 1
            Fs = bases
            break
        signs = SHAPES[shape][4]
        sign = rng.choice(signs)
        prm = dict(SHAPES[shape][2])
        if shape.startswith("dir_"):
            prm["direction"] = rng.choice(["forward", "backward"])
        p, ratio, nev = find_p(shape, recs, bases, noise, target, sign, prm)
        if p is None or abs(ratio / target - 1) > 0.005:
            p, ratio, nev = (find_p(shape, recs, bases, noise, target, -sign, prm) if -sign in signs
                             else (None, 0.0, 0))
            if p is None or abs(ratio / target - 1) > 0.005:
                continue
        Fs = [simulate(shape, rec, p, prm) for rec in recs]
        break
    else:
        raise RuntimeError("could not build trial %s" % tr["id"])
    return {"noise": noise, "target": target, "p": p, "ratio": ratio, "recs": recs, "Fs": Fs,
            "metas": metas, "rng": rng, "params": prm if shape != "none" else {}}


def main():
    master = random.Random(MASTER_SEED)
    trials = plan_trials(master)
    seeds = [master.randrange(1 << 30) for _ in trials]
    src, units = load_sources()
    key = {}
    for tr, seed in zip(trials, seeds):
        res = make_trial(tr, seed, src, units)
        rng = res["rng"]
        d = os.path.join(ROOT, "cases", tr["id"])
        os.makedirs(d, exist_ok=True)
        recs_meta = []
        for rec, Ft, meta in zip(res["recs"], res["Fs"], res["metas"]):
            Fobs = [Ft[0]] + [f + rng.gauss(0.0, res["noise"]) for f in Ft[1:]]
            write_record(os.path.join(d, meta["file"]), rec["D"], rec["X1"], rec["X2"], Fobs, rng)
            recs_meta.append(meta)
        sh = tr["shape"]
        params = res["params"]
        if sh != "none":
            params = dict(params)
            params["p_meaning"] = SHAPES[sh][3]
        key[tr["id"]] = {"category": tr["category"], "shape": sh, "strength": tr["strength"],
                         "p": res["p"], "noise_kip": res["noise"], "ratio": res["ratio"],
                         "target_ratio": res["target"], "seed": seed, "params": params,
                         "records": recs_meta}
        print("%s %-16s %-24s %-6s p=%-12.6g noise=%.4f ratio=%.3f target=%.3f" % (
            tr["id"], tr["category"], sh, tr["strength"], res["p"], res["noise"], res["ratio"],
            res["target"]), flush=True)
    with open(os.path.join(ROOT, "key.json"), "w") as fh:
        json.dump(key, fh, indent=1)


if __name__ == "__main__":
    main()
