#!/usr/bin/env python3
"""blind36 generator: 30 blind trials (A/B records) for the friction-damper discrepancy tool.

Python 3 standard library only.  Master seed 36036.  Writes ../cases/tNN/{A,B}.json and ../key.json.
Each record: drum motion and actuator motion re-cut / scaled / stretched / joined from the six
measured semi-active tests; "true" force = base model (black-box replica, model.py) + ONE hidden
effect (same parameters in A and B), or the base model alone ('none'); plus white Gaussian noise,
quantised like the measured force.  See ../NOTES.md.
"""
import array
import json
import math
import os
import random
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import model as M  # noqa: E402

ROOT = os.path.dirname(HERE)
CASES = os.path.join(ROOT, 'cases')
SRC_DIR = '/work/shared/data/brfd/semiactive'
SRC_FILES = [
    ('harmonic0.03ea1forward.json', 'one'), ('harmonic0.03ea1backward.json', 'one'),
    ('harmonic0.03ea2forward.json', 'two'), ('harmonic0.03ea2backward.json', 'two'),
    ('harmonic0.015forward.json', 'both'), ('harmonic0.015backward.json', 'both'),
]
MASTER_SEED = 36036
FS = M.FS
DT = M.DT

# recording grids, read off the measured files
Q_F = 0.0008008799341041595      # friction force step (kip)
Q_X = 5.89e-5                    # drum displacement step (in)
Q_A = 2.384185791015625e-06      # electric actuator position step (in)
Q_F1, OFF_F1 = 0.3179399769393441, 0.01655988344764836  # actuator-1 load cell step / offset (lb)
Q_F2, OFF_F2 = 0.3998999645618832, 0.13172664283200675  # actuator-2 load cell step / offset (lb)
VEL_COL_DIV = 125.4               # the files' velocity column is d(disp)/dt / ~125.4
X_MAX = 1.2                       # stroke end points within +-1.2 in (travel limit 1.3 in)

HEADER = [("dt", 0.0009765625), ("sampling freq", 1024), ("displacement units", "in"),
          ("time units", "s"), ("friction force units", "kip"), ("actuator force units", "lb")]


def f32list(xs):
    return array.array('f', xs).tolist()


