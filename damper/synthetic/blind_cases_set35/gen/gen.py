#!/usr/bin/env python3
"""blind35 generator: synthetic semi-active BRFD records = base model + ONE hidden effect + noise.

Python 3 standard library only.  Master seed 35035.  Writes
  /work/blind35/cases/tNN/{A.json,B.json}   (measured semi-active layout)
  /work/blind35/key.json                    (answer key)

The base model is the semi-active LuGre model of the paper (Eqs. 1-5) with the parameters of
/work/main/configs/brfd-semiactive.yaml, reproduced here as it was inferred from the black box
`hybridsim damper predict --no-fit` (see NOTES.md):
  * drum velocity v: central differences of the displacement column (one-sided at the ends),
    then a centred 15-sample moving average clipped to the record at its ends;
  * Eq. 4 with x'_i = actuator positions of the first row, clipped below at 0.05 kip;
  * Eq. 5 Stribeck with Fs/Fc chosen by v >= 0 (forward) or v < 0 (backward);
  * initial bristle state z0 = F(t=0) / sigma0 (the first force sample of the record);
  * step k-1 -> k: exact exponential solution of Eq. 1 with v, g frozen at their values at
    sample k; F_k = sigma0 z_k + sigma2 v_k (sigma1 = 0).
"""
import json, math, os, random, struct, sys, time

MASTER_SEED = 35035
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))      # /work/blind35
DATA = '/work/shared/data/brfd/semiactive'
MEASURED = ['harmonic0.015backward', 'harmonic0.015forward', 'harmonic0.03ea1backward',
            'harmonic0.03ea1forward', 'harmonic0.03ea2backward', 'harmonic0.03ea2forward']

DT = 1.0 / 1024.0
FS_HZ = 1024
# ---- base model parameters (configs/brfd-semiactive.yaml) ----
S0 = 15.36          # sigma0 kip/in
S2 = 0.500          # sigma2 kip s/in
FS_F, FS_B = 7.116, 3.760
FC_F, FC_B = 2.648, 1.253
VS = 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FC_FLOOR = 0.05
# Eq. 4 combined slopes (kip/in): forward (x1, x2), backward (x1, x2)
KF1 = C[0] * M[0] + C[1] * M[2]
KF2 = C[0] * M[1] + C[1] * M[3]
KB1 = C[2] * M[4] + C[3] * M[6]
KB2 = C[2] * M[5] + C[3] * M[7]

# ---- measured-file quantisation (see NOTES.md) ----
Q_FORCE = 0.00080087996      # kip, force counts (zero offset)
Q_DISP = 5.8919e-05          # in, drum displacement (stored as float32)
Q_ACT = 0.01 / 4096.0        # in, actuator position (stored as float32)
Q_AF1, OFF_AF1 = 0.31793998, 0.01653   # lb, actuator 1 force
Q_AF2, OFF_AF2 = 0.39998, 0.1260       # lb, actuator 2 force
VEL_COL_RATIO = 125.4        # velocity column = d(disp)/dt / 125.4 (quirk of the files)
VEL_COL_LAG = 6              # samples (the column lags the centred derivative)
HEADER = [("dt", DT), ("sampling freq", FS_HZ), ("displacement units", "in"),
          ("time units", "s"), ("friction force units", "kip"), ("actuator force units", "lb")]

V_MOVE, V_STILL, HOLD_DELAY = 0.10, 0.05, 0.12   # rest detector (in/s, in/s, s)
INITIAL_REST_AGE = 20.0                          # s: the first sample's force has been held long


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


# =====================================================================================
# base-model pieces
# =====================================================================================
def drum_velocity(x, dt=DT):
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / dt
    d[-1] = (x[-1] - x[-2]) / dt
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * dt)
    # centred 15-sample moving average, window clipped at the ends
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    out = [0.0] * n
    for i in range(n):
        a = max(0, i - 7)
        b = min(n - 1, i + 7)
        out[i] = (cs[b + 1] - cs[a]) / (b - a + 1)
    return out


def eq4(x1, x2, x1p, x2p, phi=None):
    """Eq. 4 kinetic friction for both directions; phi(dx) replaces the linear travel (pretension)."""
    n = len(x1)
    ff = [0.0] * n
    fb = [0.0] * n
    for k in range(n):
        d1 = x1[k] - x1p
        d2 = x2[k] - x2p
        if phi is not None:
            d1 = phi(d1)
            d2 = phi(d2)
        a = FC_F + KF1 * d1 + KF2 * d2
        b = FC_B + KB1 * d1 + KB2 * d2
        ff[k] = a if a > FC_FLOOR else FC_FLOOR
        fb[k] = b if b > FC_FLOOR else FC_FLOOR
    return ff, fb


def stribeck(v, fc, fs, vs):
    return fc + (fs - fc) * math.exp(-(v / vs) ** 2)


def g_array(v, ff, fb, vs_f=VS, vs_b=VS, hmod=None):
    n = len(v)
    g = [0.0] * n
    for k in range(n):
        vk = v[k]
        if vk >= 0:
            gk = stribeck(vk, ff[k], FS_F, vs_f)
        else:
            gk = stribeck(vk, fb[k], FS_B, vs_b)
        if hmod is not None:
            gk = gk * (1.0 + hmod(vk))
            if gk < FC_FLOOR:
                gk = FC_FLOOR
        g[k] = gk
    return g


def lugre(v, g, F0, s0f=S0, s0b=S0, s2f=S2, s2b=S2, dt=DT):
    """force form of Eqs. 1-3: f = sigma0 z; exact exponential step with v_k, g_k."""
    n = len(v)
    f = F0
    out = [0.0] * n
    for k in range(n):
        vk = v[k]
        if vk >= 0:
            if k > 0 and vk > 0:
                gk = g[k]
                f = gk + (f - gk) * math.exp(-s0f * vk / gk * dt)
            out[k] = f + s2f * vk
        else:
            if k > 0:
                gk = g[k]
                f = -gk + (f + gk) * math.exp(s0b * vk / gk * dt)
            out[k] = f + s2b * vk
    return out


def base_force(rec):
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(rec['v'], ff, fb)
    return lugre(rec['v'], g, rec['F0'])


