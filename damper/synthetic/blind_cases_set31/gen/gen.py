#!/usr/bin/env python3
"""blind31 -- blind test set for the friction-damper "model discrepancy" diagnosis.

Python 3 standard library only.  Master seed 31031.  Writes
    ../cases/tNN/{A.json,B.json}   synthetic "measured" semi-active records
    ../key.json                    the answer key
Usage:  python3 gen.py [--jobs N] [--only t01,t02] [--show]
        --jobs N   worker processes (default 2; the output does not depend on it)
        --only     regenerate only these trials (key.json is then left as it is)
        --show     print the answer key summary (default: only timings)
        GEN_DEBUG=1 reports motion re-draws; GEN_DUMP=DIR writes base/true force traces to DIR

Every record = (base model of configs/brfd-semiactive.yaml, replicated exactly, with ONE hidden
effect of our own shape) + white Gaussian noise, quantised like the measured force.
See ../NOTES.md for the model, the shapes and their literature sources.
"""
import json, math, os, random, struct, sys, time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
TEMPLATE_DIR = '/work/shared/data/brfd/semiactive'
TEMPLATES = ['harmonic0.015forward', 'harmonic0.015backward', 'harmonic0.03ea1forward',
             'harmonic0.03ea1backward', 'harmonic0.03ea2forward', 'harmonic0.03ea2backward']
MASTER_SEED = 31031

DT = 1.0 / 1024.0
# ---------------------------------------------------------------- base model parameters
# (configs/brfd-semiactive.yaml, used by `hybridsim damper predict --no-fit`)
S0, S1, S2 = 15.36, 0.0, 0.500
FS_F, FS_B, FC_F, FC_B, VS = 7.116, 3.760, 2.648, 1.253, 1.300
M = [-0.14, -0.15, -15.29, -13.00, -16.66, -15.77, -0.13, -0.15]
C = [119.68, 2.10, 1.94, 123.31]
FC_FLOOR = 0.05
# Eq. (4): Fc = b + L1*(x1 - x1') + L2*(x2 - x2')   (kip/in, per direction)
L1F = C[0] * M[0] + C[1] * M[2]
L2F = C[0] * M[1] + C[1] * M[3]
L1B = C[2] * M[4] + C[3] * M[6]
L2B = C[2] * M[5] + C[3] * M[7]

# ---------------------------------------------------------------- measured-file quantisation
QF = 0.000800879964           # friction force LSB (kip), grid k*QF
QX = 5.89421674706e-05        # drum displacement LSB (in), grid (k + 0.6631)*QX
QX_OFF = 0.6631
QA = 1.0 / 409600.0           # actuator position LSB (in), stored as float32
QT1, QT1_OFF = 0.31793998, 0.0521   # actuator 1 load cell (lb)
QT2, QT2_OFF = 0.39989996, 0.3294   # actuator 2 load cell (lb)
VCOL_RATIO = 125.38           # velocity column quirk: d(disp)/dt / 125.4
VCOL_NOISE = 3.7e-4
X_NOISE = 0.95 * QX           # displacement sensor noise before quantisation

HEADER = [('dt', 0.0009765625), ('sampling freq', 1024), ('displacement units', 'in'),
          ('time units', 's'), ('friction force units', 'kip'), ('actuator force units', 'lb')]


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def qforce(y):
    return round(y / QF) * QF


def movavg(a, h):
    n = len(a)
    p = [0.0]
    for x in a:
        p.append(p[-1] + x)
    out = []
    for i in range(n):
        lo = max(0, i - h)
        hi = min(n, i + h + 1)
        out.append((p[hi] - p[lo]) / (hi - lo))
    return out


def interp(arr, t):
    """linear interpolation of a 1024-Hz array at fractional sample index t"""
    if t <= 0:
        return arr[0]
    n = len(arr)
    if t >= n - 1:
        return arr[-1]
    i = int(t)
    f = t - i
    return arr[i] + (arr[i + 1] - arr[i]) * f