# ----------------------------------------------------------------------------------------------
# material from the measured tests
# ----------------------------------------------------------------------------------------------
class Library:
    def __init__(self):
        self.half_cycles = []      # normalised drum strokes: list of phi(t) from 0 to 1
        self.rest_noise = []       # detrended drum displacement at rest (in)
        self.events = {'one': [], 'two': [], 'both': []}   # (d1, d2) actuator excursions (in)
        self.idle = []             # idle actuator deviations (in) [(d1, d2)]
        self.x_init = []           # measured initial actuator positions (x'_1, x'_2)
        self.table = None          # F (kip) -> (f1, f2) (lb), bin means, actuators idle
        rows_all = []
        for name, kind in SRC_FILES:
            d = json.load(open(os.path.join(SRC_DIR, name)))['data']
            self._extract(d, kind)
            rows_all.append(d)
        self._force_table(rows_all)

    def _extract(self, d, kind):
        n = len(d)
        x = [r[1] for r in d]
        a1 = [r[4] for r in d]
        a2 = [r[5] for r in d]
        self.x_init.append((a1[0], a2[0]))
        # turning points of the drum (hysteresis 0.05 in on a 51-sample moving average)
        h = 25
        cs = [0.0]
        for xi in x:
            cs.append(cs[-1] + xi)
        xs = [(cs[min(n, i + h + 1)] - cs[max(0, i - h)]) / (min(n, i + h + 1) - max(0, i - h))
              for i in range(n)]
        ext = [0]
        dirn = 0
        e = 0
        for i in range(n):
            if dirn >= 0 and xs[i] >= xs[e]:
                e = i
                if dirn == 0 and xs[i] > xs[0] + 0.05:
                    dirn = 1
            elif dirn <= 0 and xs[i] <= xs[e]:
                e = i
                if dirn == 0 and xs[i] < xs[0] - 0.05:
                    dirn = -1
            if dirn == 1 and xs[i] < xs[e] - 0.05:
                ext.append(e)
                dirn = -1
                e = i
            elif dirn == -1 and xs[i] > xs[e] + 0.05:
                ext.append(e)
                dirn = 1
                e = i
        ext.append(e)
        # refine each turning point on the raw signal within +-60 samples
        ref = []
        for k, i in enumerate(ext[1:-1], 1):
            lo, hi = max(0, i - 60), min(n, i + 61)
            seg = x[lo:hi]
            if xs[ext[k - 1]] < xs[i]:
                j = lo + seg.index(max(seg))
            else:
                j = lo + seg.index(min(seg))
            ref.append(j)
        for i0, i1 in zip(ref, ref[1:]):
            D = x[i1] - x[i0]
            if abs(D) >= 0.5:
                self.half_cycles.append([(x[i] - x[i0]) / D for i in range(i0, i1 + 1)])
        # rest at the end (drum stopped): from 0.3 s after the last turning point + settle
        last = ref[-1] if ref else n - 1000
        # find where the drum has settled: |x - x_end| < 0.003 from here on
        j = n - 1
        while j > last and abs(x[j] - x[-1]) < 0.003:
            j -= 1
        s0 = j + int(0.1 * FS)
        if n - s0 > 300:
            seg = x[s0:]
            m = len(seg)
            tm = (m - 1) / 2.0
            xm = sum(seg) / m
            sxx = sum((i - tm) ** 2 for i in range(m))
            b = sum((i - tm) * (seg[i] - xm) for i in range(m)) / sxx
            self.rest_noise.append([seg[i] - xm - b * (i - tm) for i in range(m)])
        # actuator excursions
        act = [i for i in range(n) if abs(a1[i] - a1[0]) > 0.002 or abs(a2[i] - a2[0]) > 0.002]
        segs = []
        for i in act:
            if segs and i - segs[-1][1] < 200:
                segs[-1][1] = i
            else:
                segs.append([i, i])
        pad = int(0.12 * FS)
        for s, e in segs:
            lo, hi = max(0, s - pad), min(n, e + pad)
            self.events[kind].append(([a1[i] - a1[lo] for i in range(lo, hi)],
                                      [a2[i] - a2[lo] for i in range(lo, hi)]))
        first = segs[0][0] - pad if segs else n
        self.idle.append(([a1[i] - a1[0] for i in range(0, first)],
                          [a2[i] - a2[0] for i in range(0, first)]))

    def _force_table(self, rows_all):
        bins = {}
        for d in rows_all:
            x1p, x2p = d[0][4], d[0][5]
            for r in d:
                if abs(r[4] - x1p) > 0.001 or abs(r[5] - x2p) > 0.001:
                    continue
                k = round(r[2] * 2) / 2.0
                b = bins.setdefault(k, [0, 0.0, 0.0])
                b[0] += 1
                b[1] += r[6]
                b[2] += r[7]
        tab = [(k, b[1] / b[0], b[2] / b[0]) for k, b in sorted(bins.items()) if b[0] >= 150]
        self.table = tab

    def act_forces(self, F):
        """mean actuator load-cell forces (lb) for a friction force F (kip), interpolated."""
        t = self.table
        if F <= t[0][0]:
            i = 0
        elif F >= t[-1][0]:
            i = len(t) - 2
        else:
            i = 0
            while t[i + 1][0] < F:
                i += 1
        (k0, a0, b0), (k1, a1, b1) = t[i], t[i + 1]
        w = (F - k0) / (k1 - k0)
        f1 = a0 + w * (a1 - a0)
        f2 = b0 + w * (b1 - b0)
        return max(f1, 15.0), max(f2, 15.0)


