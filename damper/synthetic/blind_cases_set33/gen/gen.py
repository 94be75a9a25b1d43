#!/usr/bin/env python3
"""blind33 generator: synthetic 'measured' BRFD semi-active records = base model + ONE hidden
effect + white noise.  Python 3 standard library only.  Master seed 33033.

Writes ../cases/tNN/{A.json,B.json} and ../key.json (paths relative to this file).

Base model (black box `hybridsim damper predict --no-fit`, replicated here and checked by
verify.py against the binary):
  * drum velocity v = 15-sample centred moving average (window clipped at the record ends) of
    the central difference of the displacement column (one-sided difference at the two ends);
  * Eq. (4) kinetic friction Fc from the actuator columns, x'_k = first row, floor 0.05 kip;
    direction v >= 0 -> forward set;
  * LuGre Eqs. (1)-(3)/(5) with sigma1 = 0, z(0) = F_measured(0)/sigma0; over the step
    i -> i+1 the velocity and Fc are held at their values at sample i+1, so Eq. (1) is linear
    in z and is advanced exactly (z relaxes exponentially toward g sgn(v)/sigma0; the black box
    agrees to its 8-digit CSV output, single-step RK4 would differ by up to 2e-4 kip where
    sigma0|v|dt/g is large); output F_i = sigma0 z_i + sigma2 v_i.
"""
import array
import json
import math
import os
import random
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
TEMPLATE_DIR = '/work/shared/data/brfd/semiactive'
TEMPLATE_FILES = ['harmonic0.015backward.json', 'harmonic0.015forward.json',
                  'harmonic0.03ea1backward.json', 'harmonic0.03ea1forward.json',
                  'harmonic0.03ea2backward.json', 'harmonic0.03ea2forward.json']
MASTER_SEED = 33033

FS_HZ = 1024
DT = 1.0 / FS_HZ
H = DT

# ---- base model parameters (configs/brfd-semiactive.yaml) ----
S0 = 15.36
S2 = 0.500
FSF, FSB = 7.116, 3.760
FCF, FCB = 2.648, 1.253
VS = 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
CS = [119.68, 2.10, 1.94, 123.31]
FLOOR = 0.05
A1F = CS[0] * M[0] + CS[1] * M[2]   # d Fc / d x1, forward (kip/in)
A2F = CS[0] * M[1] + CS[1] * M[3]   # d Fc / d x2, forward
A1B = CS[2] * M[4] + CS[3] * M[6]   # d Fc / d x1, backward
A2B = CS[2] * M[5] + CS[3] * M[7]   # d Fc / d x2, backward

# ---- measurement chain (from the measured semi-active files) ----
Q_F = 0.00080087996          # friction-force LSB (kip), zero offset
Q_X = 5.8942e-5              # drum displacement LSB (in), offset differs per file
Q_P = 2.44140625e-6          # actuator position grid (in)
Q_T1, OFF_T1 = 0.31793998, 0.016555    # actuator-1 load-cell LSB and offset (lb)
Q_T2, OFF_T2 = 0.39989996, 0.131725    # actuator-2 load-cell LSB and offset (lb)
VEL_COL_FACTOR = 125.42      # velocity column = d(disp)/dt / 125.42 (known quirk)
VEL_COL_TAU = 0.006          # s, the velocity channel lags the displacement derivative
DEFL_IN_PER_LB = 4.6e-8      # actuator rod deflection under its own load cell force
X_NOISE_SD = 2.5e-5          # in, displacement sensor noise before quantisation
P_NOISE_SD = 0.6e-6          # in, actuator position sensor noise
T_NOISE_SD = 1.0             # lb, load-cell noise
TRAVEL_LIMIT = 1.25          # in, design limit (records stay inside +-1.3 in)
VMAX_DESIGN = 3.8            # in/s

HEADER = [("dt", DT), ("sampling freq", FS_HZ), ("displacement units", "in"),
          ("time units", "s"), ("friction force units", "kip"), ("actuator force units", "lb")]

_f32 = lambda seq: array.array('f', seq).tolist()


