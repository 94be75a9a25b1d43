#!/usr/bin/env python3
"""Blind synthetic BRFD test set generator (blind8).

    python3 /work/blind8/gen/gen.py --seed 8008 --out /work/blind8

Writes OUT/cases/tNN/{A,B}.json, OUT/key.json, OUT/trials.txt.  Standard library only,
deterministic for a given seed (multiprocessing is used only to parallelise pure functions;
results are collected in a fixed order).
"""
import argparse
import json
import math
import os
import random
import struct
import sys
import time
from multiprocessing import Pool

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import model as M  # noqa: E402

DATA = '/work/shared/data/brfd/semiactive'
FILES = ['harmonic0.015backward', 'harmonic0.015forward', 'harmonic0.03ea1backward',
         'harmonic0.03ea1forward', 'harmonic0.03ea2backward', 'harmonic0.03ea2forward']
N = 15361
DT = 1.0 / 1024.0
VEL_COL_SCALE = 125.39      # README quirk: velocity column = true velocity / ~125.4
Q_X = 5.894226e-5            # displacement quantum (in), offset -0.337 quantum
Q_X_OFF = -0.337
Q_F = 0.00080087996402       # friction force quantum (kip)
Q_A = 2.384186e-6            # actuator position quantum (in)
Q_L1, Q_L1_OFF = 0.3179401530, 0.0505   # actuator-1 load cell quantum (lb), offset
Q_L2, Q_L2_OFF = 0.3998999128, 0.32986  # actuator-2 load cell quantum (lb), offset
WEAK = (0.15, 0.30)
STRONG = (0.45, 0.80)
HEADER_KEYS = [('dt', 0.0009765625), ('sampling freq', 1024), ('displacement units', 'in'),
               ('time units', 's'), ('friction force units', 'kip'),
               ('actuator force units', 'lb')]


def f32(x):
    return struct.unpack('f', struct.pack('f', x))[0]


def tcol(i):
    t = i / 1024.0
    return int(t) if t == int(t) else t


# ------------------------------------------------------------------ inputs

_MEAS = {}


def measured(name):
    if name not in _MEAS:
        with open(os.path.join(DATA, name + '.json')) as fh:
            _MEAS[name] = json.load(fh)['data']
    return _MEAS[name]


def replay_inputs(name):
    D = measured(name)
    return dict(kind='replay', source=name + '.json',
                t=[r[0] for r in D], x=[r[1] for r in D], velcol=[r[3] for r in D],
                x1=[r[4] for r in D], x2=[r[5] for r in D], F0_true=D[0][2])


def _smooth_bump(t, a, b, tap):
    """1 on [a, b], raised-cosine tapers of width tap outside, 0 elsewhere."""
    if a <= t <= b:
        return 1.0
    if a - tap < t < a:
        return 0.5 - 0.5 * math.cos(math.pi * (t - (a - tap)) / tap)
    if b < t < b + tap:
        return 0.5 + 0.5 * math.cos(math.pi * (t - b) / tap)
    return 0.0