# ----------------------------------------------------------------------------------------------
# record design
# ----------------------------------------------------------------------------------------------
def noise_stream(rng, pieces, n):
    """concatenation of random sub-pieces (random sign / time direction) of measured noise."""
    out = []
    while len(out) < n:
        p = rng.choice(pieces)
        L = len(p)
        m = rng.randint(min(200, L), L)
        s = rng.randrange(0, L - m + 1)
        seg = p[s:s + m]
        if rng.random() < 0.5:
            seg = seg[::-1]
        sign = 1.0 if rng.random() < 0.5 else -1.0
        out.extend(sign * q for q in seg)
    return out[:n]


def resample(seq, m):
    """linear interpolation of seq onto m+1 points spanning it."""
    L = len(seq) - 1
    out = [0.0] * (m + 1)
    for k in range(m + 1):
        t = k * L / m
        j = int(t)
        if j >= L:
            out[k] = seq[L]
        else:
            w = t - j
            out[k] = seq[j] * (1 - w) + seq[j + 1] * w
    return out


def design_record(rng, lib, dur, act_level, rest_level):
    """returns dict with x (continuous), d1, d2 (actuator deviations), and a description.
    act_level: 0 = no actuator motion, 1 = a few events, 2..4 = increasingly busy actuators.
    rest_level: 0 normal, 1.. more/longer rests."""
    N = int(round(dur * FS)) + 1
    x = [0.0] * N
    rnoise = noise_stream(rng, lib.rest_noise, N)
    desc = {'strokes': 0, 'rests': [], 'peak_speed_in_s': 0.0, 'actuator_events': []}
    p = rng.uniform(-0.3, 0.3)
    L0 = int(rng.uniform(0.4, 1.6 + 0.5 * rest_level) * FS)
    i = 0
    for k in range(L0 + 1):
        x[k] = p + rnoise[k]
    i = L0
    desc['rests'].append(round(L0 / FS, 2))
    dirn = rng.choice([-1, 1])
    end_min = int(0.6 * FS)
    rest_prob = min(0.85, 0.4 + 0.15 * rest_level)
    while True:
        room = X_MAX - dirn * p
        if room < 0.35:
            dirn = -dirn
            room = X_MAX - dirn * p
        placed = False
        for _try in range(6):
            L = rng.uniform(0.3, min(2.3, room))
            vpk = rng.uniform(0.5, 3.5)
            T = math.pi * L / (2 * vpk)
            T = min(max(T, 0.35), 3.0)
            nT = int(round(T * FS))
            if i + nT + end_min <= N - 1:
                placed = True
                break
        if not placed:
            break
        hc = rng.choice(lib.half_cycles)
        phi = resample(hc, nT)
        for k in range(1, nT + 1):
            x[i + k] = p + dirn * L * phi[k]
        desc['strokes'] += 1
        desc['peak_speed_in_s'] = max(desc['peak_speed_in_s'], round(math.pi * L / (2 * T), 2))
        i += nT
        p = p + dirn * L
        if rng.random() < rest_prob:
            Lr = int(rng.uniform(0.3, 2.0 + 0.6 * rest_level) * FS)
            Lr = min(Lr, N - 1 - i - end_min)
            if Lr > int(0.2 * FS):
                for k in range(1, Lr + 1):
                    x[i + k] = p + rnoise[i + k]
                i += Lr
                desc['rests'].append(round(Lr / FS, 2))
        dirn = -dirn if rng.random() < 0.85 else dirn
    for k in range(i + 1, N):
        x[k] = p + rnoise[k]
    desc['rests'].append(round((N - 1 - i) / FS, 2))

    # actuators
    i1 = noise_stream(rng, [q[0] for q in lib.idle], N)
    i2 = noise_stream(rng, [q[1] for q in lib.idle], N)
    o1, o2 = i1[0], i2[0]
    d1 = [q - o1 for q in i1]
    d2 = [q - o2 for q in i2]
    if act_level > 0:
        if act_level == 1:
            n_ev = rng.randint(1, 4)
            cover = None
        else:
            cover = min(0.9, 0.25 + 0.17 * act_level)
            n_ev = 200
        busy = []
        t_used = 0.0
        tries = 0
        while len(desc['actuator_events']) < n_ev and tries < 400:
            tries += 1
            if cover is not None and t_used >= cover * dur:
                break
            kind = rng.choice(['one', 'two', 'both'])
            e1, e2 = rng.choice(lib.events[kind])
            stretch = rng.uniform(0.6, 1.8)
            m = int(len(e1) * stretch)
            e1 = resample(e1, m)
            e2 = resample(e2, m)
            pk = max(max(abs(q) for q in e1), max(abs(q) for q in e2))
            amp = rng.uniform(0.5, 1.5) if kind != 'both' else rng.uniform(0.7, 2.5)
            if act_level >= 3:
                amp *= 1.25
            amp = min(amp, 0.045 / pk)
            hold = 0
            if rng.random() < 0.3:
                # split at the largest excursion and hold it (step-like move)
                j = max(range(len(e1)), key=lambda k: abs(e1[k]) + abs(e2[k]))
                hold = int(rng.uniform(0.2, 1.0) * FS)
                e1 = e1[:j] + [e1[j]] * hold + e1[j:]
                e2 = e2[:j] + [e2[j]] * hold + e2[j:]
            m = len(e1)
            lo = int(0.5 * FS)
            hi = N - m - int(0.3 * FS)
            if hi <= lo:
                continue
            s = rng.randrange(lo, hi)
            if any(not (s + m + 200 < b0 or s > b1 + 200) for b0, b1 in busy):
                continue
            busy.append((s, s + m))
            base1 = e1[0]
            base2 = e2[0]
            for k in range(m):
                d1[s + k] += amp * (e1[k] - base1)
                d2[s + k] += amp * (e2[k] - base2)
            t_used += m / FS
            desc['actuator_events'].append({'t_s': round(s / FS, 2), 'dur_s': round(m / FS, 2),
                                            'kind': kind, 'peak_in': round(amp * pk, 4),
                                            'hold_s': round(hold / FS, 2)})
        desc['actuator_events'].sort(key=lambda e: e['t_s'])
    return {'N': N, 'x': x, 'd1': d1, 'd2': d2, 'desc': desc}


