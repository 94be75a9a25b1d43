#!/usr/bin/env python3
"""Blind test set 28 for the BRFD model-discrepancy tool.

Deterministic from MASTER_SEED: regenerates cases/t01..t30/{A,B}.json and key.json.
Python 3 standard library only.  Usage:  python3 gen/gen.py   (from /work/blind28 or anywhere)

Base model (inferred from the black box, see NOTES.md):
  * drum velocity v = central differences of the displacement column (one-sided at the ends),
    then a zero-phase moving average of half-width min(7, i, n-1-i) (15 samples, shrinking
    symmetrically at the record ends).  The velocity COLUMN of the files is ~1/125 of dx/dt
    (data quirk) and is NOT used.
  * z(0) = F_measured(0) / sigma0.
  * step i-1 -> i: exact exponential solution of dz/dt = v_i - sigma0 |v_i| / g_i * z with v, Fc,
    Fs held at their values at sample i; F_i = sigma0 z_i + sigma1 zdot + sigma2 v_i (sigma1 = 0).
  * Fc from Eq. (4) with the actuator positions of sample i, x' = positions of row 0, clipped
    at fc_floor; Fs/Fc forward for v >= 0, backward for v < 0.
"""
import json, math, os, random, struct, sys

MASTER_SEED = 28028
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SRC = '/work/shared/data/brfd/semiactive'
SRC_FILES = ['harmonic0.03ea1forward.json', 'harmonic0.03ea1backward.json',
             'harmonic0.03ea2forward.json', 'harmonic0.03ea2backward.json',
             'harmonic0.015forward.json', 'harmonic0.015backward.json']
DT = 0.0009765625
FS_HZ = 1024

# ---------------------------------------------------------------- base model (config values)
S0, S1, S2 = 15.36, 0.0, 0.500
FSF, FSB, FCF, FCB, VS = 7.116, 3.760, 2.648, 1.253, 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FLOOR = 0.05
K1F = C[0] * M[0] + C[1] * M[2]   # dFc/dx1 forward
K2F = C[0] * M[1] + C[1] * M[3]   # dFc/dx2 forward
K1B = C[2] * M[4] + C[3] * M[6]   # dFc/dx1 backward
K2B = C[2] * M[5] + C[3] * M[7]   # dFc/dx2 backward

# ---------------------------------------------------------------- quantisation (fitted on the measured files)
QF = 0.00080087996427685          # friction force LSB (kip), grid through 0
QD = 5.894216748733203e-05        # displacement LSB (in)
QA = 2.441406e-06                 # actuator position LSB (in)
QA1F = 0.31793998262477785        # actuator 1 force LSB (lb)
QA2F = 0.3998999640150478         # actuator 2 force LSB (lb)
VCOL_SCALE = 125.28               # velocity column = (dx/dt)/125.28, delayed 8 samples (quirk)
VCOL_DELAY = 8


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def qgrid(x, q, off):
    return off + round((x - off) / q) * q


def quantF(x):
    return round(x / QF) * QF


def grid_offset(vals, q):
    """offset of a uniform grid k*q+off that fits the sorted unique values."""
    vals = sorted(set(vals))
    k = [0]
    for i in range(1, len(vals)):
        k.append(k[-1] + round((vals[i] - vals[i - 1]) / q))
    n = len(vals)
    off = sum(v - q * kk for v, kk in zip(vals, k)) / n
    return off - math.floor(off / q) * q


def velocity(x, dt=DT):
    """The black box's drum velocity: central differences + 15-sample zero-phase moving average."""
    n = len(x)
    d = [0.0] * n
    d[0] = (x[1] - x[0]) / dt
    d[n - 1] = (x[n - 1] - x[n - 2]) / dt
    for i in range(1, n - 1):
        d[i] = (x[i + 1] - x[i - 1]) / (2 * dt)
    cs = [0.0]
    for a in d:
        cs.append(cs[-1] + a)
    out = [0.0] * n
    for i in range(n):
        h = min(7, i, n - 1 - i)
        out[i] = (cs[i + h + 1] - cs[i - h]) / (2 * h + 1)
    return out