# =====================================================================================
# hidden effects (each returns F_true for one record, given shape params and amplitude)
# =====================================================================================
def _sgn(a):
    return 1.0 if a >= 0 else -1.0


def rest_age(v):
    """hold time while the drum is still; hysteretic detector on the smoothed velocity."""
    n = len(v)
    age = [0.0] * n
    moving = False
    a = INITIAL_REST_AGE
    for k in range(n):
        s = abs(v[k])
        if moving:
            if s < V_STILL:
                moving = False
                a = 0.0
        elif s > V_MOVE:
            moving = True
        if moving:
            a = 0.0
        elif k > 0:
            a += DT
        age[k] = -1.0 if moving else a
    return age


def _eff_age(a):
    return a - HOLD_DELAY if a > HOLD_DELAY else 0.0


def residual(rec, shape, P, amp):
    """residual_static: the held bristle force evolves during rests (base LuGre otherwise)."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    age = rec['age']
    n = len(v)
    if shape == 'kww_stretched_relaxation':
        tau, beta, a0 = P['tau_s'], P['beta'], P['a0_s']
        def phi(a):
            return math.exp(-((a + a0) / tau) ** beta + (a0 / tau) ** beta)
        def held(Fh, a):
            return Fh * ((1 - amp) + amp * phi(_eff_age(a)))
    elif shape == 'log_time_creep':
        tc = P['tc_s']
        def held(Fh, a):
            return Fh * max(0.0, 1.0 - amp * math.log(1.0 + _eff_age(a) / tc))
    elif shape == 'zener_settling_to_offset':
        tau, Feq = P['tau_s'], P['F_eq_kip']
        def held(Fh, a):
            return Fh + amp * (Feq - Fh) * (1.0 - math.exp(-_eff_age(a) / tau))
    else:
        raise ValueError(shape)
    out = [0.0] * n
    f = rec['F0']
    # initial hold: the first force sample is the held force after INITIAL_REST_AGE s
    Fh = None
    if age[0] >= 0:
        # find Fh such that held(Fh, age0) = F0 (held() is affine in Fh)
        h0 = held(0.0, age[0])
        h1 = held(1.0, age[0])
        Fh = (f - h0) / (h1 - h0) if abs(h1 - h0) > 1e-12 else f
    prev_held = held(Fh, age[0]) if Fh is not None else None
    for k in range(n):
        vk = v[k]
        if k > 0:
            gk = g[k]
            if vk > 0:
                f = gk + (f - gk) * math.exp(-S0 * vk / gk * DT)
            elif vk < 0:
                f = -gk + (f + gk) * math.exp(S0 * vk / gk * DT)
            if age[k] >= 0:
                if age[k - 1] < 0 or Fh is None:      # a rest starts: hold this force
                    Fh = f
                    prev_held = held(Fh, age[k])
                else:
                    h = held(Fh, age[k])
                    f += h - prev_held
                    prev_held = h
            else:
                Fh = None
        out[k] = f + S2 * vk
    return out


def backlash_deadzone(rec, P, amp):
    """clearance of half-width delta in series with the bristle/band spring (Nordin & Gutman 2002)."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    d = amp
    F0 = rec['F0']
    w = F0 / S0                                      # spring deflection beyond the clearance
    y = w + (d if F0 >= 0 else -d)                   # band-end coordinate, loaded side
    out = [0.0] * len(v)
    for k in range(len(v)):
        vk = v[k]
        if k > 0:
            if y > d or y < -d:
                side = 1.0 if y > d else -1.0
                w = y - side * d
                gk = g[k]
                a = S0 * abs(vk) / gk
                if a > 0:
                    ws = (gk / S0) * (1.0 if vk > 0 else -1.0)
                    wn = ws + (w - ws) * math.exp(-a * DT)
                else:
                    wn = w
                y = side * d + wn                    # wn of opposite sign: inside the clearance
            else:
                y += vk * DT
        if y > d:
            fk = S0 * (y - d)
        elif y < -d:
            fk = S0 * (y + d)
        else:
            fk = 0.0
        out[k] = fk + S2 * vk
    return out


def backlash_slackband(rec, P, amp):
    """smooth slack: band stiffness depends on the carried tension (elastic catenary,
    Ernst/Irvine equivalent modulus): k(f) = s0 [eps + (1-eps) f^2/(f^2+fe^2)]."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    eps = P['eps']
    fe2 = amp * amp
    f = rec['F0']
    out = [0.0] * len(v)
    h = DT / 2
    for k in range(len(v)):
        vk = v[k]
        if k > 0 and vk != 0.0:
            gk = g[k]
            fs = gk if vk > 0 else -gk
            for _ in range(2):
                kk = S0 * (eps + (1 - eps) * (f * f / (f * f + fe2))) if fe2 > 0 else S0
                f = fs + (f - fs) * math.exp(-kk * abs(vk) / gk * h)
        out[k] = f + S2 * vk
    return out


def backlash_impact(rec, P, amp):
    """clearance with impact at re-engagement (impact pair, Dubowsky & Freudenstein 1971):
    the clearance of half-width delta is traversed at zero force as in the dead-zone model; when
    it closes, the link strikes the resting drum with the closing speed V and the contact spring
    (k_c) rings against the drum's equivalent mass m:  dF(t) = V sqrt(k_c m) exp(-zeta w t)
    sin(w_d t), w = sqrt(k_c/m) (linearised impact response superposed on the dead-zone force)."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    d = amp
    kc, m, zeta = P['k_c_kip_per_in'], P['m_kip_s2_per_in'], P['zeta_c']
    w = math.sqrt(kc / m)
    wd = w * math.sqrt(1 - zeta * zeta)
    Z = math.sqrt(kc * m)
    F0 = rec['F0']
    ws_ = F0 / S0
    y = ws_ + (d if F0 >= 0 else -d)
    out = [0.0] * len(v)
    events = []                         # (k_start, signed closing speed)
    for k in range(len(v)):
        vk = v[k]
        if k > 0:
            if y > d or y < -d:
                side = 1.0 if y > d else -1.0
                wv = y - side * d
                gk = g[k]
                a = S0 * abs(vk) / gk
                if a > 0:
                    wsv = (gk / S0) * (1.0 if vk > 0 else -1.0)
                    wv = wsv + (wv - wsv) * math.exp(-a * DT)
                y = side * d + wv
            else:
                y += vk * DT
                if d > 0 and (y > d or y < -d):
                    events.append((k, vk))
        if y > d:
            fk = S0 * (y - d)
        elif y < -d:
            fk = S0 * (y + d)
        else:
            fk = 0.0
        out[k] = fk + S2 * vk
    L = int(8.0 / (zeta * w) / DT) + 1
    for k0, V in events:
        A = V * Z
        for j in range(L):
            k = k0 + j
            if k >= len(out):
                break
            t = j * DT
            out[k] += A * math.exp(-zeta * w * t) * math.sin(wd * t)
    return out


