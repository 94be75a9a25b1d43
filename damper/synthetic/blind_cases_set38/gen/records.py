"""Record construction for blind set 38 (standard library only).

Drum strokes and actuator episodes are cut from the six measured semi-active tests in
/work/shared/data/brfd/semiactive/, scaled / time-stretched, and recombined.
"""
import json
import math
import os
import struct

DATA_DIR = "/work/shared/data/brfd/semiactive"
FILES = [
    "harmonic0.015backward.json", "harmonic0.015forward.json",
    "harmonic0.03ea1backward.json", "harmonic0.03ea1forward.json",
    "harmonic0.03ea2backward.json", "harmonic0.03ea2forward.json",
]
FS = 1024
DT = 1.0 / FS
META = {"dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in",
        "time units": "s", "friction force units": "kip", "actuator force units": "lb"}

# Quantisation grids estimated from the measured files (least squares on the value sets);
# values are then passed through float32 like the acquisition system's numbers.
Q_DISP = 5.891904e-05      # in
Q_FORCE = 0.00080087996    # kip
Q_ACT = 2.443808e-06       # in
Q_F1, O_F1 = 0.31793998, 0.01655988   # lb, actuator-1 load cell
Q_F2, O_F2 = 0.39989996, 0.13172664   # lb, actuator-2 load cell
VEL_COL_FACTOR = 125.39    # README quirk: velocity column = (in/s) / ~125.39

# Table 2 scaling factors, used to synthesise the band-tension (actuator load-cell) columns
C1, C2, C3, C4 = 119.68, 2.10, 1.94, 123.31


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def quant(x, q, off=0.0):
    return f32(round((x - off) / q) * q + off)


def smooth(a, w):
    n = len(a)
    out = [0.0] * n
    s = 0.0
    pre = [0.0]
    for v in a:
        s += v
        pre.append(s)
    for i in range(n):
        lo = max(0, i - w)
        hi = min(n, i + w + 1)
        out[i] = (pre[hi] - pre[lo]) / (hi - lo)
    return out


_CACHE = {}


def load_measured():
    if "m" in _CACHE:
        return _CACHE["m"]
    out = {}
    for f in FILES:
        with open(os.path.join(DATA_DIR, f)) as fh:
            d = json.load(fh)["data"]
        out[f] = d
    _CACHE["m"] = out
    return out


def extract_strokes():
    """Half-cycles (reversal to reversal) of the measured drum displacement, as normalised
    profiles u(k) in [0, 1] sampled at 1024 Hz (smoothed with a 51-sample moving average)."""
    if "s" in _CACHE:
        return _CACHE["s"]
    strokes = []
    for f, d in load_measured().items():
        x = [r[1] for r in d]
        xs = smooth(x, 25)
        n = len(xs)
        W = 200
        ext = []
        for i in range(W, n - W):
            seg = xs[i - W:i + W + 1]
            if xs[i] == max(seg) and xs[i] > 0.15:
                ext.append(i)
            elif xs[i] == min(seg) and xs[i] < -0.15:
                ext.append(i)
        m = []
        for i in ext:
            if m and i - m[-1] < 150:
                continue
            m.append(i)
        for a, b in zip(m, m[1:]):
            A = xs[b] - xs[a]
            if abs(A) < 0.4:
                continue
            u = [(xs[i] - xs[a]) / A for i in range(a, b + 1)]
            # enforce monotone non-decreasing profile (clip tiny reversals of the smoother)
            for i in range(1, len(u)):
                if u[i] < u[i - 1]:
                    u[i] = u[i - 1]
            u[-1] = 1.0
            pk = max(u[i + 1] - u[i] for i in range(len(u) - 1)) * FS  # per unit amplitude
            strokes.append({"file": f, "i0": a, "i1": b, "amp": A, "u": u, "pk": pk})
    _CACHE["s"] = strokes
    return strokes