def custom_inputs(rng, heavy=False, holds=1):
    """Own drum motion and actuator history (continuous velocity, rests/holds, a passive
    window of >= 2 full sliding cycles before the actuators first move)."""
    t_start = rng.uniform(0.15, 0.4)
    f = rng.uniform(0.42, 0.75)
    T_up = rng.uniform(1.0, 2.0)
    h2 = rng.uniform(0.0, 0.25)
    ph2 = rng.uniform(0, 2 * math.pi)
    am = rng.uniform(0.0, 0.3)
    ncyc = rng.uniform(2.0, 5.0)   # amplitude modulation period, in drum cycles
    psi = rng.uniform(0, 2 * math.pi)
    end_mode = rng.choice(['ramp_down', 'freeze'])
    t_stop = rng.uniform(13.2, 14.3)
    T_dn = rng.uniform(1.0, 2.0)
    t_pass_end = t_start + T_up + 2.25 / f      # 2 full cycles after the ramp, + margin
    tap = 0.25
    # holds after the passive window
    hl = []
    tt = t_pass_end + rng.uniform(0.3, 1.0)
    for _ in range(holds):
        Dh = rng.uniform(0.7, 1.6)
        if tt + Dh + 2 * tap > t_stop - T_dn - 0.5:
            break
        hl.append((tt + tap, tt + tap + Dh))
        tt = tt + Dh + 2 * tap + rng.uniform(1.2, 2.5)

    def speed(t):
        if t < t_start:
            return 0.0
        w = 1.0
        for a, b in hl:
            w *= 1.0 - _smooth_bump(t, a, b, tap)
        if end_mode == 'freeze':
            w *= 1.0 - _smooth_bump(t, t_stop, 1e9, 0.35)
        return 2 * math.pi * f * w

    def amp(t, th_, thd):
        """amplitude envelope and its derivative"""
        if t < t_start:
            return 0.0, 0.0
        # modulation is a function of the drum phase, so it freezes during holds
        a, da = 1.0 + am * math.sin(th_ / ncyc + psi), am / ncyc * math.cos(th_ / ncyc + psi) * thd
        if t < t_start + T_up:
            u = (t - t_start) / T_up
            e, de = 0.5 - 0.5 * math.cos(math.pi * u), 0.5 * math.pi / T_up * math.sin(math.pi * u)
            a, da = a * e, da * e + a * de
        if end_mode == 'ramp_down':
            if t > t_stop:
                return 0.0, 0.0
            if t > t_stop - T_dn:
                u = (t - (t_stop - T_dn)) / T_dn
                e, de = 0.5 + 0.5 * math.cos(math.pi * u), -0.5 * math.pi / T_dn * math.sin(math.pi * u)
                a, da = a * e, da * e + a * de
        return a, da

    th = [0.0] * N
    for i in range(1, N):
        t0, t1 = (i - 1) * DT, i * DT
        th[i] = th[i - 1] + DT / 6 * (speed(t0) + 4 * speed(0.5 * (t0 + t1)) + speed(t1))
    xr = [0.0] * N
    vr = [0.0] * N
    for i in range(N):
        t = i * DT
        sp = speed(t)
        a, da = amp(t, th[i], sp)
        S = math.sin(th[i]) + h2 * math.sin(2 * th[i] + ph2)
        dS = math.cos(th[i]) + 2 * h2 * math.cos(2 * th[i] + ph2)
        xr[i] = a * S
        vr[i] = da * S + a * dS * sp
    A_t = rng.uniform(0.7, 1.2)
    V_t = rng.uniform(3.0, 3.9)
    sc = min(A_t / max(abs(u) for u in xr), V_t / max(abs(u) for u in vr))
    xt = [u * sc for u in xr]
    vt = [u * sc for u in vr]
    x = []
    for u in xt:
        k = round((u + rng.gauss(0, 2.5e-5)) / Q_X - Q_X_OFF)
        x.append(f32(Q_X * (k + Q_X_OFF)))
    velcol = []
    for i in range(N):
        j = max(0, i - 5)
        velcol.append(f32((vt[j] + rng.gauss(0, 0.045)) / VEL_COL_SCALE))
    # actuators
    x1p = 0.655 + rng.uniform(-0.01, 0.01)
    x2p = 0.8559 + rng.uniform(-0.01, 0.01)
    d1 = [0.0] * N
    d2 = [0.0] * N
    events = []
    ta = t_pass_end + rng.uniform(0.05, 0.4)
    t_end_act = t_stop - rng.uniform(0.3, 1.0)
    tries = 0
    while True:
        typ = rng.choice(['sine', 'step', 'sine']) if heavy else rng.choice(['sine', 'step', 'sine', 'step', 'ramp'])
        which = rng.choice(['1', '2', 'both'])
        a = rng.uniform(0.018, 0.03) if heavy else rng.uniform(0.008, 0.03)
        sg = (-1.0 if rng.random() < 0.8 else 1.0) if heavy else rng.choice([-1.0, 1.0])
        a2 = a * rng.uniform(0.5, 1.0) * (sg if heavy else rng.choice([-1.0, 1.0]))
        if typ == 'sine':
            P_ = rng.uniform(0.4, 1.0) if heavy else rng.uniform(0.8, 2.0)
            dur = P_
        elif typ == 'step':
            Tr = rng.uniform(0.08, 0.25)
            H = rng.uniform(0.5, 2.0)
            dur = 2 * Tr + H
        else:
            Tr = rng.uniform(0.6, 1.5)
            H = rng.uniform(0.2, 1.0)
            dur = 2 * Tr + H
        if ta + dur > t_end_act:
            tries += 1
            if tries > 6:
                break
            continue
        ev = dict(type=typ, actuators=which, t0=round(ta, 4), duration=round(dur, 4),
                  amp1_in=round(sg * a, 5) if which in ('1', 'both') else 0.0,
                  amp2_in=round((sg * a if which == '2' else a2), 5) if which in ('2', 'both') else 0.0)
        events.append(ev)
        i0 = int(math.ceil(ta / DT))
        i1 = min(N - 1, int((ta + dur) / DT))
        for i in range(i0, i1 + 1):
            u = i * DT - ta
            if typ == 'sine':
                sh = -math.sin(2 * math.pi * u / P_)
            else:
                if u < Tr:
                    sh = 0.5 - 0.5 * math.cos(math.pi * u / Tr)
                elif u < Tr + H:
                    sh = 1.0
                else:
                    sh = 0.5 + 0.5 * math.cos(math.pi * min(1.0, (u - Tr - H) / Tr))
            d1[i] += ev['amp1_in'] * sh
            d2[i] += ev['amp2_in'] * sh
        ta += dur + (rng.uniform(0.1, 0.4) if heavy else rng.uniform(0.2, 1.5))
    x1 = [f32(Q_A * round((x1p + d + rng.gauss(0, 1.2e-6)) / Q_A)) for d in d1]
    x2 = [f32(Q_A * round((x2p + d + rng.gauss(0, 1.2e-6)) / Q_A)) for d in d2]
    x1[0] = f32(Q_A * round(x1p / Q_A))
    x2[0] = f32(Q_A * round(x2p / Q_A))
    F0_true = rng.uniform(-0.6, 0.9)
    meta = dict(f_hz=round(f, 4), amplitude_in=round(max(abs(u) for u in xt), 4),
                peak_speed_in_s=round(max(abs(u) for u in vt), 3), second_harmonic=round(h2, 3),
                t_start=round(t_start, 3), ramp_up_s=round(T_up, 3), end_mode=end_mode,
                t_stop=round(t_stop, 3), holds=[(round(a, 3), round(b, 3)) for a, b in hl],
                passive_until_s=round(events[0]['t0'] if events else 15.0, 3),
                actuator_events=events)
    return dict(kind='custom', source=None, t=[tcol(i) for i in range(N)], x=x, velcol=velcol,
                x1=x1, x2=x2, F0_true=F0_true, meta=meta)