def transition_iwan(rec, P, amp):
    """parallel Iwan (1966) / Masing element bank carrying a fraction lam of the sliding level:
    N Jenkins elements, virgin stiffness lam*s0, uniform slip displacements up to 2 g/s0."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    lam = amp
    N = P['N']
    ke = lam * S0 / N
    dmax = 2.0 / S0
    dl = [(i + 0.5) / N * dmax for i in range(N)]
    F0 = rec['F0']
    fL = (1 - lam) * F0
    g0 = g[0]
    # initial element forces: common deflection e with sum = lam F0
    el = [0.0] * N
    if lam > 0 and F0 != 0:
        target = lam * F0
        lo, hi = -10.0, 10.0
        for _ in range(60):
            e = 0.5 * (lo + hi)
            s = sum(max(-ke * di * g0, min(ke * di * g0, ke * e)) for di in dl)
            if s < target:
                lo = e
            else:
                hi = e
        el = [max(-ke * di * g0, min(ke * di * g0, ke * e)) for di in dl]
    out = [0.0] * len(v)
    for k in range(len(v)):
        vk = v[k]
        if k > 0:
            gk = g[k]
            if vk > 0:
                fL = (1 - lam) * gk + (fL - (1 - lam) * gk) * math.exp(-S0 * vk / gk * DT)
            elif vk < 0:
                fL = -(1 - lam) * gk + (fL + (1 - lam) * gk) * math.exp(S0 * vk / gk * DT)
            if lam > 0:
                dx = ke * vk * DT
                for i in range(N):
                    lim = ke * dl[i] * gk
                    e = el[i] + dx
                    el[i] = lim if e > lim else (-lim if e < -lim else e)
        out[k] = fL + sum(el) + S2 * vk
    return out


def transition_elastoplastic(rec, P, amp):
    """elasto-plastic presliding (Dupont, Hayward, Armstrong, Altpeter 2002) blended by lam:
    dz/dt = v (1 - a_eff sigma0 z sgn(v)/g), a_eff = (1-lam) + lam alpha_EP(z, v)."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    lam = amp
    rba, rmax = P['zba_ratio'], P['zmax_ratio']
    nsub = 4
    h = DT / nsub
    z = rec['F0'] / S0
    out = [0.0] * len(v)
    for k in range(len(v)):
        vk = v[k]
        if k > 0 and vk != 0.0:
            gk = g[k]
            zss = gk / S0
            zba, zmx = rba * zss, rmax * zss
            sv = 1.0 if vk > 0 else -1.0
            for _ in range(nsub):
                if z * sv <= 0:
                    aep = 0.0
                else:
                    az = abs(z)
                    if az <= zba:
                        aep = 0.0
                    elif az >= zmx:
                        aep = 1.0
                    else:
                        aep = 0.5 * math.sin(math.pi * (az - 0.5 * (zmx + zba)) / (zmx - zba)) + 0.5
                al = (1 - lam) + lam * aep
                if al > 0:
                    a = al * S0 * abs(vk) / gk
                    zs = sv * gk / (al * S0)
                    z = zs + (z - zs) * math.exp(-a * h)
                else:
                    z += vk * h
        out[k] = S0 * z + S2 * vk
    return out


def transition_bliman_sorine(rec, P, amp):
    """Bliman & Sorine (1995) second-order space-domain model, written around the base element:
    F = (1+eta) f_L - f2, where f_L is the base bristle force (fast element, travel constant
    g/s0, steady g sgn v) and f2 a slow element in travel, df2/dx = (eta g sgn v - f2)/eps2.
    Steady sliding: F = g sgn v (sliding level unchanged); after a reversal the fast element
    leads the slow one -> a force peak that decays with travel (not with velocity)."""
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g = g_array(v, ff, fb)
    eta = amp
    eps2 = P['eps2_in']
    F0 = rec['F0']
    fL = F0
    f2 = eta * F0
    out = [0.0] * len(v)
    for k in range(len(v)):
        vk = v[k]
        if k > 0 and vk != 0.0:
            gk = g[k]
            sv = 1.0 if vk > 0 else -1.0
            fL = sv * gk + (fL - sv * gk) * math.exp(-S0 * abs(vk) / gk * DT)
            f2 = sv * eta * gk + (f2 - sv * eta * gk) * math.exp(-abs(vk) * DT / eps2)
        out[k] = (1 + eta) * fL - f2 + S2 * vk
    return out


def velocity_effect(rec, shape, P, amp):
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    if shape == 'rate_state_log':
        vc, vr, sg = P['v_c'], P['v_ref'], P['sign']
        def hm(vk):
            return sg * amp * math.log((abs(vk) + vc) / (vr + vc))
    elif shape == 'power_law_third_body':
        n_, v0 = P['n'], P['v0']
        def hm(vk):
            return amp * (abs(vk) / v0) ** n_
    elif shape == 'grosch_log_gaussian_hump':
        vp, w = P['v_peak'], P['width']
        def hm(vk):
            s = abs(vk)
            if s < 1e-9:
                return 0.0
            return amp * math.exp(-(math.log(s / vp)) ** 2 / (2 * w * w))
    else:
        raise ValueError(shape)
    g = g_array(v, ff, fb, hmod=hm)
    return lugre(v, g, rec['F0'])