# ---------------------------------------------------------------- shapes
# name -> (category, parameter name, lower bound, upper (physical cap), first guess, description)
SHAPES = {
    'BL1': ('backlash', 'gap_in', 0.0, 0.25, 0.02, 'slack-band dead zone in the band deflection'),
    'BL2': ('backlash', 'A_kip', 0.0, 4.0, 0.3, 'clearance impact ringing after each reversal'),
    'BL3': ('backlash', 'beta', 0.0, 0.97, 0.3, 'travel-dependent re-engagement stiffness after reversal'),
    'RS1': ('residual_static', 'k_per_s', 0.0, 30.0, 0.5, 'Maxwell relaxation of the held band force at rest'),
    'RS2': ('residual_static', 'c_per_s_kip2', 0.0, 20.0, 0.05, 'Norton power-law creep (n=3) of the held force at rest'),
    'RS3': ('residual_static', 'kappa_per_in', 0.0, 3.0, 0.05, 'thermal contraction of the band while it cools at rest'),
    'TS1': ('transition_shape', 'u', 0.0, 1.6, 0.3, 'generalised Stribeck exponent delta = 2 - u'),
    'TS2': ('transition_shape', 'w', 0.0, 1.0, 0.3, 'elasto-plastic presliding (Dupont) blend weight'),
    'TS3': ('transition_shape', 'tau_s', 0.0, 1.0, 0.05, 'frictional memory: Stribeck curve of lagged velocity'),
    'V1': ('velocity', 'A', 0.0, 2.0, 0.05, 'rate-strengthening ln(1+|v|/v*) factor on g'),
    'V2': ('velocity', 'w', 0.0, 0.95, 0.1, 'flash-heating weakening of the kinetic level'),
    'V3': ('velocity', 'A_kip', 0.0, 3.0, 0.05, 'Eyring asinh shear-thinning drag'),
    'AL1': ('actuator_lag', 'T_s', 0.0, 0.6, 0.03, 'underdamped second-order band tension response'),
    'AL2': ('actuator_lag', 'inv_rate_s_per_in', 0.0, 400.0, 5.0, 'slew-rate-limited band clamping'),
    'AL3': ('actuator_lag', 'tau_apply_s', 0.0, 0.6, 0.03, 'asymmetric apply/release first-order lag'),
    'SE1': ('self_energizing', 'A', 0.0, 3.0, 0.1, 'wrap tightening with drum travel since reversal, energizing direction'),
    'SE2': ('self_energizing', 'kappa', 0.0, 2.2, 0.1, 'load-dependent servo factor 1/(1 -/+ kappa Fc/Fref)'),
    'SE3': ('self_energizing', 'c_per_in', 0.0, 2.5, 0.1, 'capstan amplification with drum-angle dependent wrap'),
    'PT1': ('pretension', 'u', 0.0, 6.0, 0.3, 'quadratic (Hertz-type) stiffening of the clamping law'),
    'PT2': ('pretension', 'inv_Ls_per_kip', 0.0, 50.0, 0.5, 'saturating clamping law Ls*tanh(L/Ls)'),
    'PT3': ('pretension', 'kappa_kip_per_in2', 0.0, 30000.0, 500.0, 'coupling of the two actuators through the shared band'),
    'AS1': ('asymmetry', 'u', 0.0, 2.0, 0.1, 'direction-dependent Stribeck velocity vs*exp(+-u)'),
    'AS2': ('asymmetry', 'dsigma2', 0.0, 3.0, 0.05, 'direction-dependent viscous coefficient'),
    'AS3': ('asymmetry', 'u', 0.0, 1.5, 0.1, 'band-dependent deflection stiffness sigma0*exp(+-u)'),
}
CATS = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
        'self_energizing', 'pretension', 'asymmetry']

V_GATE = 0.15     # in/s, rest gate
V_REV = 0.30      # in/s, reversal detection threshold (rest-noise spikes reach ~0.24 in/s)


def lag_positions(a, x0, kind, p, fixed):
    """effective (band) actuator positions for the actuator_lag shapes."""
    n = len(a)
    if p <= 0:
        return list(a)
    y = [0.0] * n
    y[0] = a[0]
    if kind == 'AL1':
        T = p; zeta = fixed['zeta']; w = 1.0 / T
        nsub = max(1, int(math.ceil(DT * w * 4)))
        h = DT / nsub
        yy, yd = a[0], 0.0
        for i in range(1, n):
            for _ in range(nsub):
                yd += h * (w * w * (a[i] - yy) - 2 * zeta * w * yd)
                yy += h * yd
            y[i] = yy
    elif kind == 'AL2':
        r = 1.0 / p   # in/s
        cfast = 1 - math.exp(-DT / 0.004)
        yy = a[0]
        for i in range(1, n):
            d = (a[i] - yy) * cfast
            lim = r * DT
            if d > lim: d = lim
            elif d < -lim: d = -lim
            yy += d
            y[i] = yy
    elif kind == 'AL3':
        ca = 1 - math.exp(-DT / p)
        cr = 1 - math.exp(-DT / (p * fixed['release_factor']))
        yy = a[0]
        for i in range(1, n):
            d = a[i] - yy
            yy += d * (ca if d < 0 else cr)   # d<0: retraction = clamp apply (fast)
            y[i] = yy
    return y