def quantise_columns(rng, lib, D):
    N = D['N']
    off = rng.uniform(0, Q_X)
    xq = f32list([off + round((q - off) / Q_X) * Q_X for q in D['x']])
    x1p, x2p = rng.choice(lib.x_init)
    a1 = f32list([x1p + round(q / Q_A) * Q_A for q in D['d1']])
    a2 = f32list([x2p + round(q / Q_A) * Q_A for q in D['d2']])
    a1[0] = x1p
    a2[0] = x2p
    # velocity column (the files' quirk): 31-sample smoothed derivative / 125.4 + noise
    n = N
    dd = [0.0] * n
    for i in range(1, n - 1):
        dd[i] = (xq[i + 1] - xq[i - 1]) / (2 * DT)
    dd[0], dd[-1] = dd[1], dd[-2]
    cs = [0.0]
    for q in dd:
        cs.append(cs[-1] + q)
    h = 15
    vcol = []
    for i in range(n):
        a = max(0, i - h)
        b = min(n, i + h + 1)
        vcol.append((cs[b] - cs[a]) / (b - a) / VEL_COL_DIV + rng.gauss(0, 0.0003))
    vcol = f32list(vcol)
    return xq, vcol, a1, a2


def quantise_force(F):
    return f32list([round(f / Q_F) * Q_F for f in F])


def actuator_force_columns(rng, lib, Ftrue):
    n = len(Ftrue)
    r = math.exp(-DT / 0.5)
    c = math.sqrt(1 - r * r)
    s1 = rng.gauss(0, 1)
    s2 = rng.gauss(0, 1)
    f1c = []
    f2c = []
    for i in range(n):
        s1 = r * s1 + c * rng.gauss(0, 1)
        s2 = r * s2 + c * rng.gauss(0, 1)
        f1, f2 = lib.act_forces(Ftrue[i])
        f1 = f1 * (1 + 0.03 * s1) + rng.gauss(0, 0.6)
        f2 = f2 * (1 + 0.03 * s2) + rng.gauss(0, 0.6)
        f1c.append(OFF_F1 + round((f1 - OFF_F1) / Q_F1) * Q_F1)
        f2c.append(OFF_F2 + round((f2 - OFF_F2) / Q_F2) * Q_F2)
    return f1c, f2c