def actuator_path(x, xp, shape, P, amp):
    n = len(x)
    out = [0.0] * n
    if shape == 'zener_viscoelastic_partial':
        tau = amp
        r = P['delayed_fraction']
        y = 0.0
        al = math.exp(-DT / tau) if tau > 0 else 0.0
        for k in range(n):
            d = x[k] - xp
            if k > 0:
                y = d + (y - d) * al
            out[k] = xp + (1 - r) * d + r * y
    elif shape == 'rate_limited_tension':
        R = amp
        e = 0.0
        for k in range(n):
            d = x[k] - xp
            if k > 0:
                step = d - e
                lim = R * DT
                e += lim if step > lim else (-lim if step < -lim else step)
            out[k] = xp + e
    elif shape == 'underdamped_second_order':
        wn = 2 * math.pi * amp
        ze = P['zeta']
        e, ed = 0.0, 0.0
        nsub = max(1, int(math.ceil(wn * DT / 0.05)))
        h = DT / nsub
        for k in range(n):
            d = x[k] - xp
            if k > 0:
                for _ in range(nsub):
                    ed += h * (wn * wn * (d - e) - 2 * ze * wn * ed)
                    e += h * ed
            out[k] = xp + e
    else:
        raise ValueError(shape)
    return out


def lag_effect(rec, shape, P, amp):
    x1e = actuator_path(rec['x1'], rec['x1p'], shape, P, amp)
    x2e = actuator_path(rec['x2'], rec['x2p'], shape, P, amp)
    ff, fb = eq4(x1e, x2e, rec['x1p'], rec['x2p'])
    g = g_array(rec['v'], ff, fb)
    return lugre(rec['v'], g, rec['F0'])


def pretension_effect(rec, shape, P, amp):
    if shape == 'exponential_band_stiffening':
        kap = amp
        def phi(dx):
            # retraction (dx < 0) tightens the bands: tension grows exponentially with take-up
            return dx if kap == 0 else (1.0 - math.exp(-kap * dx)) / kap
    elif shape == 'tanh_tension_saturation':
        kap = amp
        def phi(dx):
            return dx if kap == 0 else math.tanh(kap * dx) / kap
    elif shape == 'slack_threshold_deadzone':
        d0 = amp
        def phi(dx):
            if dx > d0:
                return dx - d0
            if dx < -d0:
                return dx + d0
            return 0.0
    else:
        raise ValueError(shape)
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'], phi=phi)
    g = g_array(rec['v'], ff, fb)
    return lugre(rec['v'], g, rec['F0'])


def self_energizing(rec, shape, P, amp):
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    g0 = g_array(v, ff, fb)
    n = len(v)
    if shape == 'capstan_wrap_position':
        x = rec['x']
        xn = P['x_neutral_in']
        g = [g0[k] * math.exp(amp * (x[k] - xn) * (1.0 if v[k] >= 0 else -1.0)) for k in range(n)]
        return lugre(v, g, rec['F0'])
    if shape == 'servo_buildup_travel':
        dc = P['d_c_in']
        g = [0.0] * n
        trav = 0.0
        last = 0
        for k in range(n):
            s = 1 if v[k] > V_MOVE else (-1 if v[k] < -V_MOVE else 0)
            if s != 0 and s != last:
                trav = 0.0
                last = s
            trav += abs(v[k]) * DT
            g[k] = g0[k] * (1.0 + amp * (1.0 - math.exp(-trav / dc)))
        return lugre(v, g, rec['F0'])
    if shape == 'wedge_force_feedback':
        tb, Fr = P['tau_b_s'], P['F_ref_kip']
        al = math.exp(-DT / tb)
        f = rec['F0']
        T = abs(f)
        out = [0.0] * n
        for k in range(n):
            vk = v[k]
            if k > 0:
                T = abs(f) + (T - abs(f)) * al
                gk = g0[k] * (1.0 + amp * math.tanh(T / Fr))
                if vk > 0:
                    f = gk + (f - gk) * math.exp(-S0 * vk / gk * DT)
                elif vk < 0:
                    f = -gk + (f + gk) * math.exp(S0 * vk / gk * DT)
            out[k] = f + S2 * vk
        return out
    raise ValueError(shape)


def asymmetry(rec, shape, P, amp):
    v = rec['v']
    ff, fb = eq4(rec['x1'], rec['x2'], rec['x1p'], rec['x2p'])
    fwd = P['direction'] == 'forward'
    if shape == 'direction_dependent_stiffness':
        s = S0 * (1.0 - amp)
        g = g_array(v, ff, fb)
        return lugre(v, g, rec['F0'], s0f=s if fwd else S0, s0b=S0 if fwd else s)
    if shape == 'direction_dependent_stribeck_velocity':
        fac = (1.0 + amp) if P['sense'] == 'wider' else 1.0 / (1.0 + amp)
        g = g_array(v, ff, fb, vs_f=VS * fac if fwd else VS, vs_b=VS if fwd else VS * fac)
        return lugre(v, g, rec['F0'])
    if shape == 'direction_dependent_viscous':
        s = S2 * (1.0 + amp) if P['sense'] == 'higher' else S2 / (1.0 + amp)
        g = g_array(v, ff, fb)
        return lugre(v, g, rec['F0'], s2f=s if fwd else S2, s2b=S2 if fwd else s)
    raise ValueError(shape)


SHAPES = {
    'backlash': ['deadzone_clearance', 'slack_band_tension_stiffness', 'impact_pair_clearance'],
    'residual_static': ['kww_stretched_relaxation', 'log_time_creep', 'zener_settling_to_offset'],
    'transition_shape': ['iwan_masing_parallel', 'elastoplastic_breakaway', 'bliman_sorine_overshoot'],
    'velocity': ['rate_state_log', 'power_law_third_body', 'grosch_log_gaussian_hump'],
    'actuator_lag': ['zener_viscoelastic_partial', 'rate_limited_tension', 'underdamped_second_order'],
    'self_energizing': ['capstan_wrap_position', 'servo_buildup_travel', 'wedge_force_feedback'],
    'pretension': ['exponential_band_stiffening', 'tanh_tension_saturation', 'slack_threshold_deadzone'],
    'asymmetry': ['direction_dependent_stiffness', 'direction_dependent_stribeck_velocity',
                  'direction_dependent_viscous'],
}