# ================================================================ black-box replica
def bb_velocity(x):
    """`damper predict`: central differences (one-sided at the ends) + 15-sample centred
    moving average clipped to the record."""
    n = len(x)
    v0 = [0.0] * n
    v0[0] = (x[1] - x[0]) / DT
    v0[-1] = (x[-1] - x[-2]) / DT
    for i in range(1, n - 1):
        v0[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    return movavg(v0, 7)


def lin_sim(cs, as_, w0):
    """w' = c_i - a_i*w with the inputs held at sample i over the step from i-1 to i, solved
    exactly (exponential step).  This is what `damper predict` does: it matches the black box
    to the 8 digits of its CSV, also where the Fc floor makes the step stiff (a*dt ~ 1.4),
    where an RK4 step would differ by ~2e-3 kip."""
    n = len(cs)
    w = w0
    out = [0.0] * n
    out[0] = w0
    h = DT
    ex = math.exp
    for i in range(1, n):
        a = as_[i]
        if a == 0.0:
            w = w + h * cs[i]
        else:
            ws = cs[i] / a
            w = ws + (w - ws) * ex(-a * h)
        out[i] = w
    return out


class Rec:
    """kinematics of one record + everything precomputed for the models"""

    def __init__(self, x, a1, a2):
        self.n = len(x)
        self.x = x
        self.a1 = a1
        self.a2 = a2
        self.a1p = a1[0]
        self.a2p = a2[0]
        v = bb_velocity(x)
        self.v = v
        self.av = [abs(q) for q in v]
        self.sg = [1.0 if q >= 0 else -1.0 for q in v]
        self.fs = [FS_F if q >= 0 else FS_B for q in v]
        self.b = [FC_F if q >= 0 else FC_B for q in v]
        # actuator retraction u = -(x - x'), Eq. (4) sensitivities S = -L > 0
        self.u1 = [-(p - self.a1p) for p in a1]
        self.u2 = [-(p - self.a2p) for p in a2]
        self.S1 = [-L1F if q >= 0 else -L1B for q in v]
        self.S2 = [-L2F if q >= 0 else -L2B for q in v]
        self.fc = [self.fc_of(i, self.u1[i], self.u2[i]) for i in range(self.n)]
        self.ex = [math.exp(-(q / VS) ** 2) for q in v]
        self.g = [self.fc[i] + (self.fs[i] - self.fc[i]) * self.ex[i] for i in range(self.n)]
        self.c0 = [S0 * q for q in v]
        self.a0 = [S0 * self.av[i] / self.g[i] for i in range(self.n)]
        self.s2v = [S2 * q for q in v]
        # rest weight and rest clock (for residual_static shapes)
        self.rw = [math.exp(-(q / 0.04) ** 2) for q in v]
        tr = [0.0] * self.n
        for i in range(1, self.n):
            tr[i] = tr[i - 1] + DT * self.rw[i] if self.rw[i] > 0.5 else 0.0
        self.tr = tr
        # travel since the last reversal (hysteresis 0.003 in on the recorded displacement)
        h = 0.003
        d = 0
        ext = x[0]
        xt = x[0]
        s = [0.0] * self.n
        rev = [False] * self.n
        for i in range(self.n):
            xi = x[i]
            if d == 0:
                if abs(xi - x[0]) > h:
                    d = 1 if xi > x[0] else -1
                    ext = xi
            elif d == 1:
                if xi > ext:
                    ext = xi
                elif xi < ext - h:
                    d = -1
                    xt = ext
                    ext = xi
                    rev[i] = True
            else:
                if xi < ext:
                    ext = xi
                elif xi > ext + h:
                    d = 1
                    xt = ext
                    ext = xi
                    rev[i] = True
            s[i] = abs(xi - xt)
        self.s = s
        self.rev = rev

    def fc_of(self, i, u1, u2):
        f = self.b[i] + self.S1[i] * u1 + self.S2[i] * u2
        return f if f > FC_FLOOR else FC_FLOOR

    def base(self, w0):
        w = lin_sim(self.c0, self.a0, w0)
        return [w[i] + self.s2v[i] for i in range(self.n)]


# ================================================================ templates and motions
class Templates:
    def __init__(self):
        self.x = []        # smoothed drum displacement per template
        self.tps = []      # turning points (sample indices)
        self.events = []   # actuator motion events
        for name in TEMPLATES:
            d = json.load(open(os.path.join(TEMPLATE_DIR, name + '.json')))['data']
            x = movavg(movavg([r[1] for r in d], 12), 12)
            a1 = movavg([r[4] - d[0][4] for r in d], 10)
            a2 = movavg([r[5] - d[0][5] for r in d], 10)
            tps = self.turning_points(x)
            k = len(self.x)
            self.x.append(x)
            self.tps.append(tps)
            # actuator events: |dev| > 0.0015 in, intervals closer than 0.3 s merged, padded
            # 0.1 s, the end values ramped out so that every event starts and ends at zero
            n = len(d)
            act = [abs(a1[i]) > 0.0015 or abs(a2[i]) > 0.0015 for i in range(n)]
            iv = []
            i = 0
            while i < n:
                if act[i]:
                    j = i
                    while j < n and act[j]:
                        j += 1
                    if iv and i - iv[-1][1] < 300:
                        iv[-1][1] = j
                    else:
                        iv.append([i, j])
                    i = j
                else:
                    i += 1
            for (i, j) in iv:
                lo = max(0, i - 102)
                hi = min(n, j + 102)
                if hi - lo < 500:
                    continue
                tp = max([t for t in tps if t <= i + 60] or [0])
                m = hi - lo - 1
                e1 = [a1[lo + q] - (a1[lo] + (a1[hi - 1] - a1[lo]) * q / m) for q in range(m + 1)]
                e2 = [a2[lo + q] - (a2[lo] + (a2[hi - 1] - a2[lo]) * q / m) for q in range(m + 1)]
                self.events.append({'tmpl': k, 'off': lo - tp, 'a1': e1, 'a2': e2,
                                    'hc_len': self.next_tp(tps, tp) - tp})

    @staticmethod
    def next_tp(tps, tp):
        for t in tps:
            if t > tp:
                return t
        return tp + 1024

    @staticmethod
    def turning_points(x, h=0.02):
        tps = []
        d = 0
        ext = x[0]
        ei = 0
        for i, xx in enumerate(x):
            if d >= 0 and xx > ext:
                ext, ei = xx, i
            if d <= 0 and xx < ext:
                ext, ei = xx, i
            if d == 1 and xx < ext - h:
                tps.append(ei)
                d = -1
                ext, ei = xx, i
            elif d == -1 and xx > ext + h:
                tps.append(ei)
                d = 1
                ext, ei = xx, i
            elif d == 0 and abs(xx - x[0]) > h:
                d = 1 if xx > x[0] else -1
                ext, ei = xx, i
        return tps


def build_motion(T, rng):
    """Drum displacement and actuator deviations (noise-free, 1024 Hz) re-cut from the
    measured semi-active tests: strokes (runs of half-cycles between turning points) scaled,
    time-stretched, mirrored and joined by rests; actuator events of the measured tests
    re-scaled, swapped or inverted and attached to some half-cycles."""
    dur = rng.uniform(9.0, 25.0)
    nmax = int(dur * 1024)
    x = []
    hcs = []     # (start index, length) of half-cycles in the new record
    pos = rng.uniform(-0.3, 0.3)
    x += [pos] * int(rng.uniform(0.3, 1.2) * 1024)
    final_rest = int(rng.uniform(0.5, 1.8) * 1024)
    # the electric actuators move in most (not all) records, during some of the half-cycles
    p_act = rng.uniform(0.4, 0.9) if rng.random() < 0.75 else 0.0
    misses = 0
    while misses < 40:
        room = nmax - final_rest - len(x)      # samples left for strokes and rests
        if room < 600:
            break
        k = rng.randrange(len(T.x))
        tps = T.tps[k]
        nh = rng.choice([1, 1, 2, 2, 3, 3, 4, 5, 6])
        j = rng.randrange(0, len(tps) - nh)
        seg = T.x[k][tps[j]:tps[j + nh] + 1]
        hc_bounds = [tps[j + q] - tps[j] for q in range(nh + 1)]
        y0 = seg[0]
        ys = [q - y0 for q in seg]
        ymax, ymin = max(ys), min(ys)
        span = max(abs(ymax), abs(ymin), 1e-6)
        s = rng.uniform(0.3, 1.25)
        # direction: mostly the one that keeps the stroke centred on the drum's mid position
        mid = 0.5 * (ymax + ymin)
        if abs(pos - s * mid) < abs(pos + s * mid):
            s = -s
        if rng.random() < 0.25:
            s = -s
        # keep |x| <= 1.3 : mirror or shrink
        def fits(sc):
            lo = pos + min(sc * ymax, sc * ymin)
            hi = pos + max(sc * ymax, sc * ymin)
            return lo >= -1.3 and hi <= 1.3
        if not fits(s):
            s = -s
        if not fits(s):
            lim = min((1.3 - pos) / span, (pos + 1.3) / span)
            s = math.copysign(min(abs(s), 0.98 * lim), s)
            if not fits(s):
                s = -s
        if abs(s) * span < 0.08:
            misses += 1
            continue
        vpk = max(abs(seg[i + 1] - seg[i - 1]) * 512 for i in range(1, len(seg) - 1))
        lam = rng.uniform(0.6, 2.2)            # time stretch factor (>1 slower)
        lam = max(lam, abs(s) * vpk / 4.8)     # peak drum speed <= 4.8 in/s
        lam = min(lam, 3.0)
        if abs(s) * vpk / lam > 4.8:
            misses += 1
            continue
        nnew = int((len(seg) - 1) * lam) + 1
        if nnew > room:
            misses += 1          # too long for what is left: draw another (shorter) stroke
            continue
        rest = int(rng.uniform(0.3, 2.0) * 1024)
        st = len(x)
        for i in range(nnew):
            x.append(pos + s * interp(ys, i / lam))
        for q in range(nh):
            hcs.append((st + int(hc_bounds[q] * lam), int((hc_bounds[q + 1] - hc_bounds[q]) * lam)))
        pos = x[-1]
        room = nmax - final_rest - len(x)
        if room < rest + 600:
            break
        x += [pos] * rest
    x += [pos] * final_rest
    while len(x) < 9 * 1024 + 10:
        x.append(pos)
    n = len(x)
    d1 = [0.0] * n
    d2 = [0.0] * n
    # actuator events on some half-cycles (none during the first 2.2 s, as in the tests)
    elig = [h for h in hcs if h[0] > 2.2 * 1024 and h[1] > 300]
    chosen = [h for h in elig if rng.random() < p_act]
    if p_act > 0 and not chosen and elig:
        chosen = [rng.choice(elig)]
    nev = 0
    busy_until = -1
    for (st, ln) in chosen:
        ev = rng.choice(T.events)
        lam = ln / float(ev['hc_len'])
        amp = rng.uniform(0.012, 0.06)      # largest actuator excursion of the event (in)
        sgn = -1.0 if rng.random() < 0.3 else 1.0
        e1, e2 = ev['a1'], ev['a2']
        if rng.random() < 0.3:
            e1, e2 = e2, e1
        mx = max(max(abs(q) for q in e1), max(abs(q) for q in e2))
        rho = amp / mx
        # actuator speed <= 0.45 in/s
        vmx = max(max(abs(e1[i + 1] - e1[i]) for i in range(len(e1) - 1)),
                  max(abs(e2[i + 1] - e2[i]) for i in range(len(e2) - 1))) * 1024
        lam = max(lam, rho * vmx / 0.45)
        i0 = st + int(ev['off'] * lam)
        m = int((len(e1) - 1) * lam) + 1
        if i0 <= busy_until or i0 + m >= n - 200:
            continue
        busy_until = i0 + m
        for i in range(m):
            t = i / lam
            d1[i0 + i] += sgn * rho * interp(e1, t)
            d2[i0 + i] += sgn * rho * interp(e2, t)
        nev += 1
    return x, d1, d2, nev


def realise(xs, d1, d2, rng):
    """Sensor noise + quantisation of the kinematic columns."""
    n = len(xs)
    x = [(round(q / QX + rng.gauss(0.0, X_NOISE / QX) - QX_OFF) + QX_OFF) * QX for q in xs]
    a1p = f32(round(0.655 * 409600 + rng.choice([-1, 0, 0, 1])) * QA)
    a2p = f32(round(0.8559 * 409600 + rng.choice([-1, 0, 0, 1])) * QA)
    # the measured actuator positions are sample-and-hold at ~100 Hz (updates every 10 or,
    # now and then, 20 samples): reproduce that staircase
    hold = []
    i = 0
    while i < n:
        hold.append(i)
        i += 20 if rng.random() < 0.08 else 10
    a1 = [0.0] * n
    a2 = [0.0] * n
    for k, i0 in enumerate(hold):
        i1 = hold[k + 1] if k + 1 < len(hold) else n
        p1 = f32((round((a1p + d1[i0]) / QA + rng.gauss(0.0, 0.25))) * QA)
        p2 = f32((round((a2p + d2[i0]) / QA + rng.gauss(0.0, 0.25))) * QA)
        for i in range(i0, i1):
            a1[i] = p1
            a2[i] = p2
    a1[0] = a1p
    a2[0] = a2p
    vtrue = [0.0] * n
    for i in range(1, n - 1):
        vtrue[i] = (xs[i + 1] - xs[i - 1]) / (2 * DT)
    vcol = [f32(q / VCOL_RATIO + rng.gauss(0.0, VCOL_NOISE)) for q in vtrue]
    return x, a1, a2, vcol


# ================================================================ hidden effects
# Each shape: simulate(R, w0, theta, P) -> friction force list (kip).  theta is the amplitude
# solved for the strength target (theta = 0 gives the base model); P holds the fixed shape
# parameters drawn per trial.  All shapes use the same drum velocity (the black box's
# derivation from the recorded displacement), the same initial held force w0 and the same
# RK4 step (inputs held at sample i, state advanced from i-1 to i) as the base model.

def rk4_general(R, w0, fz, out_of, z0):
    """generic scalar ODE z' = fz(z, i), inputs held at sample i over the step from i-1 to i,
    RK4 with sub-steps so that (base stiffness)*h <= 0.2 (then it agrees with the exact step of
    the base model to < 1e-6 kip when the effect amplitude is zero); F_i = out_of(z, i)"""
    n = R.n
    z = z0
    F = [0.0] * n
    F[0] = out_of(z, 0)
    a0 = R.a0
    for i in range(1, n):
        ns = 1 + int(a0[i] * DT / 0.2)
        h = DT / ns
        for _ in range(ns):
            k1 = fz(z, i)
            k2 = fz(z + 0.5 * h * k1, i)
            k3 = fz(z + 0.5 * h * k2, i)
            k4 = fz(z + h * k3, i)
            z = z + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = out_of(z, i)
    return F


def g_from_fc(R, fc):
    return [fc[i] + (R.fs[i] - fc[i]) * R.ex[i] for i in range(R.n)]


def out_w(R, w):
    return [w[i] + R.s2v[i] for i in range(R.n)]


def lin_with_g(R, g, w0):
    a = [S0 * R.av[i] / g[i] for i in range(R.n)]
    return out_w(R, lin_sim(R.c0, a, w0))


# ---------------- backlash
def dz(z, d):
    if z > d:
        return z - d
    if z < -d:
        return z + d
    return 0.0


def engage(z, d):
    """viscous part of the friction engaged only with the band: 0 inside the inner 80 % of the
    gap, ramping to 1 at the gap edge (continuous; identically 1 for d = 0)."""
    if d <= 0.0:
        return 1.0
    e = (abs(z) - 0.8 * d) / (0.2 * d)
    return 0.0 if e <= 0.0 else (1.0 if e >= 1.0 else e)


def sim_bk_deadzone(R, w0, th, P):
    d = th
    v, av, g = R.v, R.av, R.g
    def fz(z, i):
        return v[i] - av[i] * S0 * dz(z, d) / g[i]
    def out(z, i):
        return S0 * dz(z, d) + R.s2v[i] * engage(z, d)
    z0 = w0 / S0 + (math.copysign(d, w0) if w0 != 0 else 0.0)
    return rk4_general(R, w0, fz, out, z0)


def hertz_el(z, l):
    az = abs(z)
    return math.copysign(S0 * az * math.sqrt(az / (az + l)), z) if az > 0 else 0.0


def sim_bk_hertz(R, w0, th, P):
    l = th
    v, av, g = R.v, R.av, R.g
    if l <= 0:
        return R.base(w0)
    def fz(z, i):
        return v[i] - av[i] * hertz_el(z, l) / g[i]
    def out(z, i):
        az = abs(z)
        return hertz_el(z, l) + R.s2v[i] * math.sqrt(az / (az + l))
    # invert F_el(z0) = w0 (monotone) by bisection
    tgt = abs(w0)
    lo, hi = 0.0, tgt / S0 + l + 1.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if abs(hertz_el(mid, l)) < tgt:
            lo = mid
        else:
            hi = mid
    z0 = math.copysign(0.5 * (lo + hi), w0)
    return rk4_general(R, w0, fz, out, z0)


def sim_bk_loadslack(R, w0, th, P):
    kap = th
    dmax = P['gap_max_in']
    v, av, g, rev, s2v = R.v, R.av, R.g, R.rev, R.s2v
    n = R.n
    h = DT
    d = min(kap * abs(w0), dmax)
    z = w0 / S0 + (math.copysign(d, w0) if w0 != 0 else 0.0)
    F = [0.0] * n
    F[0] = w0 + s2v[0]
    for i in range(1, n):
        if rev[i]:
            fel = S0 * dz(z, d)
            dn = min(kap * abs(fel), dmax)
            if fel != 0.0:
                z = math.copysign(abs(fel) / S0 + dn, fel)
            else:
                z = max(-dn, min(dn, z))
            d = dn
        vi, ai, gi = v[i], av[i], g[i]
        ns = 1 + int(R.a0[i] * DT / 0.2)
        h = DT / ns
        for _ in range(ns):
            k1 = vi - ai * S0 * dz(z, d) / gi
            k2 = vi - ai * S0 * dz(z + 0.5 * h * k1, d) / gi
            k3 = vi - ai * S0 * dz(z + 0.5 * h * k2, d) / gi
            k4 = vi - ai * S0 * dz(z + h * k3, d) / gi
            z = z + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        F[i] = S0 * dz(z, d) + s2v[i] * engage(z, d)
    return F


# ---------------- residual_static (rest-weighted terms, applied after each LuGre step)
def _lin_step(w, c, a):
    """one exact step of w' = c - a*w (the base model's step, see lin_sim)"""
    if a == 0.0:
        return w + DT * c
    ws = c / a
    return ws + (w - ws) * math.exp(-a * DT)


def sim_rs_log(R, w0, th, P):
    A, tc = th, P['t_c_s']
    n = R.n
    w = w0
    F = [0.0] * n
    F[0] = w0 + R.s2v[0]
    c0, a0, rw, tr = R.c0, R.a0, R.rw, R.tr
    for i in range(1, n):
        w = _lin_step(w, c0[i], a0[i])
        if tr[i] > 0.0:
            w -= DT * rw[i] * A / (tc + tr[i]) * math.tanh(w / 0.05)
        F[i] = w + R.s2v[i]
    return F


def sim_rs_kww(R, w0, th, P):
    a, tau, beta = th, P['tau_s'], P['beta']
    n = R.n
    w = w0
    F = [0.0] * n
    F[0] = w0 + R.s2v[0]
    c0, a0, tr = R.c0, R.a0, R.tr
    fh = w0
    phi_prev = 0.0
    for i in range(1, n):
        w = _lin_step(w, c0[i], a0[i])
        if tr[i] > 0.0:
            if tr[i - 1] == 0.0:
                fh = w
                phi_prev = 0.0
            phi = 1.0 - math.exp(-(tr[i] / tau) ** beta)
            w -= a * fh * (phi - phi_prev)
            phi_prev = phi
        F[i] = w + R.s2v[i]
    return F


def sim_rs_equil(R, w0, th, P):
    k, feq = th, P['f_eq_kip']
    n = R.n
    w = w0
    F = [0.0] * n
    F[0] = w0 + R.s2v[0]
    c0, a0, rw = R.c0, R.a0, R.rw
    for i in range(1, n):
        w = _lin_step(w, c0[i], a0[i])
        w = feq + (w - feq) * math.exp(-k * rw[i] * DT)
        F[i] = w + R.s2v[i]
    return F


# ---------------- transition_shape (sliding level g unchanged)
def sim_ts_dahl(R, w0, th, P):
    ex = 1.0 + th
    v, sg, g = R.v, R.sg, R.g
    def fz(w, i):
        u = 1.0 - w * sg[i] / g[i]
        return S0 * v[i] * math.copysign(abs(u) ** ex, u)
    def out(w, i):
        return w + R.s2v[i]
    return rk4_general(R, w0, fz, out, w0)


def sim_ts_gms(R, w0, th, P):
    N = 4
    e = [-1.5, -0.5, 0.5, 1.5]
    al = [math.exp(th * q) for q in e]
    sa = sum(al)
    al = [q / sa for q in al]
    kap = 1.0 / N
    tot = [0.0] * R.n
    for j in range(N):
        cs = [kap * c for c in R.c0]
        as_ = [kap * S0 * R.av[i] / (al[j] * R.g[i]) for i in range(R.n)]
        wj = lin_sim(cs, as_, al[j] * w0)
        for i in range(R.n):
            tot[i] += wj[i]
    return out_w(R, tot)


def sim_ts_bliman(R, w0, th, P):
    l2 = P['l2_in']
    n = R.n
    c1 = [R.v[i] * (S0 + th * R.g[i] / l2) for i in range(n)]
    a1 = [R.av[i] * (S0 + th * R.g[i] / l2) / ((1.0 + th) * R.g[i]) for i in range(n)]
    c2 = [-th * R.g[i] * R.v[i] / l2 for i in range(n)]
    a2 = [R.av[i] / l2 for i in range(n)]
    x1 = lin_sim(c1, a1, (1.0 + th) * w0)
    x2 = lin_sim(c2, a2, -th * w0)
    return [x1[i] + x2[i] + R.s2v[i] for i in range(n)]


# ---------------- velocity (kinetic level Fc -> Fc * phi(|v|), static level unchanged)
def _vel_g(R, phi):
    return [R.fc[i] * phi[i] + (R.fs[i] - R.fc[i] * phi[i]) * R.ex[i] for i in range(R.n)]


def sim_v_ratestate(R, w0, th, P):
    vst = P['v_star_in_s']
    phi = [1.0 + th * math.log(1.0 + q / vst) for q in R.av]
    return lin_with_g(R, _vel_g(R, phi), w0)


def sim_v_grosch(R, w0, th, P):
    vp, wd = P['v_peak_in_s'], P['width_decades']
    phi = [1.0 + th * math.exp(-(math.log10(max(q, 1e-6) / vp)) ** 2 / (2 * wd * wd)) for q in R.av]
    return lin_with_g(R, _vel_g(R, phi), w0)


def sim_v_weakening(R, w0, th, P):
    vw = P['v_w_in_s']
    phi = [1.0 - th * (q / vw) / (1.0 + q / vw) for q in R.av]
    return lin_with_g(R, _vel_g(R, phi), w0)


# ---------------- actuator_lag (effective actuator positions feed Eq. 4)
def _fc_eff(R, e1, e2):
    return [R.fc_of(i, -(e1[i] - R.a1p), -(e2[i] - R.a2p)) for i in range(R.n)]


def _act_sim(R, e1, e2, w0):
    return lin_with_g(R, g_from_fc(R, _fc_eff(R, e1, e2)), w0)


def lag2(a, tn, zeta):
    """second-order lag y'' + 2 zeta wn y' + wn^2 (y - u) = 0, u held at sample i over the step,
    exact (unconditionally stable) step of the underdamped solution."""
    if tn <= 0:
        return list(a)
    wn = 1.0 / tn
    wd = wn * math.sqrt(1.0 - zeta * zeta)
    sw = zeta * wn
    ed = math.exp(-sw * DT)
    cs, sn = math.cos(wd * DT), math.sin(wd * DT)
    y = a[0]
    yd = 0.0
    out = [y]
    for i in range(1, len(a)):
        e0 = y - a[i]
        b = (yd + sw * e0) / wd
        e1 = ed * (e0 * cs + b * sn)
        yd = ed * ((-sw) * (e0 * cs + b * sn) + (-e0 * wd * sn + b * wd * cs))
        y = a[i] + e1
        out.append(y)
    return out


def sim_al_2nd(R, w0, th, P):
    z = P['zeta']
    return _act_sim(R, lag2(R.a1, th, z), lag2(R.a2, th, z), w0)


def ratelim(a, r):
    y = a[0]
    out = [y]
    step = r * DT
    for i in range(1, len(a)):
        dlt = a[i] - y
        if dlt > step:
            dlt = step
        elif dlt < -step:
            dlt = -step
        y += dlt
        out.append(y)
    return out


def sim_al_rate(R, w0, th, P):
    if th <= 0:
        return R.base(w0)
    r = 1.0 / th
    return _act_sim(R, ratelim(R.a1, r), ratelim(R.a2, r), w0)


def zener(a, rho, tau):
    k = math.exp(-DT / tau)
    lp = a[0]
    out = [a[0]]
    for i in range(1, len(a)):
        lp = a[i] + (lp - a[i]) * k
        out.append((1.0 - rho) * a[i] + rho * lp)
    return out


def sim_al_zener(R, w0, th, P):
    tau = P['tau_s']
    return _act_sim(R, zener(R.a1, th, tau), zener(R.a2, th, tau), w0)


# ---------------- self_energizing
def sim_se_capstan(R, w0, th, P):
    g = [R.g[i] * math.exp(th * R.x[i] * R.sg[i]) for i in range(R.n)]
    return lin_with_g(R, g, w0)


def sim_se_servo(R, w0, th, P):
    tf = P['tau_f_s']
    kf = math.exp(-DT / tf)
    n = R.n
    w = w0
    ff = w0
    F = [0.0] * n
    F[0] = w0 + R.s2v[0]
    fc, fs, ex, sg, av, c0, s2v = R.fc, R.fs, R.ex, R.sg, R.av, R.c0, R.s2v
    for i in range(1, n):
        fb = ff * sg[i]
        fci = fc[i] + th * (fb if fb > 0 else 0.0)
        gi = fci + (fs[i] - fci) * ex[i]
        w = _lin_step(w, c0[i], S0 * av[i] / gi)
        F[i] = w + s2v[i]
        ff = F[i] + (ff - F[i]) * kf
    return F


def sim_se_windup(R, w0, th, P):
    lam = P['lambda_in']
    g = [R.g[i] * (1.0 + th * (1.0 - math.exp(-R.s[i] / lam))) for i in range(R.n)]
    return lin_with_g(R, g, w0)


# ---------------- pretension (clamping law of Eq. 4 replaced; u = actuator retraction)


def _pt_sim(R, hfun, w0):
    fc = []
    for i in range(R.n):
        f = R.b[i] + R.S1[i] * hfun(R.u1[i]) + R.S2[i] * hfun(R.u2[i])
        fc.append(f if f > FC_FLOOR else FC_FLOOR)
    return lin_with_g(R, g_from_fc(R, fc), w0)


def sim_pt_cubic(R, w0, th, P):
    ur = P['u_ref_in']
    return _pt_sim(R, lambda u: u * (1.0 + th * (u / ur) ** 2), w0)


def sim_pt_fung(R, w0, th, P):
    if th < 1e-9:
        return R.base(w0)
    ur = P['u_ref_in']
    return _pt_sim(R, lambda u: (math.exp(th * u / ur) - 1.0) * ur / th, w0)


def sim_pt_tanh(R, w0, th, P):
    if th < 1e-9:
        return R.base(w0)
    us = P['u_ref_in'] / th
    return _pt_sim(R, lambda u: us * math.tanh(u / us), w0)


# ---------------- asymmetry (direction d* = +1 forward, -1 backward)
def _mult(th, P):
    return (1.0 + th) if P['sense'] > 0 else 1.0 / (1.0 + th)


def sim_as_viscous(R, w0, th, P):
    m = _mult(th, P)
    d = P['direction']
    w = lin_sim(R.c0, R.a0, w0)
    return [w[i] + S2 * R.v[i] * (m if R.sg[i] == d else 1.0) for i in range(R.n)]


def sim_as_stiffness(R, w0, th, P):
    m = _mult(th, P)
    d = P['direction']
    cs = [R.c0[i] * (m if R.sg[i] == d else 1.0) for i in range(R.n)]
    as_ = [R.a0[i] * (m if R.sg[i] == d else 1.0) for i in range(R.n)]
    return out_w(R, lin_sim(cs, as_, w0))


def sim_as_stribeck_exp(R, w0, th, P):
    d = P['direction']
    de = 2.0 / (1.0 + th)
    g = []
    for i in range(R.n):
        if R.sg[i] == d:
            e = math.exp(-(R.av[i] / VS) ** de)
            g.append(R.fc[i] + (R.fs[i] - R.fc[i]) * e)
        else:
            g.append(R.g[i])
    return lin_with_g(R, g, w0)


# ---------------- shape table: category, simulate, theta bound, fixed-parameter draw
def _dir(rng):
    return {'direction': rng.choice([1, -1]), 'sense': 1 if rng.random() < 0.7 else -1}


SHAPES = {
    'deadzone_play': ('backlash', sim_bk_deadzone, 0.15, 'half_gap_in', lambda r: {}),
    'hertzian_reengagement': ('backlash', sim_bk_hertz, 0.35, 'engagement_length_in', lambda r: {}),
    'load_dependent_slack': ('backlash', sim_bk_loadslack, 0.06, 'slack_per_kip_in',
                             lambda r: {'gap_max_in': 0.25}),
    'ratestate_log_relaxation': ('residual_static', sim_rs_log, 0.6, 'A_kip',
                                 lambda r: {'t_c_s': r.uniform(0.05, 0.3)}),
    'kww_stretched_relaxation': ('residual_static', sim_rs_kww, 0.85, 'relaxed_fraction',
                                 lambda r: {'tau_s': r.uniform(0.4, 1.5), 'beta': r.uniform(0.35, 0.6)}),
    'preload_equilibrium_settling': ('residual_static', sim_rs_equil, 3.0, 'rate_per_s',
                                     lambda r: {'f_eq_kip': r.uniform(-0.2, 0.6)}),
    'dahl_power_law': ('transition_shape', sim_ts_dahl, 3.0, 'exponent_minus_1', lambda r: {}),
    'maxwell_slip_iwan': ('transition_shape', sim_ts_gms, 1.5, 'log_spread', lambda r: {'elements': 4}),
    'bliman_sorine_overshoot': ('transition_shape', sim_ts_bliman, 2.5, 'overshoot_gain',
                                lambda r: {'l2_in': r.uniform(0.35, 0.7)}),
    'ratestate_log_strengthening': ('velocity', sim_v_ratestate, 0.35, 'a_minus_b',
                                    lambda r: {'v_star_in_s': r.uniform(0.05, 0.3)}),
    'grosch_loss_peak': ('velocity', sim_v_grosch, 1.2, 'peak_gain',
                         lambda r: {'v_peak_in_s': r.uniform(0.8, 2.5), 'width_decades': r.uniform(0.2, 0.4)}),
    'hyperbolic_weakening': ('velocity', sim_v_weakening, 0.75, 'weakening_fraction',
                             lambda r: {'v_w_in_s': r.uniform(0.5, 2.0)}),
    'band_second_order': ('actuator_lag', sim_al_2nd, 0.3, 'T_n_s', lambda r: {'zeta': r.uniform(0.25, 0.5)}),
    'slew_rate_limit': ('actuator_lag', sim_al_rate, 33.0, 'inverse_rate_s_per_in', lambda r: {}),
    'zener_partial_lag': ('actuator_lag', sim_al_zener, 1.0, 'delayed_fraction',
                          lambda r: {'tau_s': r.uniform(0.15, 0.8)}),
    'capstan_wrap_position': ('self_energizing', sim_se_capstan, 0.6, 'mu_theta_per_in', lambda r: {}),
    'servo_force_feedback': ('self_energizing', sim_se_servo, 0.7, 'loop_gain',
                             lambda r: {'tau_f_s': r.uniform(0.08, 0.35)}),
    'travel_windup': ('self_energizing', sim_se_windup, 0.8, 'windup_gain',
                      lambda r: {'lambda_in': r.uniform(0.25, 0.8)}),
    'cubic_hardening': ('pretension', sim_pt_cubic, 2.0, 'cubic_gain', lambda r: {}),
    'fung_exponential': ('pretension', sim_pt_fung, 2.5, 'exp_rate', lambda r: {}),
    'tanh_saturation': ('pretension', sim_pt_tanh, 4.0, 'u_ref_over_u_sat', lambda r: {}),
    'viscous_by_direction': ('asymmetry', sim_as_viscous, 4.0, 'factor_minus_1', _dir),
    'presliding_stiffness_by_direction': ('asymmetry', sim_as_stiffness, 4.0, 'factor_minus_1', _dir),
    'stribeck_exponent_by_direction': ('asymmetry', sim_as_stribeck_exp, 3.0, 'delta_ratio_minus_1',
                                       lambda r: {'direction': r.choice([1, -1])}),
}
CATEGORIES = ['backlash', 'residual_static', 'transition_shape', 'velocity', 'actuator_lag',
              'self_energizing', 'pretension', 'asymmetry']


# ================================================================ trials
_T = None


def templates():
    global _T
    if _T is None:
        _T = Templates()
    return _T


def tension_columns(F, rng):
    """actuator load cells (lb): the taut band end carries |F|/C (Table 2), the slack end a
    small residual; sensor noise and the measured quantisation."""
    t1, t2 = [], []
    for f in F:
        slack = 31.0 + 25.0 * math.exp(-(f / 0.5) ** 2) + 1.5 * abs(f)
        if f >= 0:
            a, b = slack, 30.0 + 1000.0 * f / C[1]
        else:
            a, b = 30.0 + 1000.0 * (-f) / C[2], slack
        a += rng.gauss(0.0, 0.5)
        b += rng.gauss(0.0, 0.5)
        t1.append((round(a / QT1 - QT1_OFF) + QT1_OFF) * QT1)
        t2.append((round(b / QT2 - QT2_OFF) + QT2_OFF) * QT2)
    return t1, t2


def noise_list(seed, sd, n):
    r = random.Random(seed)
    return [r.gauss(0.0, sd) for _ in range(n)]


def rms_diff(recs, Fs):
    ss = 0.0
    nn = 0
    for (R, w0, base, _), F in zip(recs, Fs):
        for a, b in zip(F, base):
            ss += (a - b) ** 2
        nn += R.n
    return math.sqrt(ss / nn)


def solve_theta(recs, sim, P, thmax, target, sd):
    def ratio(th):
        return rms_diff(recs, [sim(R, w0, th, P) for (R, w0, _, _) in recs]) / sd
    rmax = ratio(thmax)
    if rmax < target:
        return None, rmax, 1
    lo, rlo = 0.0, 0.0
    hi, rhi = thmax, rmax
    th = thmax * target / rmax
    nev = 1
    side = 0
    for it in range(40):
        r = ratio(th)
        nev += 1
        if abs(r / target - 1.0) < 0.001:
            return th, r, nev
        if r < target:
            lo, rlo = th, r
            if side == -1:
                rhi = target + (rhi - target) / 2.0
            side = -1
        else:
            hi, rhi = th, r
            if side == 1:
                rlo = target - (target - rlo) / 2.0
            side = 1
        th = lo + (hi - lo) * (target - rlo) / (rhi - rlo)
        if not (lo < th < hi):
            th = 0.5 * (lo + hi)
    return th, r, nev


def write_record(path, R, Frec, vcol, t1, t2):
    rows = []
    for i in range(R.n):
        t = i / 1024.0
        t = int(t) if t == int(t) else t
        rows.append([t, R.x[i], Frec[i], vcol[i], R.a1[i], R.a2[i], t1[i], t2[i]])
    obj = {'data': rows}
    for k, v in HEADER:
        obj[k] = v
    with open(path, 'w') as f:
        json.dump(obj, f)


def run_trial(spec):
    t0 = time.time()
    T = templates()
    rng = random.Random(spec['seed'])
    sd = spec['noise_kip']
    shape = spec['shape']
    for attempt in range(1, 13):
        recs = []
        meta = []
        for name in 'AB':
            xs, d1, d2, nev = build_motion(T, rng)
            x, a1, a2, vcol = realise(xs, d1, d2, rng)
            R = Rec(x, a1, a2)
            nseed = rng.randrange(1, 2 ** 31)
            f0 = rng.uniform(-0.9, 1.1)
            noise = noise_list(nseed, sd, R.n)
            w0 = qforce(f0 + noise[0])
            recs.append((R, w0, R.base(w0), (vcol, noise)))
            meta.append({'duration_s': round((R.n - 1) / 1024.0, 4), 'samples': R.n,
                         'noise_seed': nseed, 'f0_kip': f0, 'initial_force_kip': w0,
                         'actuator_events': nev})
        if shape == 'none':
            th, P, Fs, ratio, nev = None, {}, [r[2] for r in recs], 0.0, 0
            break
        cat, sim, thmax, thname, draw = SHAPES[shape]
        P = draw(rng)
        if cat == 'pretension':
            # nonlinearity normalised to the largest actuator travel of the trial
            ur = max(max(abs(q) for q in R.u1 + R.u2) for (R, _, _, _) in recs)
            P['u_ref_in'] = max(ur, 0.01)
        th, ratio, nev = solve_theta(recs, sim, P, thmax, spec['ratio_target'], sd)
        if th is None and os.environ.get('GEN_DEBUG'):
            sys.stderr.write('%s attempt %d: ratio at bound %.2f < %.2f  %s\n'
                             % (spec['tid'], attempt, ratio, spec['ratio_target'], meta))
        if th is not None:
            Fs = [sim(R, w0, th, P) for (R, w0, _, _) in recs]
            break
    else:
        raise RuntimeError('%s: target not reachable for %s' % (spec['tid'], shape))
    d = os.path.join(ROOT, 'cases', spec['tid'])
    os.makedirs(d, exist_ok=True)
    for name, (R, w0, base, (vcol, noise)), F in zip('AB', recs, Fs):
        Frec = [w0] + [qforce(F[i] + noise[i]) for i in range(1, R.n)]
        t1, t2 = tension_columns(F, rng)
        write_record(os.path.join(d, name + '.json'), R, Frec, vcol, t1, t2)
        if os.environ.get('GEN_DUMP'):
            with open(os.path.join(os.environ['GEN_DUMP'], '%s_%s.dat' % (spec['tid'], name)), 'w') as f:
                for i in range(R.n):
                    f.write('%.6f %.5f %.4f %.5f %.5f %.5f %.5f %.5f\n' % (i * DT, R.x[i], R.v[i], R.u1[i],
                            R.u2[i], base[i], F[i], Frec[i]))
    ent = {'category': spec['category'], 'shape': shape, 'strength': spec['strength'],
           'ratio': round(ratio, 4) if shape != 'none' else 0.0,
           'ratio_target': round(spec['ratio_target'], 4) if shape != 'none' else 0.0,
           'noise_kip': sd}
    params = {}
    if shape != 'none':
        params[thname] = th
        params.update(P)
        ent['amplitude_param'] = thname
        ent['amplitude_bounds'] = [0.0, thmax]
        ent['solver_evaluations'] = nev
    ent['params'] = params
    if shape != 'none':
        # share of the squared discrepancy that falls on samples at rest (|v| < 0.05 in/s)
        sr = st = 0.0
        for (R, w0, base, _), F in zip(recs, Fs):
            for i in range(R.n):
                q = (F[i] - base[i]) ** 2
                st += q
                if R.av[i] < 0.05:
                    sr += q
        ent['rest_share'] = round(sr / st, 3)
    ent['records'] = dict(zip('AB', meta))
    ent['motion_attempts'] = attempt
    ent['seed'] = spec['seed']
    return spec['tid'], dict(ent, gen_seconds=round(time.time() - t0, 1))


def plan():
    rng = random.Random(MASTER_SEED)
    by_cat = {c: [s for s in SHAPES if SHAPES[s][0] == c] for c in CATEGORIES}
    two_strong = set(rng.sample(CATEGORIES, 4))
    effects = []
    for c in CATEGORIES:
        shapes = list(by_cat[c])
        rng.shuffle(shapes)
        ns = 2 if c in two_strong else 1
        for k, s in enumerate(shapes):
            effects.append((c, s, 'strong' if k < ns else 'weak'))
    trials = effects + [('none', 'none', None)] * 6
    rng.shuffle(trials)
    specs = []
    for k, (c, s, st) in enumerate(trials):
        sd = rng.uniform(0.02, 0.06)
        if st == 'strong':
            tgt = rng.uniform(8.5, 11.5)
        elif st == 'weak':
            tgt = rng.uniform(2.7, 3.8)
        else:
            tgt = 0.0
        specs.append({'tid': 't%02d' % (k + 1), 'category': c, 'shape': s, 'strength': st,
                      'noise_kip': sd, 'ratio_target': tgt, 'seed': rng.randrange(1, 2 ** 31)})
    return specs


def main():
    jobs = 2
    only = None
    args = sys.argv[1:]
    if '--jobs' in args:
        jobs = int(args[args.index('--jobs') + 1])
    if '--only' in args:
        only = args[args.index('--only') + 1].split(',')
    t0 = time.time()
    specs = plan()
    if only:
        specs = [s for s in specs if s['tid'] in only]
    # heavy trials first for better load balance
    order = sorted(specs, key=lambda s: s['shape'] == 'none')
    if jobs > 1:
        import multiprocessing as mp
        with mp.Pool(jobs) as pool:
            res = pool.map(run_trial, order, chunksize=1)
    else:
        res = [run_trial(s) for s in order]
    key = {tid: {k: v for k, v in e.items() if k != 'gen_seconds'} for tid, e in sorted(res)}
    if not only:
        with open(os.path.join(ROOT, 'key.json'), 'w') as f:
            json.dump(key, f, indent=1)
    for tid, e in sorted(res):
        if '--show' in args:
            print(tid, e['category'], e['shape'], e['strength'], e['ratio'], 'att', e['motion_attempts'],
                  '%.1fs' % e['gen_seconds'])
        else:
            print(tid, 'written (%d motion draw(s), %.1f s)' % (e['motion_attempts'], e['gen_seconds']))
    print('gen.py done in %.1f s' % (time.time() - t0))


if __name__ == '__main__':
    main()