def simulate(R, shape=None, p=0.0, fixed=None):
    """Force (kip) of the base model (shape None) or of the base model plus one effect."""
    x = R['x']; v = R['v']; n = len(x)
    a1 = R['x1']; a2 = R['x2']; x10 = a1[0]; x20 = a2[0]
    fixed = fixed or {}
    if shape in ('AL1', 'AL2', 'AL3'):
        a1 = lag_positions(a1, x10, shape, p, fixed)
        a2 = lag_positions(a2, x20, shape, p, fixed)
    F0 = R['F0']
    exp = math.exp
    F = [0.0] * n
    # effect constants
    sh = shape if p > 0 else None
    de = fixed.get('dir', 1)
    # initial state
    if sh == 'BL1':
        b = p
        z = (abs(F0) / S0 + b) * (1 if F0 >= 0 else -1) if F0 != 0 else 0.0
    elif sh == 'BL3':
        z = F0 / S0
    elif sh == 'AS3':
        s0z = S0 * exp(p) if (F0 >= 0) == (de > 0) else S0
        z = F0 / s0z
    else:
        z = F0 / S0
    F[0] = F0 + S2 * v[0]
    # reversal tracking
    d = 0; xext = x[0]; xturn = x[0]; tsw = -1e9; nrev = 0
    trest = 0.0; H = 0.0; vm = v[0]; Fprev = F[0]
    for i in range(1, n):
        vi = v[i]; xi = x[i]
        fwd = vi >= 0
        # --- reversal / travel bookkeeping
        if d == 0:
            if abs(vi) > V_REV:
                d = 1 if vi > 0 else -1; xext = xi; xturn = x[0]
        else:
            if d > 0:
                if xi > xext: xext = xi
            else:
                if xi < xext: xext = xi
            if d * vi < -V_REV and abs(xi - xext) > 0.02:
                d = -d; xturn = xext; xext = xi; tsw = i * DT; nrev += 1
        s_trav = abs(xi - xturn)
        # --- kinetic friction, Eq. (4)
        if fwd:
            b0 = FCF; L = K1F * (a1[i] - x10) + K2F * (a2[i] - x20); Fs = FSF
        else:
            b0 = FCB; L = K1B * (a1[i] - x10) + K2B * (a2[i] - x20); Fs = FSB
        if sh == 'PT1':
            Fc = b0 + L + p * L * L / (2.0 * b0)
        elif sh == 'PT2':
            # saturating band force: the travel term saturates at +-1/p kip
            Ls = 1.0 / p
            Fc = b0 + Ls * math.tanh(L / Ls)
        elif sh == 'PT3':
            Fc = b0 + L - p * (a1[i] - x10) * (a2[i] - x20)
        else:
            Fc = b0 + L
        if Fc < FLOOR:
            Fc = FLOOR
        if sh == 'SE1':
            if (1 if fwd else -1) == de:
                Fc *= 1.0 + p * (1.0 - exp(-s_trav / fixed['lam']))
        elif sh == 'SE2':
            if (1 if fwd else -1) == de:
                Fc = Fc / (1.0 - p * Fc / fixed['Fref'])
            else:
                Fc = Fc / (1.0 + p * Fc / fixed['Fref'])
        elif sh == 'SE3':
            Fc *= exp(p * xi * (1 if fwd else -1))
        # --- Stribeck
        if sh == 'TS1':
            dlt = 2.0 - p
            E = exp(-(abs(vi) / VS) ** dlt) if vi != 0 else 1.0
        elif sh == 'TS3':
            vm += (vi - vm) * (1.0 - exp(-DT / p))
            E = exp(-(vm / VS) ** 2)
        elif sh == 'AS1':
            vsd = VS * exp(p * fixed['sign']) if (1 if fwd else -1) == de else VS
            E = exp(-(vi / vsd) ** 2)
        else:
            E = exp(-(vi / VS) ** 2)
        g = Fc + (Fs - Fc) * E
        if sh == 'V1':
            g *= 1.0 + p * math.log(1.0 + abs(vi) / fixed['vstar'])
        elif sh == 'V2':
            vw = fixed['vw']
            g *= 1.0 - p * (1.0 - vw / math.sqrt(vw * vw + vi * vi))
        s0e = S0
        if sh == 'BL3':
            if nrev > 0:
                s0e = S0 * (1.0 - p * exp(-s_trav / fixed['lam']))
        elif sh == 'AS3':
            s0e = S0 * exp(p) if (z >= 0) == (de > 0) else S0
        a = s0e * abs(vi) / g
        gate = None
        if sh in ('RS1', 'RS2', 'RS3'):
            gate = exp(-(vi / V_GATE) ** 2)
            if sh == 'RS1':
                a += p * gate
            elif sh == 'RS2':
                a += p * gate * (S0 * z) ** 2
        elif sh == 'TS2':
            zss = g / S0; zba = fixed['rho'] * zss
            az = abs(z)
            if (z > 0) != (vi > 0) or az <= zba:
                ad = 0.0
            elif az >= zss:
                ad = 1.0
            else:
                ad = 0.5 * math.sin(math.pi * (az - 0.5 * (zss + zba)) / (zss - zba)) + 0.5
            a *= (1.0 - p) + p * ad
        # --- state step (exact exponential, inputs held at sample i)
        if sh == 'BL1':
            z = _step_deadzone(z, vi, a, p, DT)
        else:
            if a > 0:
                zi = vi / a
                z = zi + (z - zi) * exp(-a * DT)
            else:
                z += vi * DT
        if sh == 'RS3':
            tauh = fixed['tau_h']
            H += (abs(Fprev * vi) - H / tauh) * DT
            z += gate * p * (H / tauh) * math.tanh(S0 * z / 0.1) / S0 * DT
        # --- output
        if sh == 'BL1':
            dz = abs(z) - p
            Fi = (S0 * dz * (1 if z > 0 else -1) if dz > 0 else 0.0) + S2 * vi
        elif sh in ('BL3', 'AS3'):
            if sh == 'AS3':
                s0e = S0 * exp(p) if (z >= 0) == (de > 0) else S0
            Fi = s0e * z + S2 * vi
        elif sh == 'AS2':
            Fi = S0 * z + (S2 + (p if (1 if fwd else -1) == de else 0.0)) * vi
        else:
            Fi = S0 * z + S2 * vi
        if sh == 'V3':
            Fi += p * math.asinh(vi / fixed['ve'])
        elif sh == 'BL2' and nrev > 0:
            tp = i * DT - tsw
            if tp < 0.5:
                Fi -= p * d * exp(-tp / fixed['tau']) * math.sin(2 * math.pi * fixed['f_hz'] * tp)
        F[i] = Fi
        Fprev = Fi
    return F