def extract_episodes():
    """Actuator episodes: windows where either actuator deviates from its t=0 position by
    more than 1.5 mils, padded by 40 ms, as (d1, d2) deviation arrays (in), detrended so
    they start and end at zero."""
    if "e" in _CACHE:
        return _CACHE["e"]
    eps = []
    for f, d in load_measured().items():
        a1 = [r[4] - d[0][4] for r in d]
        a2 = [r[5] - d[0][5] for r in d]
        n = len(d)
        act = [max(abs(a1[i]), abs(a2[i])) > 0.0015 for i in range(n)]
        wins = []
        i = 0
        while i < n:
            if act[i]:
                j = i
                while j < n and act[j]:
                    j += 1
                if wins and i - wins[-1][1] < int(0.06 * FS):
                    wins[-1][1] = j
                else:
                    wins.append([i, j])
                i = j
            else:
                i += 1
        for s, e in wins:
            if e - s < int(0.2 * FS):
                continue
            s = max(0, s - 41)
            e = min(n - 1, e + 41)
            d1 = a1[s:e + 1]
            d2 = a2[s:e + 1]
            L = len(d1) - 1
            d1 = [d1[k] - (d1[0] + (d1[-1] - d1[0]) * k / L) for k in range(L + 1)]
            d2 = [d2[k] - (d2[0] + (d2[-1] - d2[0]) * k / L) for k in range(L + 1)]
            kind = "both" if "0.015" in f else ("ea1" if "ea1" in f else "ea2")
            eps.append({"file": f, "i0": s, "i1": e, "kind": kind, "d1": d1, "d2": d2})
    _CACHE["e"] = eps
    return eps


def interp(arr, pos):
    i = int(math.floor(pos))
    if i < 0:
        return arr[0]
    if i >= len(arr) - 1:
        return arr[-1]
    fr = pos - i
    return arr[i] * (1 - fr) + arr[i + 1] * fr