def write_record(path, xq, Frec, vcol, a1, a2, f1c, f2c):
    n = len(xq)
    rows = []
    for i in range(n):
        t = i * DT if i else 0
        rows.append([t, xq[i], Frec[i], vcol[i], a1[i], a2[i], f1c[i], f2c[i]])
    obj = {'data': rows}
    for k, v in HEADER:
        obj[k] = v
    with open(path, 'w') as fh:
        json.dump(obj, fh)


def noise_seq(seed, n, sd):
    rg = random.Random(seed)
    return [rg.gauss(0.0, sd) for _ in range(n)]


# ----------------------------------------------------------------------------------------------
# trials
# ----------------------------------------------------------------------------------------------
FIXED = {
    'slack_deadzone': lambda r: {},
    'sag_softened_reengagement': lambda r: {'E_p': 0.5},
    'slack_snap_reengagement': lambda r: {'delta_per_p': 0.04, 'K_per_p': 0.6,
                                          'tau_d': round(r.uniform(0.04, 0.08), 3),
                                          'f_ring': round(r.uniform(7.0, 12.0), 2)},
    'prony_relaxation': lambda r: {'tau': round(r.uniform(0.6, 1.5), 3)},
    'log_creep': lambda r: {'t_c': round(r.uniform(0.05, 0.2), 3)},
    'settle_to_bias': lambda r: {'F_bias': round(r.choice([-1, 1]) * r.uniform(0.6, 1.6), 3)},
    'elastoplastic_blend': lambda r: {'breakaway_frac': round(r.uniform(0.4, 0.7), 3)},
    'iwan_masing_blend': lambda r: {'N': 16, 'K_over_sigma0': round(r.uniform(0.8, 1.2), 3)},
    'dahl_exponent': lambda r: {},
    'rate_state_log': lambda r: {'sign': r.choice([-1, 1]), 'v0': 0.1, 'v_ref': 0.25},
    'grosch_bell': lambda r: {'v_peak': round(r.uniform(0.8, 2.2), 3), 'width_decades': 0.3},
    'power_law_thirdbody': lambda r: {'n': 0.4},
    'zener_partial_lag': lambda r: {'alpha_instant': 0.3},
    'second_order_resonant': lambda r: {'zeta': round(r.uniform(0.2, 0.4), 3)},
    'leadscrew_play': lambda r: {},
    'capstan_wrap_growth': lambda r: {'mu_theta0': 1.4},
    'servo_takeup_travel': lambda r: {'ell': round(r.uniform(0.4, 0.8), 3)},
    'tension_feedback_lag': lambda r: {'tau': round(r.uniform(0.1, 0.2), 3)},
    'fung_exponential': lambda r: {},
    'tanh_saturation': lambda r: {},
    'bilinear_tension_only': lambda r: {},
    'one_side_stribeck_velocity': lambda r: {'direction': r.choice(['forward', 'backward']),
                                             'sign': r.choice([-1, 1])},
    'one_side_lining_periodic': lambda r: {'direction': r.choice(['forward', 'backward']),
                                           'wavelength_in': round(r.uniform(0.6, 1.2), 3),
                                           'phase_rad': round(r.uniform(0, 2 * math.pi), 3)},
    'one_side_presliding_stiffness': lambda r: {'direction': r.choice(['forward', 'backward'])},
}
PARAM_NAME = {
    'slack_deadzone': 'delta_in', 'sag_softened_reengagement': 'E_star_kip',
    'slack_snap_reengagement': 'p', 'prony_relaxation': 'relaxed_fraction',
    'log_creep': 'beta', 'settle_to_bias': 'rate_per_s', 'elastoplastic_blend': 'w',
    'iwan_masing_blend': 'w', 'dahl_exponent': 'one_minus_alpha', 'rate_state_log': 'abs_c',
    'grosch_bell': 'A', 'power_law_thirdbody': 'c_kip', 'zener_partial_lag': 'tau_s',
    'second_order_resonant': 'T_n_s', 'leadscrew_play': 'eps_in', 'capstan_wrap_growth': 'beta_per_in',
    'servo_takeup_travel': 'A', 'tension_feedback_lag': 'kappa', 'fung_exponential': 'beta_per_kip',
    'tanh_saturation': 'inv_Dsat_per_kip', 'bilinear_tension_only': 'kink_p',
    'one_side_stribeck_velocity': 'p_log_ratio', 'one_side_lining_periodic': 'a',
    'one_side_presliding_stiffness': 'p',
}


