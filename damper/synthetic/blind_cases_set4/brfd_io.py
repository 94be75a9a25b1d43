"""I/O helpers: read measured BRFD semi-active JSON files and write records in exactly
the same format (8 columns, units kip/in/s/lb, quirks reproduced).

Measured-format facts found by inspecting /work/shared/data/brfd/semiactive/*.json:
  * 15361 rows, dt = 1/1024 s, time written as an int when it is integral (0, 1, ..., 15).
  * friction force (kip) sits on an integer grid of q_F = 0.00080088 kip.
  * drum displacement (in) on a grid of ~5.88e-5 in (values are float32).
  * actuator positions (in) on a grid of 2.4e-6 in (float32).
  * actuator forces (lb) on grids of 0.3179 lb (act. 1) and 0.3997 lb (act. 2).
  * the velocity column is NOT in in/s: it is a smoothed derivative of the displacement,
    delayed ~7 samples and divided by ~125.4, plus small coloured noise.
"""
import json, math, struct

DT = 1.0 / 1024.0
Q_F = 0.000800879966       # kip, force grid
Q_X = 5.880002e-05          # in, displacement grid
Q_A = 2.4e-06               # in, actuator position grid
Q_F1 = 0.31790              # lb
Q_F2 = 0.39970              # lb
VEL_DIV = 125.4             # velocity column divisor (quirk)
VEL_LAG = 7                 # samples
VEL_WIN = 21                # moving-average window of the velocity column

KEYS_TAIL = [("dt", 0.0009765625), ("sampling freq", 1024), ("displacement units", "in"),
             ("time units", "s"), ("friction force units", "kip"), ("actuator force units", "lb")]


def f32(v):
    return struct.unpack('f', struct.pack('f', v))[0]


def load(path):
    with open(path) as fh:
        d = json.load(fh)
    cols = [list(c) for c in zip(*d["data"])]
    names = ["t", "x", "F", "vel", "a1", "a2", "f1", "f2"]
    return dict(zip(names, cols))


def quant(v, q, off=0.0):
    return off + q * round((v - off) / q)


def time_value(i):
    t = i * DT
    return int(t) if t == int(t) else t


def write(path, rec):
    """rec: dict with lists t (ignored, regenerated), x, F, vel, a1, a2, f1, f2."""
    n = len(rec["x"])
    rows = []
    for i in range(n):
        rows.append([time_value(i), rec["x"][i], rec["F"][i], rec["vel"][i], rec["a1"][i],
                     rec["a2"][i], rec["f1"][i], rec["f2"][i]])
    obj = {"data": rows}
    for k, v in KEYS_TAIL:
        obj[k] = v
    with open(path, "w") as fh:
        json.dump(obj, fh)


def moving_average(s, w):
    n = len(s); h = w // 2
    ps = [0.0]
    for v in s:
        ps.append(ps[-1] + v)
    out = []
    for i in range(n):
        a = max(0, i - h); b = min(n, i + h + 1)
        out.append((ps[b] - ps[a]) / (b - a))
    return out


def central_diff(x):
    n = len(x)
    v = [0.0] * n
    for i in range(1, n - 1):
        v[i] = (x[i + 1] - x[i - 1]) / (2 * DT)
    v[0] = (x[1] - x[0]) / DT
    v[-1] = (x[-1] - x[-2]) / DT
    return v


def velocity_column(x, rng):
    """Reproduce the measured quirk: delayed smoothed derivative / ~125.4 + AR(1) noise."""
    n = len(x)
    s = moving_average(central_diff(x), VEL_WIN)
    out = []
    e = 0.0
    phi = 0.80
    sig = 5.7e-5 * math.sqrt(1 - phi * phi)
    for i in range(n):
        j = max(0, i - VEL_LAG)
        e = phi * e + rng.gauss(0.0, sig)
        out.append(s[j] / VEL_DIV + e)
    return out