# =============================================================================================
#  Base model pieces
# =============================================================================================
def drum_velocity(x):
    n = len(x)
    v0 = [0.0] * n
    v0[0] = (x[1] - x[0]) / DT
    v0[n - 1] = (x[n - 1] - x[n - 2]) / DT
    for i in range(1, n - 1):
        v0[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    pre = [0.0] * (n + 1)
    s = 0.0
    for i in range(n):
        s += v0[i]
        pre[i + 1] = s
    out = [0.0] * n
    for i in range(n):
        lo = i - 7 if i >= 7 else 0
        hi = i + 8 if i + 8 <= n else n
        out[i] = (pre[hi] - pre[lo]) / (hi - lo)
    return out


def stribeck(v, fc, fs):
    return fc + (fs - fc) * math.exp(-(v / VS) ** 2)


def eq4(fwd, dx1, dx2):
    if fwd:
        r = FCF + A1F * dx1 + A2F * dx2
    else:
        r = FCB + A1B * dx1 + A2B * dx2
    return r if r > FLOOR else FLOOR


def lugre_step(f, vv, gg, kk=S0):
    """One step of f' = k v - (k|v|/g) f with v, g held: exact solution of the linear ODE
    (this is what the black box computes; it equals classical RK4 up to O((k|v|h/g)^5))."""
    a = kk * abs(vv) / gg
    y = a * H
    if y < 1e-8:
        return f + H * (kk * vv - a * f)
    return f + (kk * vv - a * f) * (-math.expm1(-y)) / a


def run_g(v, g, f0, k=None):
    """LuGre (force form f = sigma0 z) with a prescribed Stribeck level g[i] (held over the step
    ending at i) and optional per-sample stiffness k[i].  Returns F_i = f_i + sigma2 v_i."""
    n = len(v)
    F = [0.0] * n
    f = f0
    em1 = math.expm1
    for i in range(n - 1):
        F[i] = f + S2 * v[i]
        vv = v[i + 1]
        kk = S0 if k is None else k[i + 1]
        a = kk * abs(vv) / g[i + 1]
        y = a * H
        if y < 1e-8:
            f = f + H * (kk * vv - a * f)
        else:
            f = f + (kk * vv - a * f) * (-em1(-y)) / a
    F[n - 1] = f + S2 * v[n - 1]
    return F


class Rec:
    """One record as the base model sees it (recorded columns) plus design information."""

    def __init__(self, x, p1, p2, f0, rest):
        self.n = len(x)
        self.x = x
        self.p1 = p1
        self.p2 = p2
        self.f0 = f0
        self.rest = rest
        self.v = drum_velocity(x)
        self.x1p, self.x2p = p1[0], p2[0]
        self.dx1 = [a - self.x1p for a in p1]
        self.dx2 = [a - self.x2p for a in p2]
        n = self.n
        self.fwd = [vv >= 0 for vv in self.v]
        self.fcf = [eq4(True, self.dx1[i], self.dx2[i]) for i in range(n)]
        self.fcb = [eq4(False, self.dx1[i], self.dx2[i]) for i in range(n)]
        self.g = [stribeck(self.v[i], self.fcf[i], FSF) if self.fwd[i] else
                  stribeck(self.v[i], self.fcb[i], FSB) for i in range(n)]
        self._base = None

    def base(self):
        if self._base is None:
            self._base = run_g(self.v, self.g, self.f0)
        return self._base

    def g_from_fc(self, fcf, fcb):
        v = self.v
        return [stribeck(v[i], fcf[i], FSF) if v[i] >= 0 else stribeck(v[i], fcb[i], FSB)
                for i in range(self.n)]


def base_model(x, p1, p2, f0):
    return Rec(x, p1, p2, f0, None).base()


# =============================================================================================
#  Hidden effects.  Each takes (rec, amplitude, fixed) and returns F_true; amplitude 0 gives
#  the base model exactly (series-contact backlash B2/B3 tend to it as the amplitude -> 0).
# =============================================================================================
def _g_dir(vy, fcf, fcb):
    return stribeck(vy, fcf, FSF) if vy >= 0 else stribeck(vy, fcb, FSB)


# ---------------------------------------------------------------- backlash ------------------
def eff_backlash_rigid_play(rec, delta, fx):
    """B1: play (dead-zone) of half-width delta in the drive link, rigid re-engagement.
    Disengaged: the link carries no force, the (massless) drum is driven only by the band
    bristles against viscous drag: sigma2 vy = -f."""
    n, v = rec.n, rec.v
    F = [0.0] * n
    f = rec.f0
    side = 1.0 if f >= 0 else -1.0
    u = side * delta            # link relative displacement x - y
    engaged = True
    eps = 1e-12
    for i in range(n - 1):
        vv = v[i + 1]
        if engaged:
            F[i] = f + S2 * v[i]
        else:
            F[i] = 0.0
        # decide the mode for this step
        if delta <= 0.0:
            engaged = True
        else:
            at_pos = u >= delta - eps
            at_neg = u <= -delta + eps
            fl = f + S2 * vv
            engaged = (at_pos and fl >= 0.0) or (at_neg and fl <= 0.0)
        if engaged:
            f = lugre_step(f, vv, rec.g[i + 1])
            u = delta if u > 0 else -delta
            if delta <= 0.0:
                u = 0.0
        else:
            fcf, fcb = rec.fcf[i + 1], rec.fcb[i + 1]
            hs = H / 4.0
            for _ in range(4):
                def rhs(ff):
                    vy = -ff / S2
                    gy = _g_dir(vy, fcf, fcb)
                    return S0 * vy * (1.0 - (1.0 if vy >= 0 else -1.0) * ff / gy), vy
                k1, vy1 = rhs(f)
                k2, vy2 = rhs(f + 0.5 * hs * k1)
                k3, vy3 = rhs(f + 0.5 * hs * k2)
                k4, vy4 = rhs(f + hs * k3)
                f = f + hs / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
                u = u + hs * (vv - (vy1 + 2 * vy2 + 2 * vy3 + vy4) / 6.0)
            if u >= delta:
                u = delta
            elif u <= -delta:
                u = -delta
    F[n - 1] = (f + S2 * v[n - 1]) if engaged else 0.0
    return F


def _series_link(rec, link_force, link_stiff, u0, fmax=9.0):
    """Drive link (force law link_force(u, udot_fn)) in series with the LuGre band contact.
    Massless drum: sigma2 vy = F_link - f.  States u = x - y and f.  RK4 with adaptive
    sub-steps (stability of the stiff link)."""
    n, v = rec.n, rec.v
    F = [0.0] * n
    f = rec.f0
    u = u0
    Fl = f
    for i in range(n - 1):
        vv = v[i + 1]
        fcf, fcb = rec.fcf[i + 1], rec.fcb[i + 1]
        F[i] = Fl

        def rhs(uu, ff):
            fl = link_force(uu, vv, ff)
            vy = (fl - ff) / S2
            gy = _g_dir(vy, fcf, fcb)
            sg = 1.0 if vy >= 0 else -1.0
            return vv - vy, S0 * vy * (1.0 - sg * ff / gy), fl
        kl = link_stiff(u, min(fmax, abs(Fl) + 1.5))
        nsub = int(H * kl / S2 / 1.0) + 1
        hs = H / nsub
        for _ in range(nsub):
            du1, df1, _f = rhs(u, f)
            du2, df2, _f = rhs(u + 0.5 * hs * du1, f + 0.5 * hs * df1)
            du3, df3, _f = rhs(u + 0.5 * hs * du2, f + 0.5 * hs * df2)
            du4, df4, _f = rhs(u + hs * du3, f + hs * df3)
            u += hs / 6.0 * (du1 + 2 * du2 + 2 * du3 + du4)
            f += hs / 6.0 * (df1 + 2 * df2 + 2 * df3 + df4)
        Fl = link_force(u, v[i + 1], f)
    F[n - 1] = Fl
    return F


def eff_backlash_hunt_crossley(rec, delta, fx):
    """B2: clearance delta (half-width) closed by a Hertzian contact with Hunt-Crossley
    hysteretic damping, F = K p^1.5 (1 + L pdot) with p the penetration.  The liner compliance
    scales with the clearance: K = F_ref / delta^1.5 (contact deflection = delta at F_ref)."""
    if delta <= 0:
        return list(rec.base())
    fref, e, vimp = fx['F_ref_kip'], fx['restitution'], fx['v_impact_in_s']
    K = fref / delta ** 1.5
    LAM = 1.5 * (1.0 - e) * K / vimp

    def link_force(uu, vv, ff):
        p = abs(uu) - delta
        if p <= 0.0:
            return 0.0
        s = 1.0 if uu > 0 else -1.0
        P = p ** 1.5
        fl = (s * K * P + LAM * P * (vv + ff / S2)) / (1.0 + LAM * P / S2)
        if s * fl < 0.0:
            return 0.0
        return fl

    def link_stiff(uu, fm):
        return 1.5 * K ** (2.0 / 3.0) * fm ** (1.0 / 3.0)
    f0 = rec.f0
    p0 = (abs(f0) / K) ** (2.0 / 3.0)
    u0 = (delta + p0) * (1.0 if f0 >= 0 else -1.0)
    return _series_link(rec, link_force, link_stiff, u0)


def eff_backlash_antagonistic_bands(rec, u0s, fx):
    """B3: the drive acts through an antagonistic pair of slack-prone bands with exponential
    (Fung-type) tension-stretch laws, T+- = (K0/2) exp(+-u/u0): F_link = K0 sinh(u/u0).  Soft
    backlash: near-zero stiffness K0/u0 around the force zero crossing, stiffening with load."""
    if u0s <= 0:
        return list(rec.base())
    K0 = fx['K0_kip']

    def link_force(uu, vv, ff):
        return K0 * math.sinh(uu / u0s)

    def link_stiff(uu, fm):
        return math.sqrt(K0 * K0 + fm * fm) / u0s
    f0 = rec.f0
    u0 = u0s * math.asinh(f0 / K0)
    return _series_link(rec, link_force, link_stiff, u0)


# ---------------------------------------------------------------- residual static ----------
def _rest_run(rec, step_fn):
    """Base stepping; after each step, if the drum rests (design mask), step_fn(i+1, t_rest, f)
    returns the modified f.  Rest time starts at T_PRE for a record that begins at rest."""
    n, v, g = rec.n, rec.v, rec.g
    F = [0.0] * n
    f = rec.f0
    rest = rec.rest
    tr = 30.0 if rest[0] else 0.0
    for i in range(n - 1):
        F[i] = f + S2 * v[i]
        f = lugre_step(f, v[i + 1], g[i + 1])
        if rest[i + 1]:
            tr += H
            f = step_fn(i + 1, tr, f)
        else:
            tr = 0.0
    F[n - 1] = f + S2 * v[n - 1]
    return F


def eff_residual_kww(rec, rho, fx):
    """R1: stretched-exponential (Kohlrausch-Williams-Watts) relaxation of the held band force:
    F(t) = F_stop [1 - rho (1 - exp(-(t/tau)^beta))] while the drum rests."""
    tau, beta = fx['tau_s'], fx['beta']

    def phi(t):
        return 1.0 - rho * (1.0 - math.exp(-(t / tau) ** beta))

    def step(i, tr, f):
        return f * phi(tr) / phi(tr - H)
    return _rest_run(rec, step)


def eff_residual_logcreep(rec, a, fx):
    """R2: logarithmic (rate-and-state / Dieterich-type) creep relaxation of the held force,
    proportional to the clamping level: |F| drops by a * Fc_dir * ln(1 + t/t_c); never
    changes sign."""
    tc = fx['t_c_s']

    def step(i, tr, f):
        fc = rec.fcf[i] if f >= 0 else rec.fcb[i]
        d = a * fc * (math.log1p(tr / tc) - math.log1p((tr - H) / tc))
        if f >= 0:
            return f - d if f - d > 0 else 0.0
        return f + d if f + d < 0 else 0.0
    return _rest_run(rec, step)


def eff_residual_maxwell_setpoint(rec, rho, fx):
    """R3: Maxwell (single exponential) relaxation of the held force toward a non-zero
    equilibrium F_eq set by the pre-tension imbalance of the two band ends:
    F(t) = F_eq + (F_stop - F_eq) [1 - rho (1 - exp(-t/tau))]."""
    tau, feq = fx['tau_s'], fx['F_eq_kip']

    def D(t):
        return 1.0 - rho * (1.0 - math.exp(-t / tau))

    def step(i, tr, f):
        return feq + (f - feq) * D(tr) / D(tr - H)
    return _rest_run(rec, step)


# ---------------------------------------------------------------- transition shape ---------
def eff_transition_elastoplastic(rec, rho, fx):
    """T1: elasto-plastic pre-sliding (Dupont et al. 2002) blended into LuGre's drift:
    f' = sigma0 (v - alpha |v| f / g), alpha = (1-rho) + rho alpha_EP(f, v).  alpha_EP = 0 while
    unloading after a reversal (purely elastic, no bristle drift) and while |f| < w_ba Fc on
    reloading (pure pre-sliding), a sine ramp to 1 at |f| = Fc (kinetic level of the current
    direction), 1 beyond.  Steady sliding (|f| = g >= Fc) and the held levels are unchanged."""
    wba = fx['w_ba']
    n, v, g = rec.n, rec.v, rec.g
    F = [0.0] * n
    f = rec.f0
    pi = math.pi
    for i in range(n - 1):
        F[i] = f + S2 * v[i]
        vv = v[i + 1]
        gg = g[i + 1]
        fk = rec.fcf[i + 1] if vv >= 0 else rec.fcb[i + 1]
        av = abs(vv)

        def rhs(ff):
            if vv * ff <= 0.0:
                aep = 0.0
            else:
                w = abs(ff) / fk
                if w <= wba:
                    aep = 0.0
                elif w >= 1.0:
                    aep = 1.0
                else:
                    aep = 0.5 + 0.5 * math.sin(pi * (w - 0.5 * (1.0 + wba)) / (1.0 - wba))
            al = (1.0 - rho) + rho * aep
            return S0 * (vv - al * av * ff / gg)
        ns = int(S0 * av / gg * H / 0.05) + 1
        hs = H / ns
        for _ in range(ns):
            k1 = rhs(f)
            k2 = rhs(f + 0.5 * hs * k1)
            k3 = rhs(f + 0.5 * hs * k2)
            k4 = rhs(f + hs * k3)
            f = f + hs / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    F[n - 1] = f + S2 * v[n - 1]
    return F


def _iwan_part(rec, fx):
    ne = fx['n_elements']
    ke = S0 / ne
    n, v, g = rec.n, rec.v, rec.g
    w = [(2 * k - 1) / ne ** 2 for k in range(1, ne + 1)]
    g0 = g[0]
    els = []
    for k in range(ne):
        fk = rec.f0 * w[k]
        lim = w[k] * g0
        els.append(max(-lim, min(lim, fk)))
    out = [0.0] * n
    for i in range(n - 1):
        out[i] = sum(els)
        dxx = v[i + 1] * H
        gg = g[i + 1]
        for k in range(ne):
            lim = w[k] * gg
            e = els[k] + ke * dxx
            els[k] = lim if e > lim else (-lim if e < -lim else e)
    out[n - 1] = sum(els)
    return out


def eff_transition_iwan(rec, lam, fx):
    """T2: a fraction lam of the band contact behaves as an Iwan / Maxwell-slip bank (parallel
    elasto-slip elements, total stiffness sigma0, uniformly distributed break-away displacements
    up to 2 g/sigma0, slip forces summing to g(v); Masing rules).  Sliding level unchanged."""
    base = rec.base()
    key = ('iwan', fx['n_elements'])
    cache = getattr(rec, '_cache', None)
    if cache is None:
        rec._cache = cache = {}
    if key not in cache:
        cache[key] = _iwan_part(rec, fx)
    iw = cache[key]
    v = rec.v
    return [base[i] + lam * (iw[i] + S2 * v[i] - base[i]) for i in range(rec.n)]


def _bs_part(rec, fx):
    e1, e2 = fx['eps1_in'], fx['eps2_in']
    n, v = rec.n, rec.v
    s0 = 1.0 if rec.f0 >= 0 else -1.0
    w1 = w2 = s0
    out = [0.0] * n
    for i in range(n - 1):
        fc = rec.fcf[i] if v[i] >= 0 else rec.fcb[i]
        out[i] = 0.5 * fc * (w1 - w2)
        vv = v[i + 1]
        sg = 1.0 if vv >= 0 else -1.0
        ds = abs(vv) * H
        w1 = sg + (w1 - sg) * math.exp(-ds / e1)
        w2 = sg + (w2 - sg) * math.exp(-ds / e2)
    fc = rec.fcf[n - 1] if v[n - 1] >= 0 else rec.fcb[n - 1]
    out[n - 1] = 0.5 * fc * (w1 - w2)
    return out


def eff_transition_bliman_sorine(rec, A, fx):
    """T3: Bliman-Sorine-type second-order transition in the travel domain: an extra force
    A Fc (w1 - w2)/2 with dw_j/ds = (sgn v - w_j)/eps_j, eps1 < eps2: a travel-domain overshoot
    (peak) after each reversal that vanishes in steady sliding."""
    base = rec.base()
    cache = getattr(rec, '_cache', None)
    if cache is None:
        rec._cache = cache = {}
    key = ('bs', fx['eps1_in'], fx['eps2_in'])
    if key not in cache:
        cache[key] = _bs_part(rec, fx)
    bs = cache[key]
    return [base[i] + A * bs[i] for i in range(rec.n)]


# ---------------------------------------------------------------- velocity -----------------
def eff_velocity_ratestate_log(rec, a, fx):
    """V1: rate-strengthening steady-state friction of rate-and-state type:
    g -> g [1 + a ln(1 + |v|/v_star)]."""
    vst = fx['v_star_in_s']
    v = rec.v
    g = [rec.g[i] * (1.0 + a * math.log1p(abs(v[i]) / vst)) for i in range(rec.n)]
    return run_g(v, g, rec.f0)


def eff_velocity_flash_weakening(rec, c, fx):
    """V2: flash-heating weakening (Rice 2006): above the weakening speed v_w the friction
    falls as mu_w + (mu_0 - mu_w) v_w/|v|:  g -> g [1 - c (1 - v_w/|v|)] for |v| > v_w."""
    vw = fx['v_w_in_s']
    v = rec.v
    g = []
    for i in range(rec.n):
        av = abs(v[i])
        phi = 1.0 - c * (1.0 - vw / av) if av > vw else 1.0
        g.append(rec.g[i] * phi)
    return run_g(v, g, rec.f0)


def eff_velocity_grosch_bell(rec, A, fx):
    """V3: viscoelastic (Grosch-type) friction peak of the polymer lining: a bell in log speed,
    g -> g [1 + A exp(-(log10(|v|/v_p))^2 / (2 w^2))]."""
    vp, wd = fx['v_peak_in_s'], fx['width_decades']
    v = rec.v
    g = []
    for i in range(rec.n):
        av = abs(v[i])
        if av < 1e-9:
            phi = 1.0
        else:
            L = math.log10(av / vp)
            phi = 1.0 + A * math.exp(-L * L / (2 * wd * wd))
        g.append(rec.g[i] * phi)
    return run_g(v, g, rec.f0)


# ---------------------------------------------------------------- actuator lag -------------
def _g_from_positions(rec, q1, q2):
    n = rec.n
    fcf = [eq4(True, q1[i] - rec.x1p, q2[i] - rec.x2p) for i in range(n)]
    fcb = [eq4(False, q1[i] - rec.x1p, q2[i] - rec.x2p) for i in range(n)]
    return rec.g_from_fc(fcf, fcb)


def eff_lag_delay(rec, tau, fx):
    """A1: pure transport delay tau between actuator positions and band clamping."""
    n = rec.n
    sh = tau / DT

    def delayed(p):
        out = []
        for i in range(n):
            t = i - sh
            if t <= 0:
                out.append(p[0])
            else:
                j = int(t)
                fr = t - j
                out.append(p[j] + fr * (p[j + 1] - p[j]) if j + 1 < n else p[j])
        return out
    return run_g(rec.v, _g_from_positions(rec, delayed(rec.p1), delayed(rec.p2)), rec.f0)


def eff_lag_second_order(rec, T, fx):
    """A2: under-damped second-order band-tension dynamics, q'' + 2 zeta w q' + w^2 q = w^2 x,
    w = 1/T (ringing, phase lag)."""
    if T <= 0:
        return list(rec.base())
    zeta = fx['zeta']
    w = 1.0 / T
    n = rec.n
    nsub = int(H * w / 0.15) + 1
    hs = H / nsub

    def filt(p):
        q, qd = p[0], 0.0
        out = [q]
        for i in range(n - 1):
            xt = p[i + 1]
            for _ in range(nsub):
                def r(a, b):
                    return b, w * w * (xt - a) - 2 * zeta * w * b
                k1 = r(q, qd)
                k2 = r(q + 0.5 * hs * k1[0], qd + 0.5 * hs * k1[1])
                k3 = r(q + 0.5 * hs * k2[0], qd + 0.5 * hs * k2[1])
                k4 = r(q + hs * k3[0], qd + hs * k3[1])
                q += hs / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
                qd += hs / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            out.append(q)
        return out
    return run_g(rec.v, _g_from_positions(rec, filt(rec.p1), filt(rec.p2)), rec.f0)


def eff_lag_zener(rec, rho, fx):
    """A3: standard-linear-solid (Zener) band: a fraction (1-rho) of the actuator travel reaches
    the clamping at once, the rest through a first-order creep with time constant tau."""
    tau = fx['tau_s']
    n = rec.n
    c = math.exp(-H / tau)

    def filt(p):
        lp = p[0]
        out = [p[0]]
        for i in range(1, n):
            lp = p[i] + (lp - p[i]) * c
            out.append((1.0 - rho) * p[i] + rho * lp)
        return out
    return run_g(rec.v, _g_from_positions(rec, filt(rec.p1), filt(rec.p2)), rec.f0)


# ---------------------------------------------------------------- self-energizing ----------
def eff_selfenerg_capstan_position(rec, kappa, fx):
    """S1: capstan (Euler-Eytelwein) wrap that changes with drum rotation: moving away from the
    centre winds the loaded band further round the drum, g -> g exp(kappa x sgn v)."""
    v, x = rec.v, rec.x
    g = [rec.g[i] * math.exp(kappa * x[i] * (1.0 if v[i] >= 0 else -1.0)) for i in range(rec.n)]
    return run_g(v, g, rec.f0)


def eff_selfenerg_servo(rec, beta, fx):
    """S2: servo (duo-servo brake) feedback: the friction transmitted by the band feeds its
    tension through the anchor linkage, building up over the drum travel ell:
    du/ds = (beta max(0, f sgn v)/b_dir - u)/ell,  g -> g (1 + u)."""
    ell = fx['ell_in']
    n, v, g = rec.n, rec.v, rec.g
    F = [0.0] * n
    f = rec.f0
    u = beta * abs(f) / (FCF if f >= 0 else FCB)
    for i in range(n - 1):
        F[i] = f + S2 * v[i]
        vv = v[i + 1]
        gg = g[i + 1]
        av = abs(vv)
        sg = 1.0 if vv >= 0 else -1.0
        bref = FCF if vv >= 0 else FCB

        def rhs(ff, uu):
            df = S0 * (vv - av * ff / (gg * (1.0 + uu)))
            t = ff * sg
            du = av / ell * (beta * (t if t > 0 else 0.0) / bref - uu)
            return df, du
        ns = int(S0 * av / gg * H / 0.05) + 1
        hs = H / ns
        for _ in range(ns):
            k1 = rhs(f, u)
            k2 = rhs(f + 0.5 * hs * k1[0], u + 0.5 * hs * k1[1])
            k3 = rhs(f + 0.5 * hs * k2[0], u + 0.5 * hs * k2[1])
            k4 = rhs(f + hs * k3[0], u + hs * k3[1])
            f += hs / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            u += hs / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    F[n - 1] = f + S2 * v[n - 1]
    return F


def travel_since_reversal(v, thr):
    """Drum travel since the last reversal; a reversal is declared once the travel against the
    current direction exceeds thr (so sensor noise at rest does not reset it)."""
    n = len(v)
    out = [0.0] * n
    d = 1.0
    s = 1.0e3       # long travel before the record
    back = 0.0
    for i in range(n):
        dsd = v[i] * H * d
        if dsd >= 0:
            s += dsd
            back = 0.0
        else:
            back -= dsd
            if back > thr:
                d = -d
                s = back
                back = 0.0
        out[i] = s
    return out


def eff_selfenerg_wrap_buildup(rec, kappa, fx):
    """S3: wrap build-up with travel: after a reversal the newly loaded band is drawn round the
    drum and its wrap angle grows with travel s, saturating at s_w:
    g -> g exp(kappa s_w tanh(s/s_w))."""
    sw = fx['s_w_in']
    key = ('trav', fx['reversal_threshold_in'])
    cache = getattr(rec, '_cache', None)
    if cache is None:
        rec._cache = cache = {}
    if key not in cache:
        cache[key] = travel_since_reversal(rec.v, fx['reversal_threshold_in'])
    s = cache[key]
    g = [rec.g[i] * math.exp(kappa * sw * math.tanh(s[i] / sw)) for i in range(rec.n)]
    return run_g(rec.v, g, rec.f0)


# ---------------------------------------------------------------- pretension ---------------
def _fc_law(rec, law):
    n = rec.n
    fcf, fcb = [0.0] * n, [0.0] * n
    for i in range(n):
        for fwd in (True, False):
            b, a1, a2 = (FCF, A1F, A2F) if fwd else (FCB, A1B, A2B)
            r = law(b, a1, a2, rec.dx1[i], rec.dx2[i])
            r = r if r > FLOOR else FLOOR
            if fwd:
                fcf[i] = r
            else:
                fcb[i] = r
    return rec.g_from_fc(fcf, fcb)


def eff_pretension_exponential(rec, q, fx):
    """P1: exponential (capstan-like, wrap grows with band take-up) clamping law with the
    paper's slope at x': Fc = b + (exp(q D) - 1)/q, D = the paper's linear increment (kip)."""
    def law(b, a1, a2, d1, d2):
        D = a1 * d1 + a2 * d2
        if q < 1e-12:
            return b + D
        return b + math.expm1(q * D) / q
    return run_g(rec.v, _fc_law(rec, law), rec.f0)


def eff_pretension_deadband(rec, d, fx):
    """P2: band-seating dead band at each band end (clevis clearance / liner seating): the travel
    that reaches the band is the soft-thresholded u - d tanh(u/d)."""
    def D(u):
        return u - d * math.tanh(u / d) if d > 0 else u

    def law(b, a1, a2, d1, d2):
        return b + a1 * D(d1) + a2 * D(d2)
    return run_g(rec.v, _fc_law(rec, law), rec.f0)


def eff_pretension_saturating(rec, q, fx):
    """P3: slip-limited band anchor / tension saturation: the clamping increment saturates,
    Fc = b + S tanh(D/S), S = 1/q (same slope at x', softening for both signs)."""
    def law(b, a1, a2, d1, d2):
        D = a1 * d1 + a2 * d2
        if q < 1e-12:
            return b + D
        return b + math.tanh(D * q) / q
    return run_g(rec.v, _fc_law(rec, law), rec.f0)


# ---------------------------------------------------------------- asymmetry ----------------
def eff_asym_stiffness(rec, a, fx):
    """Y1: direction-dependent pre-sliding stiffness (the backward-loaded band pair and the
    forward-loaded single band have different compliance): sigma0_bwd = sigma0 (1 + a)."""
    v = rec.v
    k = [S0 if v[i] >= 0 else S0 * (1.0 + a) for i in range(rec.n)]
    return run_g(v, rec.g, rec.f0, k)


def eff_asym_stribeck(rec, m, fx):
    """Y2: direction-dependent Stribeck decay speed (anisotropic lining): backward uses
    v_s,bwd = v_s (1 + m) (m < 0 allowed via fixed sign)."""
    sgn = fx['sign']
    vsb = VS * (1.0 + sgn * m)
    v = rec.v
    g = []
    for i in range(rec.n):
        if v[i] >= 0:
            g.append(rec.g[i])
        else:
            fc = rec.fcb[i]
            g.append(fc + (FSB - fc) * math.exp(-(v[i] / vsb) ** 2))
    return run_g(v, g, rec.f0)


def eff_asym_viscous_split(rec, a, fx):
    """Y3: direction-dependent viscous (rate) term of the lining, split antisymmetrically about
    the paper's single sigma2: sigma2_fwd = sigma2 (1 + a), sigma2_bwd = sigma2 (1 - a); the
    force gains a sigma2 |v| offset that does not reverse with the direction."""
    base = rec.base()
    v = rec.v
    return [base[i] + a * S2 * abs(v[i]) for i in range(rec.n)]


# =============================================================================================
#  Shape catalogue: category, shape, function, amplitude name, bounds, fixed parameters,
#  source, whether F is linear in the amplitude.
# =============================================================================================
SHAPES = {
    'backlash': [
        dict(shape='rigid_play_deadzone', fn=eff_backlash_rigid_play, amp='half_gap_in',
             lo=0.0, hi=0.20, fixed={}, linear=False),
        dict(shape='hertz_hunt_crossley_clearance', fn=eff_backlash_hunt_crossley,
             amp='half_gap_in', lo=0.0008, hi=0.20,
             fixed={'F_ref_kip': 3.0, 'restitution': 0.55, 'v_impact_in_s': 1.0}, linear=False),
        dict(shape='antagonistic_exponential_bands', fn=eff_backlash_antagonistic_bands,
             amp='u0_in', lo=0.0004, hi=0.05, fixed={'K0_kip': 0.08}, linear=False),
    ],
    'residual_static': [
        dict(shape='kww_stretched_exponential_relaxation', fn=eff_residual_kww, amp='rho',
             lo=0.0, hi=0.85, fixed={'tau_s': 1.5, 'beta': 0.45, 'rest_before_record_s': 30.0},
             linear=False),
        dict(shape='logarithmic_creep_relaxation', fn=eff_residual_logcreep, amp='a',
             lo=0.0, hi=0.40, fixed={'t_c_s': 0.08, 'rest_before_record_s': 30.0}, linear=False),
        dict(shape='maxwell_relaxation_to_imbalance', fn=eff_residual_maxwell_setpoint, amp='rho',
             lo=0.0, hi=0.90, fixed={'tau_s': 0.9, 'rest_before_record_s': 30.0}, linear=False),
    ],
    'transition_shape': [
        dict(shape='elastoplastic_presliding', fn=eff_transition_elastoplastic, amp='rho',
             lo=0.0, hi=1.0, fixed={'w_ba': 0.9}, linear=False),
        dict(shape='iwan_maxwell_slip_bank', fn=eff_transition_iwan, amp='fraction',
             lo=0.0, hi=1.0, fixed={'n_elements': 12}, linear=True),
        dict(shape='bliman_sorine_travel_overshoot', fn=eff_transition_bliman_sorine, amp='A',
             lo=0.0, hi=1.5, fixed={'eps1_in': 0.03, 'eps2_in': 0.12}, linear=True),
    ],
    'velocity': [
        dict(shape='rate_state_log_strengthening', fn=eff_velocity_ratestate_log, amp='a',
             lo=0.0, hi=0.35, fixed={'v_star_in_s': 0.05}, linear=False),
        dict(shape='flash_heating_weakening', fn=eff_velocity_flash_weakening, amp='c',
             lo=0.0, hi=0.75, fixed={'v_w_in_s': 0.5}, linear=False),
        dict(shape='grosch_viscoelastic_bell', fn=eff_velocity_grosch_bell, amp='A',
             lo=0.0, hi=1.2, fixed={'v_peak_in_s': 1.8, 'width_decades': 0.3}, linear=False),
    ],
    'actuator_lag': [
        dict(shape='transport_delay', fn=eff_lag_delay, amp='tau_s',
             lo=0.0, hi=0.3, fixed={}, linear=False),
        dict(shape='underdamped_second_order', fn=eff_lag_second_order, amp='T_s',
             lo=0.0, hi=0.2, fixed={'zeta': 0.25}, linear=False),
        dict(shape='zener_standard_linear_solid', fn=eff_lag_zener, amp='rho',
             lo=0.0, hi=1.0, fixed={'tau_s': 0.7}, linear=False),
    ],
    'self_energizing': [
        dict(shape='capstan_position_wrap', fn=eff_selfenerg_capstan_position, amp='kappa_per_in',
             lo=0.0, hi=0.6, fixed={}, linear=False),
        dict(shape='servo_tension_feedback', fn=eff_selfenerg_servo, amp='beta',
             lo=0.0, hi=0.25, fixed={'ell_in': 0.2}, linear=False),
        dict(shape='wrap_buildup_with_travel', fn=eff_selfenerg_wrap_buildup, amp='kappa_per_in',
             lo=0.0, hi=0.9, fixed={'s_w_in': 0.5, 'reversal_threshold_in': 0.004},
             linear=False),
    ],
    'pretension': [
        dict(shape='exponential_capstan_law', fn=eff_pretension_exponential, amp='q_per_kip',
             lo=0.0, hi=1.0, fixed={}, linear=False),
        dict(shape='band_seating_deadband', fn=eff_pretension_deadband, amp='d_in',
             lo=0.0, hi=0.04, fixed={}, linear=False),
        dict(shape='saturating_anchor_law', fn=eff_pretension_saturating, amp='q_per_kip',
             lo=0.0, hi=3.0, fixed={}, linear=False),
    ],
    'asymmetry': [
        dict(shape='directional_presliding_stiffness', fn=eff_asym_stiffness, amp='a',
             lo=0.0, hi=1.2, fixed={}, linear=False),
        dict(shape='directional_stribeck_speed', fn=eff_asym_stribeck, amp='m',
             lo=0.0, hi=2.5, fixed={}, linear=False),
        dict(shape='directional_viscous_split', fn=eff_asym_viscous_split, amp='a',
             lo=0.0, hi=0.9, fixed={}, linear=True),
    ],
}
CATEGORIES = list(SHAPES.keys())

SOURCES = {
    'rigid_play_deadzone': 'dead-zone/play backlash model: Nordin & Gutman 2002, Automatica 38:1633; '
                           'Tao & Kokotovic 1996, Adaptive Control of Systems with Actuator and Sensor Nonlinearities',
    'hertz_hunt_crossley_clearance': 'clearance joint with Hertz contact and Hunt-Crossley damping: Hunt & Crossley 1975, '
                                     'J. Appl. Mech. 42:440; Lankarani & Nikravesh 1990, J. Mech. Des. 112:369',
    'antagonistic_exponential_bands': 'antagonistic tendon/band pair with exponential (Fung) tension-stretch law: '
                                      'Fung 1967, Am. J. Physiol. 213:1532; soft backlash, Nordin & Gutman 2002',
    'kww_stretched_exponential_relaxation': 'Kohlrausch-Williams-Watts stretched exponential: Williams & Watts 1970, '
                                            'Trans. Faraday Soc. 66:80',
    'logarithmic_creep_relaxation': 'logarithmic time dependence of frictional contacts (rate-and-state): Dieterich 1972, '
                                    'JGR 77:3690; Baumberger & Caroli 2006, Adv. Phys. 55:279',
    'maxwell_relaxation_to_imbalance': 'Maxwell (Debye) single-time-constant stress relaxation toward a residual '
                                       'equilibrium; BRFD residual static force: Coble et al. (seed paper, Fig. 14)',
    'elastoplastic_presliding': 'single-state elasto-plastic friction: Dupont, Hayward, Armstrong & Altpeter 2002, '
                                'IEEE TAC 47:787',
    'iwan_maxwell_slip_bank': 'Iwan 1966, J. Appl. Mech. 33:893; Maxwell-slip/GMS: Al-Bender, Lampaert & Swevers '
                              '2005, IEEE TAC 50:1883',
    'bliman_sorine_travel_overshoot': 'Bliman & Sorine 1995, Proc. 3rd ECC (space-domain second-order dry friction '
                                      'with stiction-like peak)',
    'rate_state_log_strengthening': 'rate-and-state steady-state friction a ln(v): Dieterich 1979, JGR 84:2161; '
                                    'Ruina 1983, JGR 88:10359; Marone 1998, Annu. Rev. Earth Planet. Sci. 26:643',
    'flash_heating_weakening': 'flash heating: Rice 2006, JGR 111:B05311; Goldsby & Tullis 2011, Science 334:216',
    'grosch_viscoelastic_bell': 'viscoelastic friction peak of polymers/rubber: Grosch 1963, Proc. R. Soc. A 274:21',
    'transport_delay': 'time delay in semi-active/active structural control: Agrawal & Yang 2000, EESD 29:37',
    'underdamped_second_order': 'second-order actuator/band-tension dynamics (servo actuator models, e.g. Dyke et al. '
                                '1995, J. Eng. Mech. 121:322)',
    'zener_standard_linear_solid': 'standard linear solid (Zener 1948, Elasticity and Anelasticity of Metals)',
    'capstan_position_wrap': 'capstan / Euler-Eytelwein band-brake equation with wrap angle changing with drum '
                             'rotation; self-energizing band: seed paper, Cao et al. 2015 JSV 348:41',
    'servo_tension_feedback': 'servo (duo-servo/self-energizing) brake action: Cao et al. 2015, JSV 348:41; '
                              'Limpert, Brake Design and Safety',
    'wrap_buildup_with_travel': 'band drawn taut by rotation (seed paper, Fig. 2-3) with capstan amplification',
    'exponential_capstan_law': 'capstan amplification growing with take-up (Euler-Eytelwein); amplification '
                               'rising with applied tension: seed paper Fig. 10',
    'band_seating_deadband': 'dead-zone nonlinearity (clearance at the band clevis / liner seating): Tao & '
                             'Kokotovic 1996',
    'saturating_anchor_law': 'slip-limited (Coulomb) band anchor / tension saturation',
    'directional_presliding_stiffness': 'direction-dependent LuGre parameters (asymmetric friction): '
                                        'Armstrong-Helouvry, Dupont & Canudas de Wit 1994, Automatica 30:1083',
    'directional_stribeck_speed': 'direction-dependent Stribeck curve (anisotropic surfaces): Armstrong-Helouvry et '
                                  'al. 1994; Bo & Pavelescu 1982, Wear 82:277',
    'directional_viscous_split': 'direction-dependent viscous (rate) friction of a lining: Armstrong-Helouvry et al. '
                                 '1994',
}


def shape_entry(cat, shape):
    for e in SHAPES[cat]:
        if e['shape'] == shape:
            return e
    raise KeyError(shape)


def true_force(rec, cat, shape, amp, fixed):
    if cat == 'none':
        return list(rec.base())
    return shape_entry(cat, shape)['fn'](rec, amp, fixed)


# =============================================================================================
#  Templates and motion design
# =============================================================================================
def _ma(a, w):
    n = len(a)
    h = w // 2
    pre = [0.0] * (n + 1)
    s = 0.0
    for i in range(n):
        s += a[i]
        pre[i + 1] = s
    out = []
    for i in range(n):
        lo = max(0, i - h)
        hi = min(n, i + h + 1)
        out.append((pre[hi] - pre[lo]) / (hi - lo))
    return out


def tension_model(F, dx1, dx2):
    """Load-cell forces (lb) of the two electric actuators from the friction force (kip):
    taut end ~ F / C, slack end ~ 34 lb (fitted to the measured semi-active files)."""
    def sp(u):
        w = 0.3
        return w * math.log1p(math.exp(u / w)) if u / w < 40 else u
    t1 = 34.0 + 490.0 * sp(-F) - 140.0 * dx1
    t2 = 34.0 + 520.0 * sp(F) - 150.0 * dx2
    return t1, t2


class Template:
    def __init__(self, name):
        d = json.load(open(os.path.join(TEMPLATE_DIR, name)))['data']
        self.name = name
        n = self.n = len(d)
        x = [r[1] for r in d]
        self.xs = _ma(_ma(x, 31), 31)
        self.x1p, self.x2p = d[0][4], d[0][5]
        t10, t20 = d[0][6], d[0][7]
        # commanded actuator travel = measured position change minus rod deflection
        self.c1 = [r[4] - self.x1p - DEFL_IN_PER_LB * (r[6] - t10) for r in d]
        self.c2 = [r[5] - self.x2p - DEFL_IN_PER_LB * (r[7] - t20) for r in d]
        xs = self.xs
        peaks = []
        for i in range(300, int(13.6 * FS_HZ)):
            a, b, c = xs[i - 1], xs[i], xs[i + 1]
            if (b >= a and b > c) or (b <= a and b < c):
                if abs(b - xs[i - 150]) > 0.01 and abs(b - xs[i + 150]) > 0.01:
                    if not peaks or i - peaks[-1] > 300:
                        peaks.append(i)
        self.peaks = peaks
        self.f_start = d[0][2]


class Motion:
    def __init__(self, p0):
        self.x = [p0]
        self.segments = []

    def append_seg(self, tp, i0, i1, s, r, kind):
        n_new = max(2, int(round((i1 - i0) * r)))
        p = self.x[-1]
        base_x = tp.xs[i0]
        xs = tp.xs
        for j in range(1, n_new + 1):
            t = i0 + j * (i1 - i0) / n_new
            k = int(t)
            if k >= i1:
                k, fr = i1 - 1, 1.0
            else:
                fr = t - k
            self.x.append(p + s * (xs[k] + fr * (xs[k + 1] - xs[k]) - base_x))
        self.segments.append(dict(kind=kind, template=tp.name, t0=round(i0 * DT, 4),
                                  t1=round(i1 * DT, 4), scale=round(s, 4), stretch=round(r, 4)))

    def hold(self, nh):
        p = self.x[-1]
        self.x.extend([p] * nh)
        self.segments.append(dict(kind='rest', seconds=round(nh * DT, 4)))


def _seg_range(tp, i0, i1):
    b = tp.xs[i0]
    seg = tp.xs[i0:i1 + 1]
    return min(seg) - b, max(seg) - b, max(abs(seg[k + 1] - seg[k]) for k in range(len(seg) - 1)) / DT


def _pick_scale_stretch(rng, p, rmin, rmax, vmax):
    smax = 1.25
    if rmax > 1e-9:
        smax = min(smax, (TRAVEL_LIMIT - p) / rmax)
    if rmin < -1e-9:
        smax = min(smax, (TRAVEL_LIMIT + p) / (-rmin))
    if smax < 0.3:
        return None
    s = rng.uniform(min(0.5, smax), smax)
    # speed factor relative to the measured test (peak ~3.2 in/s), kept realistic
    sp = rng.uniform(0.45, 1.2)
    r = s / sp
    r = max(r, s * vmax / VMAX_DESIGN, 0.6)
    if r > 2.5:
        return None
    return s, r


def template_events(templates):
    """Electric-actuator motion events of the measured tests (the commanded harmonic travel in
    selected drum cycles), each padded with 0.1 s of quiet."""
    ev = []
    for tp in templates:
        act = [max(abs(a), abs(b)) > 0.002 for a, b in zip(tp.c1, tp.c2)]
        i = 0
        n = tp.n
        while i < n:
            if act[i]:
                j = i
                last = i
                while j < n and (act[j] or j - last < int(0.6 * FS_HZ)):
                    if act[j]:
                        last = j
                    j += 1
                a0 = max(0, i - int(0.1 * FS_HZ))
                a1 = min(n - 1, last + int(0.1 * FS_HZ))
                ev.append(dict(template=tp.name, t0=round(a0 * DT, 4), t1=round(a1 * DT, 4),
                               c1=[tp.c1[k] - tp.c1[a0] for k in range(a0, a1 + 1)],
                               c2=[tp.c2[k] - tp.c2[a0] for k in range(a0, a1 + 1)]))
                i = last + 1
            else:
                i += 1
    return ev


def strokes_of(xd):
    n = len(xd)
    out = []
    i = 1
    while i < n - 1:
        d = xd[i + 1] - xd[i - 1]
        if abs(d) / (2 * DT) >= 0.004:
            sg = d > 0
            j = i
            while j < n - 1:
                dj = xd[j + 1] - xd[j - 1]
                if abs(dj) / (2 * DT) < 0.004 or (dj > 0) != sg:
                    break
                j += 1
            out.append((i, j))
            i = j + 1
        else:
            i += 1
    return out


def _event_pieces(e, rng):
    """A measured actuator event re-cut for a step-like command: the travel from rest to one
    extreme, a hold there, and the measured return from that extreme to rest."""
    c1, c2 = e['c1'], e['c2']
    dom = c1 if max(abs(a) for a in c1) >= max(abs(a) for a in c2) else c2
    L = len(dom)
    imin = min(range(L), key=lambda k: dom[k])
    imax = max(range(L), key=lambda k: dom[k])
    lo, hi = min(imin, imax), max(imin, imax)
    imid = min(range(lo, hi + 1), key=lambda k: abs(dom[k]))
    first = lo
    if rng.random() < 0.6:      # the first excursion of the measured event (a retraction)
        return (0, first), (first, imid)
    return (imid, hi), (hi, L - 1)


def _resample(seq, i0, i1, m):
    out = []
    for j in range(m + 1):
        t = i0 + (j * (i1 - i0) / m if m else 0)
        k = int(t)
        fr = t - k
        if k >= i1:
            k, fr = max(i0, i1 - 1), (1.0 if i1 > i0 else 0.0)
        out.append(seq[k] + fr * (seq[k + 1] - seq[k]) if i1 > i0 else seq[i0])
    return out


def design_actuators(rng, xd, events, act_on):
    """Electric-actuator travel: measured events (harmonic, or re-cut into step-like
    retract/extend - hold - return commands that may span several strokes) pasted into drum
    strokes, scaled and stretched."""
    n = len(xd)
    c1 = [0.0] * n
    c2 = [0.0] * n
    placed = []
    if not act_on:
        return c1, c2, placed
    p_act = rng.uniform(0.6, 1.0)
    p_step = rng.uniform(0.2, 1.0)
    strokes = [s for s in strokes_of(xd) if s[1] - s[0] >= int(0.4 * FS_HZ)]
    k = 0
    while k < len(strokes):
        s0, s1 = strokes[k]
        D = s1 - s0
        if rng.random() > p_act:
            k += 1
            continue
        e = rng.choice(events)
        a1 = rng.uniform(0.6, 1.5)
        a2 = rng.uniform(0.6, 1.5)
        swap = rng.random() < 0.3
        e1, e2 = (e['c2'], e['c1']) if swap else (e['c1'], e['c2'])
        L = len(e1)
        if rng.random() < p_step:
            kind = 'step'
            k_end = min(len(strokes) - 1, k + rng.choice([0, 0, 1, 1, 2]))
            st = s0 + int(rng.uniform(0.0, 0.25) * D)
            en = strokes[k_end][1] - int(rng.uniform(0.0, 0.25) * (strokes[k_end][1] - strokes[k_end][0]))
            m = en - st
            (i0, i1), (j0, j1) = _event_pieces(dict(c1=e1, c2=e2), rng)
            m_in = int(rng.uniform(0.1, 0.3) * FS_HZ)
            m_out = int(rng.uniform(0.1, 0.3) * FS_HZ)
            m_hold = m - m_in - m_out
            if m_hold < int(0.1 * FS_HZ):
                k += 1
                continue
            w1 = _resample(e1, i0, i1, m_in) + [e1[i1]] * m_hold + _resample(e1, j0, j1, m_out)[1:]
            w2 = _resample(e2, i0, i1, m_in) + [e2[i1]] * m_hold + _resample(e2, j0, j1, m_out)[1:]
            w1 = [a - w1[0] for a in w1]
            w2 = [a - w2[0] for a in w2]
            k = k_end + 1
        else:
            kind = 'harmonic'
            m = int(D * rng.uniform(0.7, 1.0))
            st = s0 + rng.randrange(0, D - m + 1)
            w1 = _resample(e1, 0, L - 1, m)
            w2 = _resample(e2, 0, L - 1, m)
            k += 1
        for j in range(len(w1)):
            if st + j < n:
                c1[st + j] += a1 * w1[j]
                c2[st + j] += a2 * w2[j]
        # whatever offset is left at the end of the event stays (actuator holds position)
        for kk in range(st + len(w1), n):
            c1[kk] += a1 * w1[-1]
            c2[kk] += a2 * w2[-1]
        placed.append(dict(kind=kind, template=e['template'], t0=e['t0'], t1=e['t1'],
                           at_s=round(st * DT, 4), seconds=round(len(w1) * DT, 4),
                           scale=[round(a1, 3), round(a2, 3)], swapped=swap))
    return c1, c2, placed


def design_motion(rng, templates, events, act_on):
    """Drum + actuator motion for one record from re-cut, scaled, stretched and joined pieces
    of the measured semi-active tests, with rests between strokes."""
    for _attempt in range(200):
        T_target = rng.uniform(9.0, 25.0)
        mo = Motion(rng.uniform(-0.25, 0.25))
        tp = rng.choice(templates)
        # initial rest, then the ramp-up of a test from rest to one of its first peaks
        mo.hold(int(rng.uniform(0.3, 1.5) * FS_HZ))
        ok = False
        for _ in range(30):
            k = rng.randrange(1, 6)
            rmin, rmax, vmax = _seg_range(tp, 0, tp.peaks[k])
            ss = _pick_scale_stretch(rng, mo.x[-1], rmin, rmax, vmax)
            if ss:
                mo.append_seg(tp, 0, tp.peaks[k], ss[0], ss[1], 'ramp-up')
                ok = True
                break
        if not ok:
            continue
        bad = False
        while len(mo.x) < (T_target - 3.0) * FS_HZ:
            if rng.random() < 0.75:
                mo.hold(int(rng.uniform(0.3, 3.0) * FS_HZ))
            placed = False
            for _ in range(60):
                tp2 = rng.choice(templates)
                pk = tp2.peaks
                nh = rng.randrange(1, 5)
                j = rng.randrange(0, len(pk) - nh)
                rmin, rmax, vmax = _seg_range(tp2, pk[j], pk[j + nh])
                ss = _pick_scale_stretch(rng, mo.x[-1], rmin, rmax, vmax)
                if ss:
                    mo.append_seg(tp2, pk[j], pk[j + nh], ss[0], ss[1], 'strokes')
                    placed = True
                    break
            if not placed:
                bad = True
                break
        if bad:
            continue
        # ending: ramp-down of a test to rest, or a final rest at a peak
        if rng.random() < 0.5:
            placed = False
            for _ in range(30):
                tp3 = rng.choice(templates)
                j = rng.randrange(len(tp3.peaks) - 3, len(tp3.peaks))
                rmin, rmax, vmax = _seg_range(tp3, tp3.peaks[j], tp3.n - 1)
                ss = _pick_scale_stretch(rng, mo.x[-1], rmin, rmax, vmax)
                if ss:
                    mo.append_seg(tp3, tp3.peaks[j], tp3.n - 1, ss[0], min(ss[1], 1.3),
                                  'ramp-down')
                    placed = True
                    break
            if not placed:
                mo.hold(int(rng.uniform(0.8, 2.5) * FS_HZ))
        else:
            mo.hold(int(rng.uniform(0.8, 2.5) * FS_HZ))
        n = len(mo.x)
        if n < 9 * FS_HZ + 1:
            mo.hold(9 * FS_HZ + 1 - n + int(rng.uniform(0.0, 1.0) * FS_HZ))
        if len(mo.x) > 25 * FS_HZ + 1:
            continue
        if max(abs(a) for a in mo.x) > 1.28:
            continue
        c1, c2, placed = design_actuators(rng, mo.x, events, act_on)
        mx = max(max(abs(a) for a in c1), max(abs(a) for a in c2))
        if (act_on and mx < 0.008) or mx > 0.047:
            continue
        mo.c1, mo.c2, mo.events = c1, c2, placed
        return mo
    raise RuntimeError('motion design failed')


def rest_mask(xd):
    n = len(xd)
    vd = [0.0] * n
    for i in range(1, n - 1):
        vd[i] = (xd[i + 1] - xd[i - 1]) / (2 * DT)
    vd[0], vd[-1] = vd[1], vd[-2]
    still = [abs(a) < 0.004 for a in vd]
    mask = [False] * n
    i = 0
    while i < n:
        if still[i]:
            j = i
            while j < n and still[j]:
                j += 1
            if j - i >= int(0.15 * FS_HZ):
                for k in range(i, j):
                    mask[k] = True
            i = j
        else:
            i += 1
    return mask


def quant(vals, q, off):
    return [off + q * round((a - off) / q) for a in vals]


def build_record(rng, templates, events, act_on):
    """Returns (Rec, columns dict, meta) with everything except the friction-force column."""
    mo = design_motion(rng, templates, events, act_on)
    n = len(mo.x)
    xoff = rng.uniform(0.0, Q_X)
    x = _f32(quant([a + rng.gauss(0.0, X_NOISE_SD) for a in mo.x], Q_X, xoff))
    tp0 = templates[0]
    x1p, x2p = tp0.x1p, tp0.x2p
    f_init = Q_F * round(rng.uniform(-0.6, 1.2) / Q_F)
    # pre-pass: base force with commanded positions -> rod deflections -> recorded positions
    p1c = [x1p + a for a in mo.c1]
    p2c = [x2p + a for a in mo.c2]
    Fpre = base_model(x, p1c, p2c, f_init)
    t10, t20 = tension_model(Fpre[0], 0.0, 0.0)
    p1, p2 = [], []
    for i in range(n):
        t1, t2 = tension_model(Fpre[i], mo.c1[i], mo.c2[i])
        p1.append(p1c[i] + DEFL_IN_PER_LB * (t1 - t10) + (rng.gauss(0.0, P_NOISE_SD) if i else 0.0))
        p2.append(p2c[i] + DEFL_IN_PER_LB * (t2 - t20) + (rng.gauss(0.0, P_NOISE_SD) if i else 0.0))
    p1 = _f32(quant(p1, Q_P, 0.0))
    p2 = _f32(quant(p2, Q_P, 0.0))
    rec = Rec(x, p1, p2, f_init, rest_mask(mo.x))
    runs = []
    i = 0
    while i < n:
        if rec.rest[i]:
            j = i
            while j < n and rec.rest[j]:
                j += 1
            runs.append([i, j])
            i = j
        else:
            i += 1
    meta = dict(seconds=round((n - 1) * DT, 4), samples=n, actuators_move=bool(act_on),
                actuator_peak_travel_in=round(max(max(abs(a) for a in mo.c1),
                                                  max(abs(a) for a in mo.c2)), 4),
                rest_fraction=round(sum(rec.rest) / n, 3), rest_intervals=runs,
                initial_force_kip=f_init,
                segments=mo.segments, actuator_events=mo.events)
    return rec, meta


def write_record(path, rec, F_true, noise_seed, noise_sd, tseed):
    n = rec.n
    nr = random.Random(noise_seed)
    Fm = [rec.f0] + [Q_F * round((F_true[i] + nr.gauss(0.0, noise_sd)) / Q_F) for i in range(1, n)]
    tr = random.Random(tseed)
    T1, T2 = [], []
    for i in range(n):
        t1, t2 = tension_model(F_true[i], rec.dx1[i], rec.dx2[i])
        T1.append(t1 + tr.gauss(0.0, T_NOISE_SD))
        T2.append(t2 + tr.gauss(0.0, T_NOISE_SD))
    T1 = quant(T1, Q_T1, OFF_T1)
    T2 = quant(T2, Q_T2, OFF_T2)
    c = math.exp(-DT / VEL_COL_TAU)
    lp = rec.v[0]
    vc = []
    for i in range(n):
        lp = rec.v[i] + (lp - rec.v[i]) * c
        vc.append(lp / VEL_COL_FACTOR + tr.gauss(0.0, 0.01 / VEL_COL_FACTOR))
    vc = _f32(vc)
    rows = []
    for i in range(n):
        rows.append([0 if i == 0 else i * DT, rec.x[i], Fm[i], vc[i], rec.p1[i], rec.p2[i],
                     T1[i], T2[i]])
    obj = {"data": rows}
    for k, val in HEADER:
        obj[k] = val
    with open(path, 'w') as fh:
        json.dump(obj, fh)
    return Fm


def rest_from_intervals(n, runs):
    m = [False] * n
    for a, b in runs:
        for k in range(a, b):
            m[k] = True
    return m


def load_record(path, meta=None):
    """Rebuild the model view of a written record (rest mask from the key's rest_intervals)."""
    obj = json.load(open(path))
    d = obj['data']
    x = [r[1] for r in d]
    p1 = [r[4] for r in d]
    p2 = [r[5] for r in d]
    rest = rest_from_intervals(len(d), meta['rest_intervals']) if meta else [False] * len(d)
    return Rec(x, p1, p2, d[0][2], rest), obj


def noise_array(seed, n, sd):
    nr = random.Random(seed)
    return [0.0] + [nr.gauss(0.0, sd) for _ in range(1, n)]


# =============================================================================================
#  Strength solving
# =============================================================================================
def ratio_of(recs, cat, shape, amp, fixed, sd):
    ss, nn = 0.0, 0
    for r in recs:
        Ft = true_force(r, cat, shape, amp, fixed)
        Fb = r.base()
        ss += sum((a - b) ** 2 for a, b in zip(Ft, Fb))
        nn += r.n
    return math.sqrt(ss / nn) / sd


def solve_amp(recs, cat, ent, fixed, sd, target, tol=1.5e-3):
    f = lambda a: ratio_of(recs, cat, ent['shape'], a, fixed, sd) - target
    lo, hi = ent['lo'], ent['hi']
    fhi = f(hi)
    if fhi < 0:
        return None, fhi + target
    if ent['linear']:
        r1 = fhi + target
        a = hi * target / r1
        return a, ratio_of(recs, cat, ent['shape'], a, fixed, sd)
    flo = f(lo)
    if flo > 0:
        return None, flo + target
    # Illinois regula falsi on a geometric-friendly bracket
    a, fa, b, fb = lo, flo, hi, fhi
    side = 0
    c, fc = b, fb
    for _ in range(60):
        c = (a * fb - b * fa) / (fb - fa)
        if not (min(a, b) < c < max(a, b)):
            c = 0.5 * (a + b)
        fc = f(c)
        if abs(fc) <= tol * target:
            break
        if fc * fb > 0:
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    if abs(fc) > tol * target:
        return None, fc + target
    return c, fc + target


# =============================================================================================
#  Main
# =============================================================================================
def plan(master):
    """Trial plan: 24 effect trials (3 shapes x 8 categories), 6 none, shuffled; 12 strong /
    12 weak with every category holding both a strong and a weak trial."""
    trials = []
    cats = CATEGORIES[:]
    master.shuffle(cats)
    two_strong = set(cats[:4])
    for cat in CATEGORIES:
        shapes = [e['shape'] for e in SHAPES[cat]]
        master.shuffle(shapes)
        ns = 2 if cat in two_strong else 1
        for k, sh in enumerate(shapes):
            trials.append(dict(category=cat, shape=sh, strength='strong' if k < ns else 'weak'))
    for _ in range(6):
        trials.append(dict(category='none', shape='none', strength='none'))
    master.shuffle(trials)
    for t in trials:
        t['seed'] = master.randrange(1, 2 ** 31 - 1)
    return trials


def make_trial(tid, tr, templates, events, outdir, log):
    rng = random.Random(tr['seed'])
    cat, shape, strength = tr['category'], tr['shape'], tr['strength']
    noise_sd = rng.uniform(0.02, 0.06)
    if strength == 'strong':
        target = rng.uniform(8.5, 11.5)
    elif strength == 'weak':
        target = rng.uniform(2.7, 3.8)
    else:
        target = 0.0
    ent = shape_entry(cat, shape) if cat != 'none' else None
    fixed = dict(ent['fixed']) if ent else {}
    if cat == 'residual_static' and shape == 'maxwell_relaxation_to_imbalance':
        fixed['F_eq_kip'] = round(rng.choice([-1, 1]) * rng.uniform(0.2, 0.6), 3)
    if cat == 'asymmetry' and shape == 'directional_stribeck_speed':
        fixed['sign'] = 1.0
    need_act = cat in ('actuator_lag', 'pretension')
    for attempt in range(40):
        recs, metas = [], []
        for _r in range(2):
            act_on = True if need_act else (rng.random() < 0.6)
            rec, meta = build_record(rng, templates, events, act_on)
            recs.append(rec)
            metas.append(meta)
        if cat == 'none':
            amp, got = 0.0, 0.0
            break
        amp, got = solve_amp(recs, cat, ent, fixed, noise_sd, target)
        log('  %s attempt %d: %s/%s target %.3f -> amp %s ratio %.4f' % (
            tid, attempt, cat, shape, target, None if amp is None else '%.6g' % amp, got))
        if amp is not None:
            break
    else:
        raise RuntimeError('%s: could not reach the target ratio' % tid)
    tdir = os.path.join(outdir, tid)
    os.makedirs(tdir, exist_ok=True)
    recinfo = {}
    for name, rec, meta in zip(('A', 'B'), recs, metas):
        Ft = true_force(rec, cat, shape, amp, fixed)
        nseed = rng.randrange(1, 2 ** 31 - 1)
        tseed = rng.randrange(1, 2 ** 31 - 1)
        write_record(os.path.join(tdir, name + '.json'), rec, Ft, nseed, noise_sd, tseed)
        meta['noise_seed'] = nseed
        meta['aux_seed'] = tseed
        recinfo[name] = meta
    entry = dict(category=cat, shape=shape, strength=strength, ratio=round(got, 4),
                 source=SOURCES.get(shape, ''),
                 ratio_target=round(target, 4), noise_kip=round(noise_sd, 6),
                 noise_kip_exact=noise_sd,
                 params=({ent['amp']: amp} if ent else {}),
                 fixed=fixed, amplitude_name=(ent['amp'] if ent else None),
                 amplitude_bounds=([ent['lo'], ent['hi']] if ent else None),
                 records=recinfo)
    if ent:
        entry['params'].update(fixed)
    return entry


def main():
    t0 = time.time()
    outdir = os.path.join(ROOT, 'cases')
    os.makedirs(outdir, exist_ok=True)
    master = random.Random(MASTER_SEED)
    templates = [Template(nm) for nm in TEMPLATE_FILES]
    events = template_events(templates)
    trials = plan(master)
    key = {}
    log = lambda s: (print(s), sys.stdout.flush())
    only = set(sys.argv[1:])
    for k, tr in enumerate(trials):
        tid = 't%02d' % (k + 1)
        if only and tid not in only:
            continue
        t1 = time.time()
        key[tid] = make_trial(tid, tr, templates, events, outdir, log)
        log('%s %-16s %-36s %-6s ratio %.3f  (%.1f s)' % (
            tid, tr['category'], tr['shape'], tr['strength'], key[tid]['ratio'], time.time() - t1))
    if not only:
        with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
            json.dump(key, fh, indent=1)
    log('gen.py done in %.1f s' % (time.time() - t0))


if __name__ == '__main__':
    main()