def _step_deadzone(z, v, a, b, dt):
    """dz/dt = v - a*D(z), D = dead zone of half-width b; exact piecewise solution."""
    t = dt
    for _ in range(4):
        if t <= 0:
            break
        if abs(z) < b or (abs(z) == b and v * z <= 0):
            if v == 0:
                return z
            zb = b if v > 0 else -b
            tc = (zb - z) / v
            if tc >= t:
                return z + v * t
            z = zb; t -= tc
            continue
        sgn = 1.0 if z > 0 else -1.0
        w = z - sgn * b
        if a <= 0:
            wn = w + v * t
            if wn * sgn < 0:
                tc = -w / v; z = sgn * b; t -= tc; continue
            return sgn * b + wn
        wi = v / a
        wn = wi + (w - wi) * math.exp(-a * t)
        if wn * sgn >= 0:
            return sgn * b + wn
        # crosses into the dead zone
        tc = math.log((w - wi) / (-wi)) / a
        z = sgn * b; t -= tc
    return z


# ---------------------------------------------------------------- measured material
def load_sources():
    src = {}
    for fn in SRC_FILES:
        with open(os.path.join(SRC, fn)) as fh:
            d = json.load(fh)
        D = d['data']
        cols = list(zip(*D))
        rec = {'name': fn, 'header': [k for k in d.keys()], 'hdr': {k: d[k] for k in d if k != 'data'},
               't': list(cols[0]), 'x': list(cols[1]), 'F': list(cols[2]), 'vc': list(cols[3]),
               'x1': list(cols[4]), 'x2': list(cols[5]), 'a1': list(cols[6]), 'a2': list(cols[7])}
        rec['offD'] = grid_offset(rec['x'], QD)
        rec['offA1'] = grid_offset(rec['x1'], QA)
        rec['offA2'] = grid_offset(rec['x2'], QA)
        rec['offF1'] = grid_offset(rec['a1'], QA1F)
        rec['offF2'] = grid_offset(rec['a2'], QA2F)
        n = len(D); x = rec['x']
        # extrema of the steady 1-in cycles
        ext = []
        for i in range(300, n - 300):
            if abs(x[i]) > 0.9:
                w = x[i - 250:i + 251]
                if (x[i] >= max(w) or x[i] <= min(w)) and (not ext or i - ext[-1] > 300):
                    ext.append(i)
        x1 = rec['x1']; x2 = rec['x2']
        mv = [j for j in range(n) if abs(x1[j] - x1[0]) > 0.001 or abs(x2[j] - x2[0]) > 0.001]
        groups = []
        for j in mv:
            if groups and j - groups[-1][1] <= 200:
                groups[-1][1] = j
            else:
                groups.append([j, j])
        strokes = []
        for ia, ib in zip(ext[:-1], ext[1:]):
            span = x[ib] - x[ia]
            u = [(x[j] - x[ia]) / span for j in range(ia, ib + 1)]
            moving = any(not (g1 < ia - 100 or g0 > ib + 100) for g0, g1 in groups)
            strokes.append({'ia': ia, 'ib': ib, 'u': u, 'event': moving})
        # actuator motion events: one harmonic cycle of x1 and/or x2 during one drum stroke
        events = []
        for g0, g1 in groups:
            j0, j1 = g0 - 20, g1 + 20
            host_s = max(strokes, key=lambda s_: min(s_['ib'], j1) - max(s_['ia'], j0))
            events.append({'src': fn, 't0': round(j0 * DT, 4), 't1': round(j1 * DT, 4),
                           'd1': [x1[j] - x1[0] for j in range(j0, j1 + 1)],
                           'd2': [x2[j] - x2[0] for j in range(j0, j1 + 1)],
                           'both': '0.015' in fn, 'stroke': host_s})
        rec['strokes'] = strokes
        rec['events'] = events
        # rest noise (final rest) of displacement, mean removed
        mv = [i for i in range(n) if abs(x[i] - x[-1]) > 0.01]
        r0 = mv[-1] + 300
        seg = x[r0:]
        m = sum(seg) / len(seg)
        rec['restx'] = [a - m for a in seg]
        vseg = rec['vc'][r0:]
        mv_ = sum(vseg) / len(vseg)
        rec['vc_sd'] = (sum((a - mv_) ** 2 for a in vseg) / len(vseg)) ** 0.5
        src[fn] = rec
    # actuator-force model: a_k = c0 + cp*max(F,0) + cn*max(-F,0) (lb), least squares on all files
    def lsq(rows, ys):
        # 3x3 normal equations
        A = [[0.0] * 3 for _ in range(3)]; bb = [0.0] * 3
        for r, y in zip(rows, ys):
            for p_ in range(3):
                bb[p_] += r[p_] * y
                for q_ in range(3):
                    A[p_][q_] += r[p_] * r[q_]
        # gauss
        for c_ in range(3):
            piv = A[c_][c_]
            for r_ in range(c_ + 1, 3):
                f = A[r_][c_] / piv
                for k_ in range(3):
                    A[r_][k_] -= f * A[c_][k_]
                bb[r_] -= f * bb[c_]
        sol = [0.0] * 3
        for c_ in (2, 1, 0):
            sol[c_] = (bb[c_] - sum(A[c_][k_] * sol[k_] for k_ in range(c_ + 1, 3))) / A[c_][c_]
        return sol
    rows = []; y1 = []; y2 = []
    for rec in src.values():
        for j in range(0, len(rec['F']), 7):
            Fj = rec['F'][j]
            rows.append((1.0, max(Fj, 0.0), max(-Fj, 0.0))); y1.append(rec['a1'][j]); y2.append(rec['a2'][j])
    c1 = lsq(rows, y1); c2 = lsq(rows, y2)
    r1 = [y - (c1[0] + c1[1] * r[1] + c1[2] * r[2]) for r, y in zip(rows, y1)]
    r2 = [y - (c2[0] + c2[1] * r[1] + c2[2] * r[2]) for r, y in zip(rows, y2)]
    sd1 = (sum(a * a for a in r1) / len(r1)) ** 0.5; sd2 = (sum(a * a for a in r2) / len(r2)) ** 0.5
    actmodel = {'a1': c1, 'a2': c2, 'sd1': min(sd1, 25.0), 'sd2': min(sd2, 40.0)}
    return src, actmodel