def ratio_of(cat, shape, p, recs, fx, sd, bases):
    ss = 0.0
    nn = 0
    for R, Fb in zip(recs, bases):
        Ft = M.simulate(cat, shape, p, R, fx)
        ss += sum((a - b) ** 2 for a, b in zip(Ft, Fb))
        nn += len(Ft)
    return math.sqrt(ss / nn) / sd


def solve(cat, shape, recs, fx, sd, target, pmax, bases):
    """Illinois false position on [0, pmax] for ratio(p) = target."""
    fa = -target
    a = 0.0
    b = pmax
    fb = ratio_of(cat, shape, b, recs, fx, sd, bases) - target
    if fb < 0:
        return None, fb + target
    side = 0
    c, fc = b, fb
    for _ in range(60):
        c = (a * fb - b * fa) / (fb - fa)
        fc = ratio_of(cat, shape, c, recs, fx, sd, bases) - target
        if abs(fc) < 0.002:
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
    return c, fc + target


def build_trials(rng):
    cats = list(M.SHAPES.keys())
    trials = []
    # strengths: 12 strong / 12 weak, every category has at least one of each
    two_strong = set(rng.sample(cats, 4))
    for cat in cats:
        shapes = list(M.SHAPES[cat].keys())
        rng.shuffle(shapes)
        st = ['strong', 'strong', 'weak'] if cat in two_strong else ['strong', 'weak', 'weak']
        rng.shuffle(st)
        for sh, s in zip(shapes, st):
            trials.append({'category': cat, 'shape': sh, 'strength': s})
    for _ in range(6):
        trials.append({'category': 'none', 'shape': 'none', 'strength': None})
    rng.shuffle(trials)
    for k, t in enumerate(trials):
        t['id'] = 't%02d' % (k + 1)
    return trials