# ------------------------------------------------------------------ noise & columns

def make_noise(rng, sigma, colour):
    if colour == 'white':
        return [rng.gauss(0, sigma) for _ in range(N)], {}
    if colour == 'ar1':
        phi = rng.uniform(0.85, 0.97)
        e = rng.gauss(0, sigma)
        out = [e]
        c = sigma * math.sqrt(1 - phi * phi)
        for _ in range(N - 1):
            e = phi * e + rng.gauss(0, c)
            out.append(e)
        return out, {'phi': round(phi, 4)}
    # hum: 60 Hz mains (+ small 180 Hz) + white, total RMS sigma
    ph = rng.uniform(0, 2 * math.pi)
    ph3 = rng.uniform(0, 2 * math.pi)
    a1 = sigma * math.sqrt(2 * 0.5)      # 50 % of variance in 60 Hz
    a3 = sigma * math.sqrt(2 * 0.1)      # 10 % in 180 Hz
    sw = sigma * math.sqrt(0.4)
    out = [a1 * math.sin(2 * math.pi * 60 * i * DT + ph) + a3 * math.sin(2 * math.pi * 180 * i * DT + ph3)
           + rng.gauss(0, sw) for i in range(N)]
    return out, {'hum_hz': [60, 180], 'variance_split': [0.5, 0.1, 0.4]}


def qforce(F):
    return Q_F * round(F / Q_F)


def load_cells(rng, Ftrue):
    """Synthetic actuator load cells (lb): the taut band carries ~1000/C_taut lb per kip of
    friction (C2 = 2.10 forward, C3 = 1.94 backward), the slack band ~1000/C_slack
    (C1 = 119.68, C4 = 123.31), on top of a small static tension."""
    p1 = rng.uniform(30, 60)
    p2 = rng.uniform(40, 110)
    c1, c2 = [], []
    for F in Ftrue:
        l1 = p1 + 1000.0 / 1.94 * max(-F, 0.0) + 1000.0 / 119.68 * max(F, 0.0) + rng.gauss(0, 6.0)
        l2 = p2 + 1000.0 / 2.10 * max(F, 0.0) + 1000.0 / 123.31 * max(-F, 0.0) + rng.gauss(0, 9.0)
        l1 = max(l1, 20.0)
        l2 = max(l2, 20.0)
        c1.append(Q_L1 * (round(l1 / Q_L1 - Q_L1_OFF) + Q_L1_OFF))
        c2.append(Q_L2 * (round(l2 / Q_L2 - Q_L2_OFF) + Q_L2_OFF))
    return c1, c2