def resample(u, L):
    """linear interpolation of template u onto L samples (same end points)."""
    n = len(u)
    if L == n:
        return list(u)
    out = []
    for k in range(L):
        s = k * (n - 1) / (L - 1)
        j = int(s)
        if j >= n - 1:
            out.append(u[-1])
        else:
            f = s - j
            out.append(u[j] * (1 - f) + u[j + 1] * f)
    return out


def tile_noise(rng, pool, m):
    """m samples of measured rest noise: random chunks joined continuously (starts at 0)."""
    out = []
    last = 0.0
    while len(out) < m:
        arr = rng.choice(pool)
        j0 = rng.randrange(0, len(arr) - 50)
        k = min(m - len(out), len(arr) - j0)
        chunk = arr[j0:j0 + k]
        off = last - chunk[0]
        out.extend(a + off for a in chunk)
        last = out[-1]
    return out


def build_record(rng, src, actmodel, cfg):
    """Displacement and actuator traces from pieces of the measured tests.
    cfg: need_motion, early, both (prefer two-actuator events), nev (range)."""
    host = src[rng.choice(SRC_FILES)]
    allstrokes = [(fn, s) for fn in SRC_FILES for s in src[fn]['strokes']]
    allevents = [e for fn in SRC_FILES for e in src[fn]['events']]
    pool = [src[fn]['restx'] for fn in SRC_FILES]
    t_body = rng.uniform(5.0, 20.0)            # duration of strokes+inner rests
    t_final = rng.uniform(1.6, 3.2)
    early = cfg['early']
    nev_lo, nev_hi = cfg['nev']
    nev = rng.randint(nev_lo, nev_hi)
    plan = []          # list of ('rest', m) / ('stroke', info)
    t0 = rng.uniform(0.05, 0.3) if early else rng.uniform(0.05, 1.2)
    plan.append(('rest', max(2, int(t0 / DT))))
    t = t0
    pos = start_pos = rng.uniform(-0.3, 0.3)
    plan_last_dir = 1
    nstroke = 0
    while t < t_body or nstroke < 3:
        A = rng.uniform(0.5, 2.3)
        ts = rng.uniform(0.6, 1.7)
        # direction: alternate mostly, keep |x| <= 1.3
        if nstroke == 0:
            dr = rng.choice([-1, 1])
        else:
            dr = -plan_last_dir if rng.random() < 0.8 else plan_last_dir
        if abs(pos + dr * A) > 1.3:
            dr = -dr
            if abs(pos + dr * A) > 1.3:
                A = max(0.4, 1.25 - pos * dr)
        plan_last_dir = dr
        plan.append(('stroke', {'A': A, 'ts': ts, 'dir': dr, 'start_t': t}))
        pos += dr * A
        nstroke += 1
        t += ts
        if rng.random() < 0.35 and t < t_body:
            tr = rng.uniform(0.3, 2.0)
            plan.append(('rest', int(tr / DT)))
            t += tr
        if t > 22.0 - t_final:
            break
    # choose event strokes
    sidx = [k for k, (kind, _) in enumerate(plan) if kind == 'stroke']
    if early:
        cand = sidx[1:]
        chosen = [sidx[0]]
        nev = max(nev, 1)
    else:
        cand = [k for k in sidx if plan[k][1]['start_t'] >= 1.0]
        chosen = []
    rng.shuffle(cand)
    chosen += cand[:max(0, nev - len(chosen))]
    nboth = 0
    for k in chosen:
        ev = rng.choice(allevents)
        if cfg.get('both') and nboth < 2:
            ev = rng.choice([e for e in allevents if e['both']])
        nboth += ev['both']
        info = plan[k][1]
        info['event'] = ev
        info['ts'] = max(info['ts'], (len(ev['d1']) + 40) / len(ev['stroke']['u']))
        info['ev_scale'] = rng.uniform(0.8, 1.5) * rng.choice([-1, 1])
    # synthesise
    x = []; d1 = []; d2 = []
    pos = start_pos
    events_info = []
    for kind, info in plan:
        if kind == 'rest':
            m = info
            nz = tile_noise(rng, pool, m)
            x.extend(pos + a for a in nz)
            d1.extend([0.0] * m); d2.extend([0.0] * m)
        else:
            if 'event' in info:
                ev = info['event']; u0 = ev['stroke']['u']
                srcname = ev['src']; sia = ev['stroke']['ia']
            else:
                fn, s = rng.choice(allstrokes)
                u0 = s['u']; srcname = fn; sia = s['ia']
            L = max(200, int(round(len(u0) * info['ts'])))
            u = resample(u0, L)
            start = len(x)
            x.extend(pos + info['dir'] * info['A'] * a for a in u)
            d1.extend([0.0] * L); d2.extend([0.0] * L)
            info['piece'] = {'src': srcname, 'src_t0': round(sia * DT, 4), 'len_s': round(L * DT, 4),
                             'travel_in': round(info['A'], 4), 'dir': info['dir'],
                             'time_scale': round(L / len(u0), 4)}
            if 'event' in info:
                ev = info['event']
                le = len(ev['d1'])
                off = start + (L - le) // 2
                for j in range(le):
                    if off + j < len(d1):
                        d1[off + j] += ev['d1'][j] * info['ev_scale']
                        d2[off + j] += ev['d2'][j] * info['ev_scale']
                # (the tail past the stroke end is appended when the trace is longer)
                events_info.append({'src': ev['src'], 'src_t0': ev['t0'], 'src_t1': ev['t1'],
                                    'scale': round(info['ev_scale'], 4),
                                    't_start': round(off * DT, 4), 'stroke_dir': info['dir']})
            pos = x[-1]
    # final rest
    m = int(t_final / DT)
    nz = tile_noise(rng, pool, m)
    x.extend(pos + a for a in nz)
    d1.extend([0.0] * m); d2.extend([0.0] * m)
    n = len(x)
    # actuator baseline noise: measured traces of a non-moving actuator (mean removed chunks)
    quiet = [[a - src['harmonic0.03ea2forward.json']['x1'][0] for a in src['harmonic0.03ea2forward.json']['x1']],
             [a - src['harmonic0.03ea2backward.json']['x1'][0] for a in src['harmonic0.03ea2backward.json']['x1']],
             [a - src['harmonic0.03ea1forward.json']['x2'][0] for a in src['harmonic0.03ea1forward.json']['x2']],
             [a - src['harmonic0.03ea1backward.json']['x2'][0] for a in src['harmonic0.03ea1backward.json']['x2']]]
    q1 = tile_noise(rng, quiet, n); q2 = tile_noise(rng, quiet, n)
    x10 = host['x1'][0]; x20 = host['x2'][0]
    # quantise
    xq = [f32(qgrid(a, QD, host['offD'])) for a in x]
    xq[1] = xq[0]
    x1q = [f32(qgrid(x10 + a + b * 0.25, QA, host['offA1'])) for a, b in zip(d1, q1)]
    x2q = [f32(qgrid(x20 + a + b * 0.25, QA, host['offA2'])) for a, b in zip(d2, q2)]
    x1q[0] = f32(x10); x2q[0] = f32(x20)
    pieces = [info['piece'] for kind, info in plan if kind == 'stroke']
    rests = [round(info * DT, 4) for kind, info in plan if kind == 'rest']
    return {'x': xq, 'x1': x1q, 'x2': x2q, 'host': host['name'],
            'info': {'host_file': host['name'], 'duration_s': round((n - 1) * DT, 4),
                     'n_samples': n, 'final_rest_s': round(m * DT, 4), 'strokes': pieces,
                     'rests_s': rests, 'actuator_events': events_info, 'early_motion_planned': early}}