def main():
    t_start = time.time()
    rng = random.Random(MASTER_SEED)
    lib = Library()
    print('library: %d half-strokes, %d rest pieces, events %s, table %d bins (%.1fs)' % (
        len(lib.half_cycles), len(lib.rest_noise), {k: len(v) for k, v in lib.events.items()},
        len(lib.table), time.time() - t_start))
    trials = build_trials(rng)
    key = {}
    os.makedirs(CASES, exist_ok=True)
    for t in trials:
        t0 = time.time()
        cat, shape = t['category'], t['shape']
        trng = random.Random(rng.getrandbits(64))
        sd = round(trng.uniform(0.02, 0.06), 4)
        if t['strength'] == 'strong':
            target = trng.uniform(8.5, 11.5)
        elif t['strength'] == 'weak':
            target = trng.uniform(2.7, 3.8)
        else:
            target = 0.0
        fx = FIXED[shape](trng) if cat != 'none' else {}
        needs_act = cat in ('actuator_lag', 'pretension')
        durs = [round(trng.uniform(9.0, 25.0), 2) for _ in range(2)]
        F0s = [trng.uniform(-1.0, 1.4) for _ in range(2)]
        act_flags = [trng.random() < 0.5 for _ in range(2)]
        design_seed = trng.getrandbits(64)
        noise_seeds = [trng.getrandbits(63) for _ in range(2)]
        aux_seed = trng.getrandbits(64)
        p_sol = None
        for attempt in range(8):
            drng = random.Random(design_seed + attempt)
            act_level = 2 + min(attempt, 2) if needs_act else None
            rest_level = min(attempt, 3) if cat == 'residual_static' else 0
            designs = []
            recs = []
            cols = []
            for r in range(2):
                al = act_level if needs_act else (1 if act_flags[r] else 0)
                D = design_record(drng, lib, durs[r], al, rest_level)
                xq, vcol, a1, a2 = quantise_columns(drng, lib, D)
                F0 = round(F0s[r] / Q_F) * Q_F
                F0 = f32list([F0])[0]
                R = M.Rec(xq, a1, a2, F0)
                designs.append(D)
                recs.append(R)
                cols.append((xq, vcol, a1, a2))
            bases = [R.base() for R in recs]
            if cat == 'none':
                p_sol, achieved = 0.0, 0.0
                break
            pmax = M.SHAPES[cat][shape][1]
            p_sol, achieved = solve(cat, shape, recs, fx, sd, target, pmax, bases)
            if p_sol is not None:
                break
            print('   %s %s/%s: target %.2f not reachable (max %.2f, sd %.4f), redesign' % (
                t['id'], cat, shape, target, achieved, sd))
        if p_sol is None:
            raise SystemExit('could not reach target for %s' % t['id'])
        # final truth, noise, columns
        arng = random.Random(aux_seed)
        os.makedirs(os.path.join(CASES, t['id']), exist_ok=True)
        rec_info = {}
        ss = 0.0
        nn = 0
        for r, name in enumerate(('A', 'B')):
            R = recs[r]
            Ft = M.simulate(cat, shape, p_sol, R, fx)
            ss += sum((a - b) ** 2 for a, b in zip(Ft, bases[r]))
            nn += R.n
            nz = noise_seq(noise_seeds[r], R.n, sd)
            Frec = quantise_force([a + b for a, b in zip(Ft, nz)])
            Frec[0] = R.E0          # first sample = the held force the black box starts from
            f1c, f2c = actuator_force_columns(arng, lib, Ft)
            xq, vcol, a1, a2 = cols[r]
            write_record(os.path.join(CASES, t['id'], name + '.json'), xq, Frec, vcol, a1, a2, f1c, f2c)
            d = designs[r]['desc']
            rec_info[name] = {
                'duration_s': round((R.n - 1) * DT, 4), 'n_samples': R.n, 'noise_seed': noise_seeds[r],
                'initial_force_kip': R.E0, 'strokes': d['strokes'], 'rests_s': d['rests'],
                'peak_speed_in_s': d['peak_speed_in_s'],
                'actuator_events': d['actuator_events'],
                'rms_effect_kip': round(math.sqrt(sum((a - b) ** 2 for a, b in zip(Ft, bases[r])) / R.n), 5),
            }
        ratio = math.sqrt(ss / nn) / sd
        entry = {'category': cat, 'shape': shape, 'strength': t['strength'] or 'none',
                 'ratio': round(ratio, 4), 'target_ratio': round(target, 4), 'noise_kip': sd,
                 'params': dict(fx)}
        if cat != 'none':
            entry['params'][PARAM_NAME[shape]] = p_sol
            entry['params']['_strength_param'] = PARAM_NAME[shape]
            entry['params']['_strength_param_max'] = M.SHAPES[cat][shape][1]
        entry['records'] = rec_info
        key[t['id']] = entry
        print('%s %-16s %-30s %-6s sd=%.4f target=%6.3f ratio=%6.3f p=%.5g  dur=%s  (%.1fs)' % (
            t['id'], cat, shape, t['strength'] or '-', sd, target, ratio, p_sol,
            [rec_info['A']['duration_s'], rec_info['B']['duration_s']], time.time() - t0))
        sys.stdout.flush()
    key = {k: key[k] for k in sorted(key)}
    with open(os.path.join(ROOT, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)
    print('done in %.1f s' % (time.time() - t_start))


if __name__ == '__main__':
    main()