def build_record(rng, dur_target):
    """Return a dict with the noise-free drum path x_true, measured-like columns, and the
    structure description. rng: random.Random."""
    strokes = extract_strokes()
    episodes = extract_episodes()
    xpath = []
    segs = []
    pos = rng.uniform(-0.15, 0.15)
    # initial rest
    r0 = int(rng.uniform(0.25, 0.9) * FS)
    xpath += [pos] * r0
    segs.append(("rest", 0, r0))
    moving = []  # (start, end) sample ranges of strokes
    final_rest = rng.uniform(1.8, 3.5)
    while True:
        # one burst of 1-6 half-strokes
        nh = rng.randint(1, 6)
        direction = rng.choice([-1, 1])
        burst = []
        for h in range(nh):
            if h > 0 and len(xpath) / FS + final_rest >= dur_target - 0.5:
                break
            for _ in range(50):
                peak = direction * rng.uniform(0.25, 1.28)
                if abs(peak - pos) >= 0.35:
                    break
            else:
                peak = direction * 1.0
            st = rng.choice(strokes)
            L = peak - pos
            vpk = rng.uniform(0.8, 3.8)  # target peak speed (in/s)
            T = st["pk"] * ((len(st["u"]) - 1) / FS) * abs(L) / vpk  # seconds
            T = min(max(T, 0.25), 2.6)
            nS = int(round(T * FS))
            u = st["u"]
            m = len(u) - 1
            seg = [pos + L * interp(u, k * m / nS) for k in range(1, nS + 1)]
            # speed check
            sp = max(abs(seg[k + 1] - seg[k]) for k in range(len(seg) - 1)) * FS
            if sp > 3.95:
                fac = sp / 3.9
                nS = int(math.ceil(nS * fac))
                seg = [pos + L * interp(u, k * m / nS) for k in range(1, nS + 1)]
            s0 = len(xpath)
            xpath += seg
            moving.append((s0, len(xpath)))
            burst.append({"from": round(pos, 4), "to": round(peak, 4),
                          "src": "%s[%d:%d]" % (st["file"], st["i0"], st["i1"]),
                          "dur_s": round(nS / FS, 4)})
            pos = peak
            direction = -direction
        segs.append(("burst", burst))
        t_now = len(xpath) / FS
        if t_now + final_rest >= dur_target - 1.0:
            break
        if t_now + final_rest > 20.5:
            break
        rr = int(rng.uniform(0.3, 2.6) * FS)
        s0 = len(xpath)
        xpath += [pos] * rr
        segs.append(("rest", s0, len(xpath)))
    s0 = len(xpath)
    xpath += [pos] * int(final_rest * FS)
    segs.append(("final_rest", s0, len(xpath)))
    n = len(xpath)
    if n > 25 * FS:
        raise ValueError("too long")

    # actuator episodes, placed during strokes
    d1 = [0.0] * n
    d2 = [0.0] * n
    ep_desc = []
    nep = rng.randint(3, 6)
    busy = [False] * n
    tries = 0
    kinds_wanted = ["ea1", "ea2", "both"]
    rng.shuffle(kinds_wanted)
    while len(ep_desc) < nep and tries < 400:
        tries += 1
        want = kinds_wanted[len(ep_desc) % 3]
        pool = [e for e in episodes if e["kind"] == want or want == "combo"]
        ep = rng.choice(pool)
        stretch = rng.uniform(0.8, 1.6)
        mx = max(max(abs(v) for v in ep["d1"]), max(abs(v) for v in ep["d2"]))
        scale = rng.uniform(0.6, min(2.0, 0.058 / mx))
        swap = ep["kind"] != "both" and rng.random() < 0.35
        L = int(round((len(ep["d1"]) - 1) * stretch))
        mv = rng.choice(moving)
        if mv[1] - mv[0] < 0.3 * FS:
            continue
        st = rng.randint(mv[0], max(mv[0], mv[1] - L // 2))
        if st + L >= n - int(1.5 * FS) or any(busy[st:st + L + 1]):
            continue
        m = len(ep["d1"]) - 1
        a = ep["d2"] if swap else ep["d1"]
        b = ep["d1"] if swap else ep["d2"]
        for k in range(L + 1):
            d1[st + k] += scale * interp(a, k * m / L)
            d2[st + k] += scale * interp(b, k * m / L)
            busy[st + k] = True
        ep_desc.append({"src": "%s[%d:%d]" % (ep["file"], ep["i0"], ep["i1"]),
                        "t0_s": round(st / FS, 4), "dur_s": round(L / FS, 4),
                        "scale": round(scale, 4), "stretch": round(stretch, 4),
                        "swapped_actuators": swap})
    return {"x": xpath, "d1": d1, "d2": d2, "segs": segs, "episodes": ep_desc,
            "moving": moving}


def measured_columns(rng, rec, x1p, x2p):
    """Measured-like drum displacement, velocity column and actuator positions."""
    x = rec["x"]
    n = len(x)
    disp = [quant(x[i] + rng.gauss(0.0, 3.5e-5), Q_DISP) for i in range(n)]
    # velocity column (README quirk: ~1/125 of in/s), from the true path, lightly filtered
    vt = [0.0] * n
    for i in range(n):
        a = max(0, i - 1)
        b = min(n - 1, i + 1)
        vt[i] = (x[b] - x[a]) / ((b - a) * DT) if b > a else 0.0
    vt = smooth(vt, 6)
    vcol = [vt[i] / VEL_COL_FACTOR + rng.gauss(0.0, 1.5e-5) for i in range(n)]
    a1 = [quant(x1p + rec["d1"][i] + rng.gauss(0.0, 1.0e-6), Q_ACT) for i in range(n)]
    a2 = [quant(x2p + rec["d2"][i] + rng.gauss(0.0, 1.0e-6), Q_ACT) for i in range(n)]
    # the first row defines x'_1, x'_2: exactly the chosen initial positions
    a1[0] = quant(x1p, Q_ACT)
    a2[0] = quant(x2p, Q_ACT)
    return disp, vcol, a1, a2


def band_tension_columns(rng, F, p1, p2):
    """Synthetic actuator load-cell columns (lb) consistent with Table 2: the taut actuator
    carries |F|/C (C2 forward for actuator 2, C3 backward for actuator 1), the slack one
    |F|/C1 or |F|/C4, plus a small pre-tension offset and load-cell noise."""
    out1, out2 = [], []
    for f in F:
        fp = max(f, 0.0)
        fm = max(-f, 0.0)
        t1 = 1000.0 * (fm / C3 + fp / C1) + p1 + rng.gauss(0.0, 1.2)
        t2 = 1000.0 * (fp / C2 + fm / C4) + p2 + rng.gauss(0.0, 1.5)
        out1.append(quant(max(t1, 5.0), Q_F1, O_F1))
        out2.append(quant(max(t2, 5.0), Q_F2, O_F2))
    return out1, out2


def write_record(path, t_disp, force, vcol, a1, a2, f1, f2):
    n = len(force)
    rows = []
    for i in range(n):
        t = i / FS
        if t == int(t):
            t = int(t)
        rows.append([t, t_disp[i], force[i], vcol[i], a1[i], a2[i], f1[i], f2[i]])
    obj = {"data": rows}
    obj.update(META)
    with open(path, "w") as fh:
        json.dump(obj, fh)