def write_record(path, src, R, Frec, rngaux, actmodel):
    host = src[R['host']]
    n = len(R['x'])
    v = R['v']
    rows = []
    c1 = actmodel['a1']; c2 = actmodel['a2']
    vsd = host['vc_sd']
    for i in range(n):
        t = i * DT
        tt = int(t) if t == int(t) else t
        vi = v[max(0, i - VCOL_DELAY)] / VCOL_SCALE + rngaux.gauss(0.0, vsd)
        Fi = Frec[i]
        a1 = c1[0] + c1[1] * max(Fi, 0) + c1[2] * max(-Fi, 0) + rngaux.gauss(0.0, actmodel['sd1'])
        a2 = c2[0] + c2[1] * max(Fi, 0) + c2[2] * max(-Fi, 0) + rngaux.gauss(0.0, actmodel['sd2'])
        a1 = qgrid(max(a1, 20.0), QA1F, host['offF1'])
        a2 = qgrid(max(a2, 20.0), QA2F, host['offF2'])
        row = [tt, R['x'][i], Fi, vi, R['x1'][i], R['x2'][i], a1, a2]
        rows.append([0 if (k > 0 and val == 0) else val for k, val in enumerate(row)])
    d = {'data': rows}
    for k in host['header']:
        if k != 'data':
            d[k] = host['hdr'][k]
    with open(path, 'w') as fh:
        json.dump(d, fh)