# amplitude name, physically plausible bounds, and whether the effect grows with the amplitude
AMP = {
    'deadzone_clearance': ('delta_in', 0.0, 0.35, +1),
    'slack_band_tension_stiffness': ('f_e_kip', 0.0, 1.2, +1),
    'impact_pair_clearance': ('delta_in', 0.0, 0.30, +1),
    'kww_stretched_relaxation': ('relaxing_fraction', 0.0, 0.95, +1),
    'log_time_creep': ('c_per_ln_time', 0.0, 0.40, +1),
    'zener_settling_to_offset': ('settled_fraction', 0.0, 1.0, +1),
    'iwan_masing_parallel': ('iwan_fraction', 0.0, 1.0, +1),
    'elastoplastic_breakaway': ('ep_fraction', 0.0, 1.0, +1),
    'bliman_sorine_overshoot': ('eta_overshoot', 0.0, 2.0, +1),
    'rate_state_log': ('A_log', 0.0, 0.60, +1),
    'power_law_third_body': ('B_power', 0.0, 0.70, +1),
    'grosch_log_gaussian_hump': ('C_hump', 0.0, 1.0, +1),
    'zener_viscoelastic_partial': ('tau_s', 0.0, 4.0, +1),
    'rate_limited_tension': ('rate_limit_in_per_s', 0.004, 5.0, -1),
    'underdamped_second_order': ('f_n_hz', 0.4, 25.0, -1),
    'capstan_wrap_position': ('kappa_per_in', 0.0, 0.60, +1),
    'servo_buildup_travel': ('eta_servo', 0.0, 1.0, +1),
    'wedge_force_feedback': ('eps_wedge', 0.0, 0.80, +1),
    'exponential_band_stiffening': ('kappa_per_in', 0.0, 45.0, +1),
    'tanh_tension_saturation': ('kappa_per_in', 0.0, 300.0, +1),
    'slack_threshold_deadzone': ('threshold_in', 0.0, 0.035, +1),
    'direction_dependent_stiffness': ('softening', 0.0, 0.75, +1),
    'direction_dependent_stribeck_velocity': ('a_vs', 0.0, 2.0, +1),
    'direction_dependent_viscous': ('a_sigma2', 0.0, 3.0, +1),
}


def shape_params(shape, r):
    """fixed (non-amplitude) parameters, drawn per trial."""
    if shape == 'slack_band_tension_stiffness':
        return {'eps': round(r.uniform(0.08, 0.15), 4)}
    if shape == 'impact_pair_clearance':
        return {'k_c_kip_per_in': round(r.uniform(150, 400), 1), 'm_kip_s2_per_in': round(r.uniform(3e-4, 8e-4), 6),
                'zeta_c': round(r.uniform(0.06, 0.15), 3)}
    if shape == 'kww_stretched_relaxation':
        return {'tau_s': round(r.uniform(0.8, 2.5), 3), 'beta': round(r.uniform(0.4, 0.6), 3), 'a0_s': 0.03}
    if shape == 'log_time_creep':
        return {'tc_s': round(r.uniform(0.05, 0.25), 3)}
    if shape == 'zener_settling_to_offset':
        return {'tau_s': round(r.uniform(0.4, 1.5), 3),
                'F_eq_kip': round(r.choice([-1, 1]) * r.uniform(0.3, 1.2), 3)}
    if shape == 'iwan_masing_parallel':
        return {'N': 24}
    if shape == 'elastoplastic_breakaway':
        zb = r.uniform(0.5, 0.8)
        return {'zba_ratio': round(zb, 3), 'zmax_ratio': 0.95}
    if shape == 'bliman_sorine_overshoot':
        return {'eps2_in': round(r.uniform(0.25, 0.5), 3)}
    if shape == 'rate_state_log':
        return {'v_c': round(r.uniform(0.2, 0.5), 3), 'v_ref': round(r.uniform(0.4, 1.2), 3),
                'sign': r.choice([-1, 1])}
    if shape == 'power_law_third_body':
        return {'n': round(r.uniform(0.3, 0.5), 3), 'v0': 1.0}
    if shape == 'grosch_log_gaussian_hump':
        return {'v_peak': round(r.uniform(0.8, 2.5), 3), 'width': round(r.uniform(0.5, 0.8), 3)}
    if shape == 'zener_viscoelastic_partial':
        return {'delayed_fraction': round(r.uniform(0.7, 0.95), 3)}
    if shape == 'underdamped_second_order':
        return {'zeta': round(r.uniform(0.15, 0.3), 3)}
    if shape == 'capstan_wrap_position':
        return {'x_neutral_in': 0.0}
    if shape == 'servo_buildup_travel':
        return {'d_c_in': round(r.uniform(0.3, 0.8), 3)}
    if shape == 'wedge_force_feedback':
        return {'tau_b_s': round(r.uniform(0.03, 0.12), 3), 'F_ref_kip': round(r.uniform(2.0, 4.0), 3)}
    if shape == 'direction_dependent_stiffness':
        return {'direction': r.choice(['forward', 'backward'])}
    if shape == 'direction_dependent_stribeck_velocity':
        return {'direction': r.choice(['forward', 'backward']), 'sense': r.choice(['wider', 'narrower'])}
    if shape == 'direction_dependent_viscous':
        return {'direction': r.choice(['forward', 'backward']), 'sense': 'higher'}
    return {}


def true_force(rec, cat, shape, P, amp):
    if cat == 'none':
        return base_force(rec)
    if cat == 'backlash':
        return {'deadzone_clearance': backlash_deadzone, 'slack_band_tension_stiffness': backlash_slackband,
                'impact_pair_clearance': backlash_impact}[shape](rec, P, amp)
    if cat == 'residual_static':
        return residual(rec, shape, P, amp)
    if cat == 'transition_shape':
        return {'iwan_masing_parallel': transition_iwan, 'elastoplastic_breakaway': transition_elastoplastic,
                'bliman_sorine_overshoot': transition_bliman_sorine}[shape](rec, P, amp)
    if cat == 'velocity':
        return velocity_effect(rec, shape, P, amp)
    if cat == 'actuator_lag':
        return lag_effect(rec, shape, P, amp)
    if cat == 'self_energizing':
        return self_energizing(rec, shape, P, amp)
    if cat == 'pretension':
        return pretension_effect(rec, shape, P, amp)
    if cat == 'asymmetry':
        return asymmetry(rec, shape, P, amp)
    raise ValueError(cat)


def null_amp(shape):
    """amplitude at which the shape equals the base model."""
    nm, lo, hi, sense = AMP[shape]
    if shape == 'rate_limited_tension':
        return 1e6
    if shape == 'underdamped_second_order':
        return 200.0
    return 0.0