def write_record(path, inp, Fw, l1, l2):
    rows = []
    for i in range(N):
        rows.append([inp['t'][i], inp['x'][i], Fw[i], inp['velcol'][i], inp['x1'][i], inp['x2'][i],
                     l1[i], l2[i]])
    d = {'data': rows}
    for k, v in HEADER_KEYS:
        d[k] = v
    with open(path, 'w') as fh:
        json.dump(d, fh)


# ------------------------------------------------------------------ effects / calibration

def effect_fn(cat, shape):
    for name, fn, pname in M.EFFECTS[cat]:
        if name == shape:
            return fn, pname
    raise KeyError(shape)


def build_recs(tr):
    recs = []
    for inp, F0w in zip(tr['inputs'], tr['F0w']):
        recs.append(M.Rec(inp['x'], inp['x1'], inp['x2'], F0w))
    return recs


def rms_of(tr, recs, bases, s):
    fn, _ = effect_fn(tr['category'], tr['shape'])
    ss, nn = 0.0, 0
    for r, Fb in zip(recs, bases):
        Fe = fn(r, s, tr['q'])
        ss += sum((a - b) ** 2 for a, b in zip(Fe, Fb))
        nn += len(Fb)
    return math.sqrt(ss / nn)


GRID_K = 12


def scan_job(tr):
    """RMS(effect - base) on a geometric grid of strengths (for feasibility/bracketing)."""
    recs = build_recs(tr)
    bases = [M.base_force(r) for r in recs]
    lo, hi = M.S_BOUNDS[tr['shape']]
    grid = [lo * (hi / lo) ** (k / (GRID_K - 1)) for k in range(GRID_K)]
    return [(s, rms_of(tr, recs, bases, s)) for s in grid]


def calib_job(args):
    tr, scan, target = args
    recs = build_recs(tr)
    bases = [M.base_force(r) for r in recs]
    # first grid crossing of the target
    prev = (0.0, 0.0)
    br = None
    for s, v in scan:
        if v >= target:
            br = (prev, (s, v))
            break
        prev = (s, v)
    if br is None:
        s, v = max(scan, key=lambda p: p[1])
        return s, v
    (s0, v0), (s1, v1) = br
    best = (s1, v1)
    for _ in range(30):
        if s0 <= 0:
            s = s1 * 0.5
        else:
            # interpolate in log-log, safeguarded
            try:
                a = (math.log(v1) - math.log(max(v0, 1e-9))) / (math.log(s1) - math.log(s0))
                s = math.exp(math.log(s0) + (math.log(target) - math.log(max(v0, 1e-9))) / a) if a > 0 else math.sqrt(s0 * s1)
            except (ValueError, ZeroDivisionError):
                s = math.sqrt(s0 * s1)
            if not (min(s0, s1) < s < max(s0, s1)):
                s = math.sqrt(s0 * s1)
        v = rms_of(tr, recs, bases, s)
        if abs(v - target) < abs(best[1] - target):
            best = (s, v)
        if abs(v / target - 1) < 0.01:
            break
        if v >= target:
            s1, v1 = s, v
        else:
            s0, v0 = s, v
    return best


# ------------------------------------------------------------------ plan

CATS = ['actuator_lag', 'asymmetry', 'backlash', 'pretension', 'residual_static',
        'self_energizing', 'transition_shape', 'velocity']