def ratio_of(RA, RB, FtA, FtB, FbA, FbB, noise):
    s = 0.0
    for Ft, Fb in ((FtA, FbA), (FtB, FbB)):
        for a, b in zip(Ft, Fb):
            s += (a - b) ** 2
    return math.sqrt(s / (len(FtA) + len(FtB))) / noise


def solve_amplitude(shape, fixed, RA, RB, FbA, FbB, noise, target):
    cat, pname, lo, cap, guess, _ = SHAPES[shape]
    def R(p):
        return ratio_of(RA, RB, simulate(RA, shape, p, fixed), simulate(RB, shape, p, fixed), FbA, FbB, noise)
    hi = guess; rhi = R(hi)
    plo, rlo = 0.0, 0.0
    while rhi < target and hi < cap:
        plo, rlo = hi, rhi
        hi = min(cap, hi * 2.0)
        rhi = R(hi)
    if rhi < target:
        return None, rhi
    # Illinois regula falsi on R(p) - target
    a, fa = plo, rlo - target; b, fb = hi, rhi - target
    side = 0; p = b; r = rhi
    for _ in range(60):
        p = (a * fb - b * fa) / (fb - fa)
        r = R(p); fp = r - target
        if abs(fp) < 2e-4 * target:
            break
        if fp * fb > 0:
            b, fb = p, fp
            if side == -1: fa /= 2
            side = -1
        else:
            a, fa = p, fp
            if side == 1: fb /= 2
            side = 1
    return p, r


def fixed_params(shape, rng):
    f = {}
    if shape == 'BL2': f = {'tau': 0.1, 'f_hz': 8.0}
    elif shape == 'BL3': f = {'lam': 0.12}
    elif shape == 'RS3': f = {'tau_h': 3.0}
    elif shape == 'TS2': f = {'rho': 0.6}
    elif shape == 'V1': f = {'vstar': 2.0}
    elif shape == 'V2': f = {'vw': 1.5}
    elif shape == 'V3': f = {'ve': 0.2}
    elif shape == 'AL1': f = {'zeta': 0.3}
    elif shape == 'AL3': f = {'release_factor': 4.0}
    elif shape == 'SE1': f = {'lam': 0.6, 'dir': rng.choice([1, -1])}
    elif shape == 'SE2': f = {'Fref': 10.0, 'dir': rng.choice([1, -1])}
    elif shape == 'AS1': f = {'dir': rng.choice([1, -1]), 'sign': rng.choice([1, -1])}
    elif shape == 'AS2': f = {'dir': rng.choice([1, -1])}
    elif shape == 'AS3': f = {'dir': rng.choice([1, -1])}
    return f