# =====================================================================================
# templates from the measured semi-active tests
# =====================================================================================
def load_templates():
    T = {'strokes': [], 'rest': [], 'events': [], 'af': None}
    regs = {6: [], 7: []}
    for name in MEASURED:
        d = json.load(open(os.path.join(DATA, name + '.json')))
        D = d['data']
        x = [r[1] for r in D]
        v = drum_velocity(x)
        n = len(x)
        # reversals: sign changes of the smoothed velocity while moving
        mv = [abs(a) > 0.05 for a in v]
        first = mv.index(True)
        last = n - 1 - mv[::-1].index(True)
        rev = [first]
        for i in range(first, last):
            if v[i] == 0 or (v[i] > 0) != (v[i + 1] > 0):
                if abs(x[i] - x[rev[-1]]) > 0.2:
                    rev.append(i)
        rev.append(last)
        for a, b in zip(rev[:-1], rev[1:]):
            dx = x[b] - x[a]
            if abs(dx) >= 0.4:
                seg = [(x[i] - x[a]) / dx for i in range(a, b + 1)]
                vpk = max(abs(v[i]) for i in range(a, b + 1)) / abs(dx)   # peak speed per unit travel
                T['strokes'].append({'s': seg, 'vpk_norm': vpk, 'src': name})
        # rest jitter: the final rest (from 0.3 s after the last motion)
        r0 = last + int(0.3 * FS_HZ)
        rest = x[r0:]
        if len(rest) > 200:
            mu = sum(rest) / len(rest)
            T['rest'].append([a - mu for a in rest])
        # actuator events
        x1 = [r[4] for r in D]
        x2 = [r[5] for r in D]
        ev = [i for i in range(n) if abs(x1[i] - x1[0]) > 0.002 or abs(x2[i] - x2[0]) > 0.002]
        cl = []
        s = p = ev[0]
        for i in ev[1:]:
            if i - p > 150:
                cl.append((s, p))
                s = i
            p = i
        cl.append((s, p))
        pad = int(0.15 * FS_HZ)
        for a, b in cl:
            a0, b0 = max(0, a - pad), min(n - 1, b + pad)
            T['events'].append({'d1': [x1[i] - x1[0] for i in range(a0, b0 + 1)],
                                'd2': [x2[i] - x2[0] for i in range(a0, b0 + 1)], 'src': name})
        for c in (6, 7):
            regs[c].append([(max(r[2], 0.0), max(-r[2], 0.0), r[c]) for r in D[::4]])
    # actuator-force regression  T_c = a + b max(F,0) + c max(-F,0)
    af = {}
    for c in (6, 7):
        rows = [q for L in regs[c] for q in L]
        X = [(1.0, p, m) for p, m, _ in rows]
        y = [t for _, _, t in rows]
        A = [[sum(a[i] * a[j] for a in X) for j in range(3)] for i in range(3)]
        bb = [sum(a[i] * t for a, t in zip(X, y)) for i in range(3)]
        Mx = [A[i] + [bb[i]] for i in range(3)]
        for i in range(3):
            piv = Mx[i][i]
            for j in range(i, 4):
                Mx[i][j] /= piv
            for k2 in range(3):
                if k2 != i:
                    fct = Mx[k2][i]
                    for j in range(i, 4):
                        Mx[k2][j] -= fct * Mx[i][j]
        coef = [Mx[i][3] for i in range(3)]
        res = [t - (coef[0] + coef[1] * a[1] + coef[2] * a[2]) for a, t in zip(X, y)]
        sd = math.sqrt(sum(r * r for r in res) / len(res))
        af[c] = {'coef': coef, 'sd': sd}
    T['af'] = af
    T['x1p'] = 0.6549999713897705
    T['x2p'] = 0.8559008240699768
    return T


def interp(seq, t):
    i = int(t)
    if i >= len(seq) - 1:
        return seq[-1]
    fr = t - i
    return seq[i] * (1 - fr) + seq[i + 1] * fr


# =====================================================================================
# record synthesis
# =====================================================================================
ACT_PEAK_MAX = 0.055     # in, largest actuator excursion from x'