def plan(seed):
    rng = random.Random(seed)
    trials = []
    for cat in CATS:
        shapes = [s[0] for s in M.EFFECTS[cat]]
        ncust = 2 if cat == 'residual_static' else 1
        cust = set(rng.sample(range(3), ncust))
        for k, sh in enumerate(shapes):
            trials.append(dict(category=cat, shape=sh, input_kind='custom' if k in cust else 'replay'))
    for k in range(6):
        trials.append(dict(category='none', shape='none', input_kind='custom' if k < 2 else 'replay'))
    # noise level / colour (balanced)
    sig = [0.02] * 15 + [0.06] * 15
    col = ['white'] * 10 + ['ar1'] * 10 + ['hum'] * 10
    rng.shuffle(sig)
    rng.shuffle(col)
    for tr, s_, c_ in zip(trials, sig, col):
        tr['noise_sigma_kip'] = s_
        tr['noise_colour'] = c_
    # inputs
    for k, tr in enumerate(trials):
        r2 = random.Random(seed * 1000 + 17 * k + 1)
        if tr['input_kind'] == 'replay':
            a, b = r2.sample(FILES, 2)
            tr['inputs'] = [replay_inputs(a), replay_inputs(b)]
        else:
            # dense actuation where the effect needs it, and at random elsewhere (so the input
            # style does not reveal the category)
            heavy = tr['category'] in ('actuator_lag', 'pretension') or r2.random() < 0.4
            nh = 2 if tr['category'] == 'residual_static' else (1 if heavy else r2.choice([1, 2]))
            tr['inputs'] = [custom_inputs(r2, heavy=heavy, holds=nh), custom_inputs(r2, heavy=heavy, holds=nh)]
        tr['q'] = {}
        if tr['shape'] == 'second_order_underdamped':
            tr['q'] = {'zeta': round(r2.uniform(0.3, 0.6), 3)}
        if tr['shape'] == 'toward_residual_level':
            tr['q'] = {'R': round(r2.uniform(0.6, 1.6), 3), 'vr': 0.03}
        if tr['shape'] in ('relax_to_zero', 'power_law_creep'):
            tr['q'] = {'vr': 0.03}
        if tr['shape'] == 'power_law_creep':
            tr['q']['t0'] = 0.05
        if tr['shape'] == 'slip_drift':
            tr['q'] = {'S0': round(r2.uniform(10.0, 25.0), 2)}
        if tr['shape'] == 'maxwell_slip':
            tr['q'] = {'k': [2.8, 0.7, 0.3, 0.2]}
        if tr['shape'] == 'load_dependent_gap':
            tr['q'] = {'vrev': 0.05}
        # noise
        tr['noise'] = []
        tr['noise_params'] = []
        tr['F0w'] = []
        for inp in tr['inputs']:
            nz, npar = make_noise(r2, tr['noise_sigma_kip'], tr['noise_colour'])
            tr['noise'].append(nz)
            tr['noise_params'].append(npar)
            tr['F0w'].append(qforce(inp['F0_true'] + nz[0]))
        tr['rng_state'] = seed * 1000 + 17 * k + 2
    return rng, trials


def assign_strengths(rng, trials, scans):
    """12 strong / 12 weak among the 24 effect trials, every category gets at least one of
    each where feasible; strong only where the strength range can reach it."""
    eff = [k for k, t in enumerate(trials) if t['category'] != 'none']
    maxr = {k: max(v for _, v in scans[k]) for k in eff}
    strong_ok = {k for k in eff if maxr[k] >= 0.50}
    cls = {}
    bycat = {}
    for k in eff:
        bycat.setdefault(trials[k]['category'], []).append(k)
    cats = sorted(bycat)
    rng.shuffle(cats)
    nstrong = 0
    # one strong per category (if feasible)
    for c in cats:
        ks = [k for k in bycat[c] if k in strong_ok]
        if ks:
            k = rng.choice(ks)
            cls[k] = 'strong'
            nstrong += 1
    rest = [k for k in eff if k not in cls]
    rng.shuffle(rest)
    for k in rest:
        c = trials[k]['category']
        nweak_c = sum(1 for kk in bycat[c] if cls.get(kk) == 'weak')
        if nstrong < 12 and k in strong_ok and nweak_c >= 1:
            cls[k] = 'strong'
            nstrong += 1
        else:
            cls[k] = 'weak'
    for k in rest:  # top up if needed
        if nstrong >= 12:
            break
        c = trials[k]['category']
        if cls[k] == 'weak' and k in strong_ok and sum(1 for kk in bycat[c] if cls.get(kk) == 'weak') >= 2:
            cls[k] = 'strong'
            nstrong += 1
    for k in eff:
        if cls[k] == 'strong':
            lo, hi = STRONG[0] + 0.02, min(STRONG[1] - 0.05, 0.95 * maxr[k])
        else:
            lo, hi = WEAK[0] + 0.02, WEAK[1] - 0.02
        trials[k]['strength_class'] = cls[k]
        trials[k]['target_rms_kip'] = round(rng.uniform(lo, hi), 4)


def strip(tr):
    return {k: v for k, v in tr.items() if k not in ('inputs', 'noise')}