def make_trial(args):
    tid, slot, early_flags, src_actmodel = args
    src, actmodel = src_actmodel
    shape, strength = slot
    trng = random.Random(MASTER_SEED * 1000 + int(tid[1:]))
    noise = trng.uniform(0.02, 0.06)
    cat = SHAPES[shape][0] if shape != 'none' else 'none'
    need_motion = cat in ('actuator_lag', 'pretension')
    fixed = fixed_params(shape, trng) if shape != 'none' else {}
    if shape != 'none':
        lohi = (2.7, 3.8) if strength == 'weak' else (8.5, 11.5)
        target = trng.uniform(*lohi)
    else:
        target = 0.0
    note = ''
    for attempt in range(6):
        recs = {}
        for lab, early in zip(('A', 'B'), early_flags):
            rrng = random.Random(trng.randrange(1 << 30))
            if need_motion:
                nev = (4, 9)
            else:
                nev = (2, 9) if (early or rrng.random() < 0.8) else (0, 0)
            cfg = {'early': early, 'nev': nev, 'both': shape == 'PT3'}
            R = build_record(rrng, src, actmodel, cfg)
            R['v'] = velocity(R['x'])
            nseed = trng.randrange(1 << 30)
            R['noise_seed'] = nseed
            nrng = random.Random(nseed)
            R['noise'] = [nrng.gauss(0.0, noise) for _ in range(len(R['x']))]
            F_init = trng.uniform(-1.2, 1.5)
            R['F0'] = quantF(F_init + R['noise'][0])
            R['aux_seed'] = trng.randrange(1 << 30)
            recs[lab] = R
        RA, RB = recs['A'], recs['B']
        FbA = simulate(RA); FbB = simulate(RB)
        if shape == 'none':
            p = 0.0; ratio = 0.0
            break
        p, ratio = solve_amplitude(shape, fixed, RA, RB, FbA, FbB, noise, target)
        if p is not None:
            break
        note += 'attempt %d: target %.2f unreachable with these records (max %.2f at cap); records redrawn. ' % (
            attempt + 1, target, ratio)
    if shape == 'none':
        FtA, FtB = FbA, FbB
    else:
        if p is None and strength == 'strong':
            note += 'strong unreachable: made weak'
            strength = 'weak'
            target = trng.uniform(2.7, 3.8)
            p, ratio = solve_amplitude(shape, fixed, RA, RB, FbA, FbB, noise, target)
        if p is None:
            note += ' weak target unreachable either'
            p = SHAPES[shape][3]
        FtA = simulate(RA, shape, p, fixed); FtB = simulate(RB, shape, p, fixed)
        ratio = ratio_of(RA, RB, FtA, FtB, FbA, FbB, noise)
    outdir = os.path.join(ROOT, 'cases', tid)
    os.makedirs(outdir, exist_ok=True)
    recinfo = {}
    for lab, R, Ft in (('A', RA, FtA), ('B', RB, FtB)):
        Frec = [R['F0']] + [quantF(Ft[i] + R['noise'][i]) for i in range(1, len(Ft))]
        write_record(os.path.join(outdir, lab + '.json'), src, R, Frec, random.Random(R['aux_seed']), actmodel)
        info = dict(R['info'])
        info['noise_seed'] = R['noise_seed']; info['aux_seed'] = R['aux_seed']
        info['F0_kip'] = R['F0']
        first = None
        for i in range(len(R['x1'])):
            if abs(R['x1'][i] - R['x1'][0]) > 0.002 or abs(R['x2'][i] - R['x2'][0]) > 0.002:
                first = round(i * DT, 4); break
        info['first_actuator_motion_s'] = first
        recinfo[lab] = info
    cat, pname = (SHAPES[shape][0], SHAPES[shape][1]) if shape != 'none' else ('none', None)
    params = {} if shape == 'none' else dict(fixed, **{pname: p})
    entry = {'category': cat, 'shape': shape, 'shape_desc': SHAPES[shape][5] if shape != 'none' else 'base model + noise',
             'strength': strength if shape != 'none' else 'none', 'target_ratio': round(target, 4),
             'ratio': round(ratio, 4), 'params': params, 'noise_kip': noise, 'records': recinfo}
    if note:
        entry['note'] = note
    return tid, entry


def main():
    rng = random.Random(MASTER_SEED)
    # strengths: per category 1 or 2 strong, 12 strong in all
    cats2 = CATS[:]
    rng.shuffle(cats2)
    two_strong = set(cats2[:4])
    slots = []
    for cat in CATS:
        shs = [s for s in SHAPES if SHAPES[s][0] == cat]
        k = 2 if cat in two_strong else 1
        st = ['strong'] * k + ['weak'] * (3 - k)
        rng.shuffle(st)
        slots += list(zip(shs, st))
    slots += [('none', 'none')] * 6
    rng.shuffle(slots)
    # early actuator motion in 20 of the 60 records
    flags = [True] * 20 + [False] * 40
    rng.shuffle(flags)
    tids = ['t%02d' % (k + 1) for k in range(30)]
    # trials whose effect needs actuator motion: early flag does not matter (motion in both anyway)
    src_act = load_sources()
    jobs = [(tid, slots[k], (flags[2 * k], flags[2 * k + 1]), src_act) for k, tid in enumerate(tids)]
    procs = int(os.environ.get('GEN_PROCS', '2'))
    if procs > 1:
        import multiprocessing as mp
        with mp.get_context('fork').Pool(procs) as pool:
            res = pool.map(make_trial, jobs, chunksize=1)
    else:
        res = [make_trial(j) for j in jobs]
    key = {tid: e for tid, e in res}
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)
    with open(os.path.join(HERE, 'actuator_force_model.json'), 'w') as fh:
        json.dump(src_act[1], fh, indent=1)
    for tid in tids:
        e = key[tid]
        print(tid, e['category'], e['shape'], e['strength'], e['ratio'], e.get('note', ''))


if __name__ == '__main__':
    main()