def event_wave(src, kind, stretch, hold, scale):
    """one actuator event re-cut from a measured harmonic event (deviation from x').
    'cycle': the measured cycle, stretched and scaled.  'step': the measured rise to the first
    extremum, a hold, and the measured return from the last extremum (paper's step tests)."""
    pk = max(abs(a) for a in src)
    sc = scale
    if pk * abs(sc) > ACT_PEAK_MAX:
        sc = _sgn(sc) * ACT_PEAK_MAX / pk
    if kind == 'cycle':
        seq = src
    else:
        n = len(src)
        i1 = max(range(n // 2), key=lambda i: abs(src[i]))
        i2 = max(range(n // 2, n), key=lambda i: abs(src[i]) if src[i] * src[i1] < 0 else -1.0)
        rise = src[:i1 + 1]
        back = src[i2:]
        k = src[i1] / back[0] if abs(back[0]) > 1e-4 else 1.0
        nh = int(hold * FS_HZ / stretch)
        seq = rise + [src[i1]] * nh + [k * a for a in back]
    L = int((len(seq) - 1) * stretch)
    return [sc * interp(seq, j / stretch) for j in range(L + 1)]


def make_motion(T, r, want_act):
    """drum displacement and actuator commands for one record (before quantisation)."""
    dur = r.uniform(9.0, 25.0)
    n = int(round(dur * FS_HZ)) + 1
    fin_rest = r.uniform(1.0, 3.0)
    x = []
    rests = T['rest']

    def add_rest(P, secs):
        m = int(secs * FS_HZ)
        while m > 0:
            src = r.choice(rests)
            L = min(m, r.randint(200, len(src)))
            o = r.randint(0, len(src) - L)
            x.extend(P + src[o + j] for j in range(L))
            m -= L

    P = r.uniform(-0.3, 0.3)
    add_rest(P, r.uniform(0.3, 2.0))
    limit = n - int(fin_rest * FS_HZ)
    strokes = []
    while True:
        nb = r.randint(1, 6)
        stop = False
        for _ in range(nb):
            if r.random() < 0.8 or abs(P) < 0.35:
                Q = -_sgn(P) * r.uniform(0.25, 1.25) if abs(P) > 0.05 else r.choice([-1, 1]) * r.uniform(0.4, 1.25)
            else:
                Q = _sgn(P) * r.uniform(0.05, abs(P) - 0.25)
            tpl = r.choice(T['strokes'])
            travel = abs(Q - P)
            vpk = r.uniform(0.7, 4.2)
            # duration from the template's peak-speed-per-travel
            ntpl = len(tpl['s'])
            base_dur = (ntpl - 1) * DT
            vpk_tpl = tpl['vpk_norm'] * travel          # template peak speed scaled to this travel
            stretch = vpk_tpl / vpk
            new_dur = base_dur * stretch
            if new_dur < 0.3:
                stretch = 0.3 / base_dur
            if new_dur > 4.0:
                stretch = 4.0 / base_dur
            m = int(round(base_dur * stretch * FS_HZ))
            if len(x) + m > limit:
                stop = True
                break
            s = tpl['s']
            for j in range(1, m + 1):
                x.append(P + (Q - P) * interp(s, j / stretch))
            P = x[-1]
            strokes.append(len(x))
        if stop or len(x) > limit - int(0.8 * FS_HZ):
            break
        add_rest(P, r.uniform(0.8, 3.5))
        if len(x) >= limit:
            break
    # final rest up to the record length
    if len(x) < n:
        add_rest(P, (n - len(x)) / FS_HZ + 0.01)
    x = x[:n]
    # actuators: 'none', 'a1', 'a2', 'both'
    xp1, xp2 = T['x1p'], T['x2p']
    d1 = [0.0] * n
    d2 = [0.0] * n
    mode = want_act
    if mode != 'none':
        nev = r.randint(5, 12)
        busy1, busy2 = [], []
        t_lo = int(0.3 * FS_HZ)
        for _ in range(nev):
            if mode == 'both':
                ch = r.choice(['a1', 'a2', 'pair', 'pair'])
            else:
                ch = mode
            ev = r.choice(T['events'])
            amp1 = max(abs(a) for a in ev['d1'])
            amp2 = max(abs(a) for a in ev['d2'])
            if ch == 'pair' and min(amp1, amp2) < 0.005:
                ch = r.choice(['a1', 'a2'])
            srcs = {}
            if ch in ('a1', 'pair'):
                srcs['a1'] = ev['d1'] if amp1 > 0.005 else ev['d2']
            if ch in ('a2', 'pair'):
                srcs['a2'] = ev['d2'] if amp2 > 0.005 else ev['d1']
            kind = 'step' if r.random() < 0.5 else 'cycle'
            stretch = r.uniform(0.6, 2.0)
            hold = r.uniform(0.5, 4.0)
            scale = r.uniform(0.6, 1.7) * r.choice([1, 1, -1])
            waves = {key: event_wave(src, kind, stretch, hold, scale) for key, src in srcs.items()}
            L = max(len(wv) for wv in waves.values()) - 1
            if n - L - t_lo - int(fin_rest * FS_HZ) <= t_lo:
                continue
            placed = False
            for _try in range(20):
                t0 = r.randint(t_lo, n - L - int(0.5 * FS_HZ))
                ok = True
                for key in waves:
                    busy = busy1 if key == 'a1' else busy2
                    if any(not (t0 + L < a or t0 > b) for a, b in busy):
                        ok = False
                if ok:
                    placed = True
                    break
            if not placed:
                continue
            for key, wv in waves.items():
                dd = d1 if key == 'a1' else d2
                for j, a in enumerate(wv):
                    dd[t0 + j] += a
                (busy1 if key == 'a1' else busy2).append((t0, t0 + len(wv) - 1))
    return x, d1, d2, xp1, xp2


def quantize_disp(x):
    return [f32(round(a / Q_DISP) * Q_DISP) for a in x]


def quantize_act(xp, d, r, sd=1.2e-6):
    out = []
    for k, a in enumerate(d):
        val = xp + a + (r.gauss(0, sd) if k > 0 else 0.0)
        out.append(f32(round(val / Q_ACT) * Q_ACT) if k > 0 else xp)
    return out


def qforce(F):
    return round(F / Q_FORCE) * Q_FORCE


def build_record(T, r, want_act):
    x, d1, d2, xp1, xp2 = make_motion(T, r, want_act)
    xq = quantize_disp(x)
    x1 = quantize_act(xp1, d1, r)
    x2 = quantize_act(xp2, d2, r)
    v = drum_velocity(xq)
    rec = {'x': xq, 'x1': x1, 'x2': x2, 'x1p': x1[0], 'x2p': x2[0], 'v': v, 'n': len(xq),
           'act_mode': want_act}
    rec['age'] = rest_age(v)
    return rec


def ratio_of(recs, Fb, cat, shape, P, amp, sd):
    ss = 0.0
    cnt = 0
    for rec, fb in zip(recs, Fb):
        ft = true_force(rec, cat, shape, P, amp)
        for a, b in zip(ft, fb):
            ss += (a - b) ** 2
        cnt += len(fb)
    return math.sqrt(ss / cnt) / sd


def solve_amp(recs, Fb, cat, shape, P, sd, target, tol=0.001):
    nm, lo, hi, sense = AMP[shape]
    if sense > 0:
        rhi = ratio_of(recs, Fb, cat, shape, P, hi, sd)
        if rhi < target:
            return None, rhi
        a, b = lo, hi
        for _ in range(60):
            mid = 0.5 * (a + b)
            rm = ratio_of(recs, Fb, cat, shape, P, mid, sd)
            if abs(rm - target) / target < tol:
                return mid, rm
            if rm < target:
                a = mid
            else:
                b = mid
        return mid, rm
    # effect decreases with the parameter: scan down from hi in log steps to the first crossing
    grid = [hi * (lo / hi) ** (i / 40.0) for i in range(41)]
    prev = grid[0]
    rprev = ratio_of(recs, Fb, cat, shape, P, prev, sd)
    if rprev > target:
        return None, rprev
    for gval in grid[1:]:
        rg = ratio_of(recs, Fb, cat, shape, P, gval, sd)
        if rg >= target:
            a, b = math.log(prev), math.log(gval)     # ratio(a) < target <= ratio(b)
            for _ in range(60):
                mid = 0.5 * (a + b)
                rm = ratio_of(recs, Fb, cat, shape, P, math.exp(mid), sd)
                if abs(rm - target) / target < tol:
                    return math.exp(mid), rm
                if rm < target:
                    a = mid
                else:
                    b = mid
            return math.exp(mid), rm
        prev, rprev = gval, rg
    return None, rprev


def write_record(path, rec, Fmeas, T, r):
    n = rec['n']
    v = rec['v']
    af = T['af']
    rows = []
    for k in range(n):
        t = k * DT
        tt = int(t) if t == int(t) else t
        vc = f32(v[max(0, k - VEL_COL_LAG)] / VEL_COL_RATIO)
        F = Fmeas[k]
        Fp, Fm = max(F, 0.0), max(-F, 0.0)
        c6, c7 = af[6]['coef'], af[7]['coef']
        a1 = c6[0] + c6[1] * Fp + c6[2] * Fm + r.gauss(0, 0.6 * af[6]['sd'])
        a2 = c7[0] + c7[1] * Fp + c7[2] * Fm + r.gauss(0, 0.6 * af[7]['sd'])
        a1 = max(a1, 15.0)
        a2 = max(a2, 15.0)
        a1 = OFF_AF1 + round((a1 - OFF_AF1) / Q_AF1) * Q_AF1
        a2 = OFF_AF2 + round((a2 - OFF_AF2) / Q_AF2) * Q_AF2
        rows.append([tt, rec['x'][k], F, vc, rec['x1'][k], rec['x2'][k], a1, a2])
    obj = {'data': rows}
    for kk, vv in HEADER:
        obj[kk] = vv
    with open(path, 'w') as fh:
        json.dump(obj, fh)


def main():
    t_start = time.time()
    R = random.Random(MASTER_SEED)
    T = load_templates()
    # ---- trial plan ----
    plan = []
    cats = list(SHAPES.keys())
    # 12 strong / 12 weak: 4 categories get (2 strong, 1 weak), the other 4 get (1 strong, 2 weak)
    two_strong = set(R.sample(cats, 4))
    for cat in cats:
        ns = 2 if cat in two_strong else 1
        st = ['strong'] * ns + ['weak'] * (3 - ns)
        R.shuffle(st)
        for shape, s in zip(SHAPES[cat], st):
            plan.append((cat, shape, s))
    for _ in range(6):
        plan.append(('none', 'none', None))
    R.shuffle(plan)
    key = {}
    os.makedirs(os.path.join(ROOT, 'cases'), exist_ok=True)
    for ti, (cat, shape, strength) in enumerate(plan):
        tid = 't%02d' % (ti + 1)
        tr = random.Random(MASTER_SEED * 100 + ti + 1)
        noise_sd = tr.uniform(0.02, 0.06)
        target = tr.uniform(8.5, 11.5) if strength == 'strong' else (tr.uniform(2.7, 3.8) if strength == 'weak' else 0.0)
        P = shape_params(shape, tr) if cat != 'none' else {}
        attempts = 0
        while True:
            attempts += 1
            mr = random.Random(tr.getrandbits(64))
            modes = [mr.choice(['none', 'a1', 'a2', 'both', 'both', 'both']) for _ in range(2)]
            if modes[0] == 'none' and modes[1] == 'none':
                modes[mr.randint(0, 1)] = mr.choice(['a1', 'a2', 'both'])
            recs = [build_record(T, mr, m) for m in modes]
            for rec in recs:
                rec['F0_true'] = mr.uniform(-1.0, 1.0)
            # noise sequences and the anchored first sample
            seeds = [tr.getrandbits(48) for _ in recs]
            noises = []
            for rec, sd_seed in zip(recs, seeds):
                nr = random.Random(sd_seed)
                nz = [nr.gauss(0.0, noise_sd) for _ in range(rec['n'])]
                noises.append(nz)
                rec['F0'] = qforce(rec['F0_true'] + nz[0])
            Fb = [base_force(rec) for rec in recs]
            if cat == 'none':
                amp, ratio = None, 0.0
                break
            amp, ratio = solve_amp(recs, Fb, cat, shape, P, noise_sd, target)
            if amp is not None:
                break
            print('  %s %s/%s: target %.2f not reachable (max %.2f), new motions' % (tid, cat, shape, target, ratio),
                  flush=True)
            if attempts >= 60:
                raise SystemExit('cannot reach target for ' + tid)
        Ft = [true_force(rec, cat, shape, P, amp) if cat != 'none' else fb for rec, fb in zip(recs, Fb)]
        tdir = os.path.join(ROOT, 'cases', tid)
        os.makedirs(tdir, exist_ok=True)
        recinfo = {}
        for lab, rec, ft, nz, sd_seed in zip('AB', recs, Ft, noises, seeds):
            Fm = [rec['F0']] + [qforce(ft[k] + nz[k]) for k in range(1, rec['n'])]
            write_record(os.path.join(tdir, lab + '.json'), rec, Fm, T, random.Random(sd_seed + 7))
            fb = Fb['AB'.index(lab)]
            recinfo[lab] = {'duration_s': round((rec['n'] - 1) * DT, 4), 'actuators': rec['act_mode'],
                            'noise_seed': sd_seed, 'F0_kip': rec['F0'],
                            'rms_effect_kip': round(math.sqrt(sum((a - b) ** 2 for a, b in zip(ft, fb)) / len(fb)), 5)}
        entry = {'category': cat, 'shape': shape, 'strength': strength if cat != 'none' else None,
                 'ratio': ratio, 'target_ratio': target if cat != 'none' else 0.0,
                 'noise_kip': noise_sd, 'params': dict(P), 'records': recinfo,
                 'motion_attempts': attempts}
        if cat != 'none':
            nm = AMP[shape][0]
            entry['params'][nm] = amp
            entry['amplitude_name'] = nm
            entry['amplitude_bounds'] = [AMP[shape][1], AMP[shape][2]]
        key[tid] = entry
        print('%s %-16s %-38s %-6s ratio %.3f (target %.3f) noise %.4f attempts %d  [%.0f s]' % (
            tid, cat, shape, strength, ratio, target, noise_sd, attempts, time.time() - t_start), flush=True)
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1, sort_keys=True)
    print('done in %.1f s' % (time.time() - t_start))


if __name__ == '__main__':
    main()