def final_job(args):
    k, tr, s, outdir = args
    recs = build_recs(tr)
    r2 = random.Random(tr['rng_state'])
    res = []
    for j, (r, inp, nz) in enumerate(zip(recs, tr['inputs'], tr['noise'])):
        Fb = M.base_force(r)
        if tr['category'] == 'none':
            Fe = Fb
        else:
            fn, _ = effect_fn(tr['category'], tr['shape'])
            Fe = fn(r, s, tr['q'])
        Fw = [tr['F0w'][j]] + [qforce(Fe[i] + nz[i]) for i in range(1, N)]
        l1, l2 = load_cells(r2, Fe)
        path = os.path.join(outdir, 'AB'[j] + '.json')
        write_record(path, inp, Fw, l1, l2)
        d = [a - b for a, b in zip(Fe, Fb)]
        res.append(dict(rms_effect=math.sqrt(sum(u * u for u in d) / N),
                        rms_noise=math.sqrt(sum(u * u for u in nz) / N),
                        ss=sum(u * u for u in d)))
    return k, res


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument('--seed', type=int, default=8008)
    ap.add_argument('--out', default='/work/blind8')
    ap.add_argument('--jobs', type=int, default=max(1, min(4, os.cpu_count() or 1)))
    a = ap.parse_args()
    t0 = time.time()
    rng, trials = plan(a.seed)
    eff = [k for k, t in enumerate(trials) if t['category'] != 'none']
    with Pool(a.jobs) as pool:
        scans_l = pool.map(scan_job, [trials[k] for k in eff])
        scans = dict(zip(eff, scans_l))
        assign_strengths(rng, trials, scans)
        cal = pool.map(calib_job, [(trials[k], scans[k], trials[k]['target_rms_kip']) for k in eff])
        for k, (s, v) in zip(eff, cal):
            trials[k]['strength'] = s
            trials[k]['calibrated_rms_kip'] = v
        # mix the order
        order = list(range(len(trials)))
        rng.shuffle(order)
        ids = ['t%02d' % (j + 1) for j in range(len(trials))]
        jobs = []
        for j, k in enumerate(order):
            tr = trials[k]
            tr['id'] = ids[j]
            od = os.path.join(a.out, 'cases', ids[j])
            os.makedirs(od, exist_ok=True)
            jobs.append((k, tr, tr.get('strength', 0.0), od))
        fin = pool.map(final_job, jobs)
    for k, res in fin:
        tr = trials[k]
        tot = math.sqrt(sum(r['ss'] for r in res) / (2 * N))
        tr['rms_effect_minus_base_kip'] = round(tot, 4)
        tr['rms_effect_per_record_kip'] = [round(r['rms_effect'], 4) for r in res]
        tr['rms_noise_per_record_kip'] = [round(r['rms_noise'], 4) for r in res]
    key = {'seed': a.seed, 'generator': 'gen/gen.py', 'trials': []}
    for j, k in enumerate(order):
        tr = trials[k]
        e = {'id': tr['id'], 'category': tr['category'], 'shape': tr['shape']}
        if tr['category'] != 'none':
            _, pname = effect_fn(tr['category'], tr['shape'])
            e.update(strength=round(tr['strength'], 6), strength_param=pname,
                     shape_constants=tr['q'], strength_class=tr['strength_class'],
                     target_rms_kip=tr['target_rms_kip'],
                     rms_effect_minus_base_kip=tr['rms_effect_minus_base_kip'],
                     rms_effect_per_record_kip=tr['rms_effect_per_record_kip'])
        else:
            e.update(strength=0.0, strength_class='none', rms_effect_minus_base_kip=0.0)
        e.update(noise_sigma_kip=tr['noise_sigma_kip'], noise_colour=tr['noise_colour'],
                 noise_params=tr['noise_params'], rms_noise_per_record_kip=tr['rms_noise_per_record_kip'],
                 input_kind=tr['input_kind'],
                 records={'A': {'source': tr['inputs'][0]['source'], 'F0_kip': tr['F0w'][0],
                                'x_prime_in': [tr['inputs'][0]['x1'][0], tr['inputs'][0]['x2'][0]],
                                'custom': tr['inputs'][0].get('meta')},
                          'B': {'source': tr['inputs'][1]['source'], 'F0_kip': tr['F0w'][1],
                                'x_prime_in': [tr['inputs'][1]['x1'][0], tr['inputs'][1]['x2'][0]],
                                'custom': tr['inputs'][1].get('meta')}})
        key['trials'].append(e)
    with open(os.path.join(a.out, 'key.json'), 'w') as fh:
        json.dump(key, fh, indent=1)
    with open(os.path.join(a.out, 'trials.txt'), 'w') as fh:
        fh.write('\n'.join(ids) + '\n')
    print('wrote %d trials to %s in %.1f s' % (len(trials), a.out, time.time() - t0))


if __name__ == '__main__':
    main()
