"""Inputs (drum displacement, actuator positions) of the synthetic records.

kind 'harmonic'  : the inputs of one measured semi-active test, unchanged.
kind 'broadband' : earthquake-like drum motion.  0 .. T_s: the measured drum motion of a
                   semi-active test up to its drum extremum near 3.5 s (actuators still), then a
                   smooth return to centre (1.2 s), a 1.0 s dwell at rest, a strong-motion
                   segment built from a measured earthquake displacement history of
                   /work/shared/data/brfd/earthquake-profiles (smoothed, re-centred, scaled to
                   ~0.9 in peak and time-stretched to ~4.5 in/s peak velocity, tapered), and a
                   rest to the end (15 s in all).  Actuators: step commands (like the paper's step
                   validation tests) during the strong motion, through a 2nd-order servo
                   response with a 0.6 in/s rate limit, back at x' before the final rest.
Quantisation grids and float32 storage as in the measured files.
"""
import math, random
import brfd_io as io

import os
DATA = os.environ.get('BRFD_DATA', os.path.join(os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..')), '..', 'shared', 'data', 'brfd'))
SEMI = ['harmonic0.015forward', 'harmonic0.015backward', 'harmonic0.03ea1forward',
        'harmonic0.03ea1backward', 'harmonic0.03ea2forward', 'harmonic0.03ea2backward']
EQ = ['KocaeliMCE', 'ImperialValleyDBE']
N = 15361


def harmonic(name):
    r = io.load('%s/semiactive/%s.json' % (DATA, name))
    return dict(kind='harmonic', source=name, x=r['x'], a1=r['a1'], a2=r['a2'],
                F_init=r['F'][0], src=r)


def _smooth(s, w):
    return io.moving_average(s, w)


def _interp(s, tq, dt):
    j = tq / dt
    k = int(math.floor(j))
    if k < 0:
        return s[0]
    if k >= len(s) - 1:
        return s[-1]
    f = j - k
    return s[k] * (1 - f) + s[k + 1] * f


def broadband(base_name, eq_name, seed):
    rng = random.Random(seed)
    r = io.load('%s/semiactive/%s.json' % (DATA, base_name))
    x0 = r['x']
    dt = io.DT
    # drum extremum near 3.5 s (inside the passive window of every semi-active test)
    i_s = min(range(int(3.2 / dt), int(3.7 / dt)), key=lambda i: x0[i])
    xs_m = _smooth(x0, 31)
    xs = xs_m[i_s]
    Tr, Td = 1.2, 1.0
    if eq_name == 'synthetic':
        return _broadband_synth(r, x0, i_s, xs, Tr, Td, rng, base_name)
    # earthquake strong-motion segment
    e = io.load('%s/earthquake-profiles/%s.json' % (DATA, eq_name))
    ex = _smooth(e['x'], 41)
    ev = io.central_diff(ex)
    vmax_i = max(range(len(ev)), key=lambda i: abs(ev[i]))
    # window around the strongest motion
    if eq_name.startswith('Kocaeli'):
        w0, w1 = 5.9, 12.0
    else:
        w0, w1 = 3.9, 9.8
    i0, i1 = int(w0 / dt), int(w1 / dt)
    seg = [a - ex[i0] for a in ex[i0:i1]]
    # end of segment: bring back toward a residual offset smoothly (taper of 0.4 s)
    sv = io.central_diff(seg)
    lam = rng.uniform(1.6, 2.0)                       # time stretch
    A = rng.uniform(4.0, 5.0) * lam / max(abs(a) for a in sv)   # peak drum speed 4-5 in/s
    seg_T = (len(seg) - 1) * dt * lam
    t_eq0 = i_s * dt + Tr + Td
    t_end_avail = (N - 1) * dt - 1.6      # keep >= 1.6 s of final rest
    if t_eq0 + seg_T > t_end_avail:
        seg_T = t_end_avail - t_eq0
    taper = 0.5
    x = []
    for i in range(N):
        t = i * dt
        if i <= i_s:
            val = x0[i]
        elif t < i_s * dt + Tr:
            u = (t - i_s * dt) / Tr
            val = xs * 0.5 * (1 + math.cos(math.pi * u))
        elif t < t_eq0:
            val = 0.0
        elif t < t_eq0 + seg_T:
            tl = (t - t_eq0) / lam
            val = A * _interp(seg, tl, dt)
            rem = t_eq0 + seg_T - t
            if rem < taper:   # hold the last value smoothly
                pass
        else:
            val = A * _interp(seg, seg_T / lam, dt)
        x.append(val)
    # smooth the joint at the end of the segment (cosine blend over `taper`)
    i_e = int((t_eq0 + seg_T) / dt)
    i_b = int((t_eq0 + seg_T - taper) / dt)
    xe = x[i_b]
    # end value: hold where it is at i_b, blended with the original path
    for i in range(i_b, min(N, i_e + 1)):
        u = (i - i_b) / max(1, i_e - i_b)
        w = 0.5 * (1 - math.cos(math.pi * u))
        x[i] = x[i] * (1 - w) + xe * w
    for i in range(i_e + 1, N):
        x[i] = xe
    return _finish(r, x0, i_s, x, t_eq0, seg_T, rng, base_name, eq_name, A, lam, Tr)


def _broadband_synth(r, x0, i_s, xs, Tr, Td, rng, base_name):
    """Random-phase broadband drum motion (12 components, 0.3-2 Hz, amplitudes ~ f^-0.5,
    envelope: 1 s rise, 4.5 s strong, exponential decay), peak drum speed 4-5 in/s."""
    dt = io.DT
    t_eq0 = i_s * dt + Tr + Td
    seg_T = (N - 1) * dt - 1.8 - t_eq0
    comps = []
    for k in range(12):
        f = math.exp(rng.uniform(math.log(0.3), math.log(2.0)))
        comps.append((f, rng.uniform(0.5, 1.0) * f ** -0.5, rng.uniform(0, 2 * math.pi)))
    def env(tl):
        if tl < 0:
            return 0.0
        if tl < 1.0:
            return 0.5 * (1 - math.cos(math.pi * tl))
        if tl < 5.5:
            return 1.0
        return math.exp(-(tl - 5.5) / 0.6)
    raw = []
    for i in range(N):
        t = i * dt
        if i <= i_s:
            raw.append(None); continue
        if t < i_s * dt + Tr:
            u = (t - i_s * dt) / Tr
            raw.append(xs * 0.5 * (1 + math.cos(math.pi * u))); continue
        tl = t - t_eq0
        if tl < 0:
            raw.append(0.0); continue
        val = env(min(tl, seg_T)) * sum(a * (math.sin(2 * math.pi * f * min(tl, seg_T) + ph) - math.sin(ph))
                                  for f, a, ph in comps)
        raw.append(val)
    # normalise the strong part to a peak drum speed of 4-5 in/s (and <= 0.95 in peak)
    i0 = int(t_eq0 / dt)
    seg = raw[i0:]
    sv = io.central_diff(seg)
    A = rng.uniform(4.0, 5.0) / max(abs(a) for a in sv)
    A = min(A, 0.95 / max(abs(a) for a in seg))
    x = [x0[i] if raw[i] is None else (raw[i] * A if i >= i0 else raw[i]) for i in range(N)]
    return _finish(r, x0, i_s, x, t_eq0, seg_T, rng, base_name, 'synthetic', A, 1.0, Tr)


def _finish(r, x0, i_s, x, t_eq0, seg_T, rng, base_name, eq_name, A, lam, Tr):
    dt = io.DT
    # small smoothing of the whole synthetic part (drive/servo bandwidth), then sensor
    xs2 = _smooth(x, 21)
    off = x0[0] - io.Q_X * round(x0[0] / io.Q_X)
    xq = []
    for i in range(N):
        if i <= i_s:
            xq.append(x0[i])
        else:
            val = xs2[i] + rng.gauss(0.0, 0.35 * io.Q_X)
            xq.append(io.f32(io.quant(val, io.Q_X, off)))
    # actuator commands during the strong motion: step holds and sine bursts (0.8-1.6 Hz)
    x10, x20 = r['a1'][0], r['a2'][0]
    mode = rng.choice(['one', 'two', 'both'])
    c1 = []; c2 = []
    t_a0 = t_eq0 + 0.3
    t_a1 = min(t_eq0 + seg_T, (N - 1) * dt - 2.0)
    steps = []
    t = t_a0
    while t < t_a1 - 0.6:
        hold = rng.uniform(0.6, 1.4)
        amp = rng.choice([-1, -1, 1]) * rng.uniform(0.012, 0.03)
        kind = rng.choice(['step', 'sine'])       # step hold, or a sine burst (harmonic tests)
        steps.append((t, min(t + hold, t_a1), amp, kind, rng.uniform(0.8, 1.6)))
        t += hold + rng.uniform(0.0, 0.5)
    for i in range(N):
        t = i * dt
        u = 0.0
        for (ta, tb, amp, kind, fq) in steps:
            if ta <= t < tb:
                if kind == 'step':
                    u = amp
                else:
                    u = amp * math.sin(2 * math.pi * fq * (t - ta)) * math.sin(math.pi * (t - ta) / (tb - ta))
        c1.append(u if mode in ('one', 'both') else 0.0)
        c2.append(u * (1.0 if mode == 'both' else 1.0) if mode in ('two', 'both') else 0.0)
    # servo: 2nd order, fn 6 Hz, zeta 0.8, rate limit 0.6 in/s
    def servo(c):
        wn = 2 * math.pi * 6.0; ze = 0.8
        y = 0.0; yd = 0.0; o = []
        h = dt / 4
        for i in range(N):
            for _ in range(4):
                ydd = wn * wn * (c[i] - y) - 2 * ze * wn * yd
                yd += h * ydd
                yd = max(-0.6, min(0.6, yd))
                y += h * yd
            o.append(y)
        return o
    y1 = servo(c1); y2 = servo(c2)
    a1 = []; a2 = []
    for i in range(N):
        if i == 0:
            a1.append(x10); a2.append(x20); continue
        a1.append(io.f32(io.quant(x10 + y1[i] + rng.gauss(0, 0.8 * io.Q_A), io.Q_A)))
        a2.append(io.f32(io.quant(x20 + y2[i] + rng.gauss(0, 0.8 * io.Q_A), io.Q_A)))
    return dict(kind='broadband', source='%s+%s' % (base_name, eq_name), x=xq, a1=a1, a2=a2,
                F_init=r['F'][0], src=r, actuator_mode=mode, eq_scale=A, eq_stretch=lam,
                t_rest=(i_s * dt + Tr, t_eq0), t_strong=(t_eq0, t_eq0 + seg_T))
