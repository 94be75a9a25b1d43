#!/usr/bin/env python3
"""Blind synthetic test set 7 for the BRFD model-discrepancy tool.
Usage: python3 gen/gen.py [--seed 7007] [--out /work/blind7]
Deterministic from the seed; standard-library Python only."""
import argparse, json, math, os, random, struct, sys, time
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from base import velocity, DT
from effects import simulate

SRC = "/work/shared/data/brfd/semiactive"
FILES = ["harmonic0.015backward.json", "harmonic0.015forward.json",
         "harmonic0.03ea1backward.json", "harmonic0.03ea1forward.json",
         "harmonic0.03ea2backward.json", "harmonic0.03ea2forward.json"]
N = 15361
Q_X, Q_F, Q_A, Q_L1, Q_L2 = 5.8651e-5, 8.0049e-4, 2.384186e-6, 0.317842, 0.399649
VEL_COL_SCALE, VEL_COL_LAG = 125.42, 8     # quirk of the files' velocity column


def f32(v):
    return struct.unpack("f", struct.pack("f", v))[0]


def qz(v, q):
    return round(v / q) * q


def load(fn):
    d = json.load(open(os.path.join(SRC, fn)))["data"]
    return dict(x=[r[1] for r in d], f0=d[0][2], vcol=[r[3] for r in d],
                a1=[r[4] for r in d], a2=[r[5] for r in d], src=fn)


# ---------------------------------------------------------------- custom inputs
def custom_input(rng):
    """Drum: cosine half-cycles peak to peak (continuous velocity), passive window of >= 5
    half-cycles of ~+-1 in first, then varied amplitude/period, a hold at a peak mid-record and
    a hold at the end. Actuators: harmonic or trapezoidal-step moves after the passive window."""
    segs = [(0.0, 0.3)]
    amps = [0.5 * rng.uniform(0.8, 1.1)] + [rng.uniform(0.85, 1.1) for _ in range(5)]
    sgn = 1
    th = rng.uniform(0.85, 1.0)
    for a in amps:
        segs.append((sgn * a, th)); sgn = -sgn
    t_pass = sum(d for _, d in segs)
    t_hold = rng.uniform(8.0, 10.5)
    hold_len = rng.uniform(1.2, 2.4)
    t, held = t_pass, False
    prev = segs[-1][0]
    while t < 15.0 - 1.6:
        if not held and t >= t_hold:
            segs.append((prev, hold_len)); t += hold_len; held = True; continue
        a = rng.uniform(0.35, 1.2)
        tgt = sgn * a
        dur = max(0.45 * abs(tgt - prev), rng.uniform(0.35, 1.1)) if abs(tgt - prev) > 0 else 0.5
        dur = max(dur, abs(tgt - prev) * 0.5)   # peak speed <= ~pi in/s
        segs.append((tgt, dur)); t += dur; sgn = -sgn; prev = tgt
    # end hold fills the rest
    xs = []
    cur, t0 = 0.0, 0.0
    bounds = []
    for tgt, dur in segs:
        bounds.append((t0, t0 + dur, cur, tgt)); t0 += dur; cur = tgt
    j = 0
    for k in range(N):
        t = k * DT
        while j < len(bounds) and t > bounds[j][1]:
            j += 1
        if j >= len(bounds):
            xs.append(cur); continue
        ta, tb, p0, p1 = bounds[j]
        u = (t - ta) / (tb - ta)
        xs.append(0.5 * (p0 + p1) + 0.5 * (p0 - p1) * math.cos(math.pi * u))
    off = rng.uniform(-0.01, 0.01)
    x = [f32(qz(xx + off + rng.gauss(0, 8e-5), Q_X)) for xx in xs]
    # actuators
    x10, x20 = 0.655 + rng.uniform(-3e-6, 3e-6), 0.8559 + rng.uniform(-3e-6, 3e-6)
    t_act = t_pass + rng.uniform(0.2, 0.8)
    which = rng.choice([(1,), (2,), (1, 2)])
    kind = rng.choice(["harmonic", "steps"])
    moves = {1: [0.0] * N, 2: [0.0] * N}
    desc = {"actuators": list(which), "kind": kind, "t_start": round(t_act, 3)}
    for ai in which:
        if kind == "harmonic":
            amp = rng.choice([0.015, 0.02, 0.03]) * rng.choice([1, 1, -1])
            fr = rng.uniform(0.3, 0.9)
            dur = rng.uniform(4.0, 6.0)
            desc["a%d" % ai] = {"amp_in": amp, "freq_hz": round(fr, 3), "dur_s": round(dur, 2)}
            for k in range(N):
                t = k * DT - t_act
                if 0 <= t <= dur:
                    env = min(1.0, t / 0.5, (dur - t) / 0.5)
                    moves[ai][k] = amp * env * math.sin(2 * math.pi * fr * t)
        else:
            lev, ts = [], t_act
            levels = []
            for _ in range(rng.randint(3, 5)):
                levels.append((ts, rng.uniform(-0.03, 0.03)))
                ts += rng.uniform(0.8, 1.8)
            levels.append((ts, 0.0))
            ramp = rng.uniform(0.05, 0.15)
            desc["a%d" % ai] = {"steps": [(round(a, 2), round(b, 4)) for a, b in levels], "ramp_s": round(ramp, 3)}
            cur = 0.0
            for k in range(N):
                t = k * DT
                val = 0.0
                for (ta, lv), prevlv in zip(levels, [0.0] + [l for _, l in levels[:-1]]):
                    if t >= ta:
                        u = min(1.0, (t - ta) / ramp)
                        val = prevlv + (lv - prevlv) * 0.5 * (1 - math.cos(math.pi * u))
                moves[ai][k] = val
    a1 = [f32(qz(x10 + moves[1][k] + rng.gauss(0, 1.2e-6), Q_A)) for k in range(N)]
    a2 = [f32(qz(x20 + moves[2][k] + rng.gauss(0, 1.2e-6), Q_A)) for k in range(N)]
    v = velocity(x)
    vcol = [v[max(0, k - VEL_COL_LAG)] / VEL_COL_SCALE + rng.gauss(0, 4e-6) for k in range(N)]
    f0 = f32(qz(rng.uniform(-0.4, 0.9), Q_F))
    desc.update(t_passive_end=round(t_pass, 3), hold_s=round(hold_len, 2), hold_at_s=round(t_hold, 2))
    return dict(x=x, a1=a1, a2=a2, vcol=vcol, f0=f0, src="custom", desc=desc)


# ---------------------------------------------------------------- noise, load cells, writing
def noise(rng, n, rms, colour):
    if colour == "white":
        return [0.0] + [rng.gauss(0, rms) for _ in range(n - 1)]
    phi = colour
    sd = rms * math.sqrt(1 - phi * phi)
    y, out = rng.gauss(0, rms), [0.0]
    for _ in range(n - 1):
        y = phi * y + rng.gauss(0, sd)
        out.append(y)
    return out


def load_cells(rng, F):
    """Actuator load cells (lb): taut band carries ~F/C (Table 2), slack band ~30-40 lb plus chatter."""
    b1, b2 = rng.uniform(28, 40), rng.uniform(28, 40)
    l1, l2 = [], []
    y1 = y2 = 0.0
    for f in F:
        y1 = 0.9 * y1 + rng.gauss(0, 1.5)
        y2 = 0.9 * y2 + rng.gauss(0, 1.5)
        l1.append(qz(b1 + 472.0 * max(-f, 0) + 8.4 * max(f, 0) + y1 + rng.gauss(0, 1.0), Q_L1))
        l2.append(qz(b2 + 515.0 * max(f, 0) + 8.1 * max(-f, 0) + y2 + rng.gauss(0, 1.0), Q_L2))
    return l1, l2


def write_record(path, inp, F):
    rows = []
    for k in range(N):
        t = k * DT
        t = int(t) if t == int(t) else t
        rows.append([t, float(inp["x"][k]), float(F[k]), float(inp["vcol"][k]), float(inp["a1"][k]),
                     float(inp["a2"][k]), float(inp["l1"][k]), float(inp["l2"][k])])
    obj = {"data": rows, "dt": 0.0009765625, "sampling freq": 1024, "displacement units": "in",
           "time units": "s", "friction force units": "kip", "actuator force units": "lb"}
    with open(path, "w") as fh:
        json.dump(obj, fh)


# ---------------------------------------------------------------- effect catalogue
def effect_spec(cat, shape, rng):
    e = {"category": cat, "shape": shape}
    if cat == "backlash":
        if shape == "deadzone_gap":
            e.update(s_max=0.6, unit="total lost motion (in)")
        else:
            e.update(lam=round(rng.uniform(0.05, 0.15), 3), v_dir=0.02, s_max=0.95,
                     unit="friction deficit at reversal (fraction), recovered over travel lam (in)")
    elif cat == "residual_static":
        e["v_rest"] = 0.03
        if shape == "exp_relaxation":
            e.update(tau=round(rng.uniform(0.4, 1.5), 3), s_max=0.95, unit="relaxed fraction of the at-rest force")
        elif shape == "log_creep":
            e.update(tau0=round(rng.uniform(0.03, 0.15), 3), s_max=1.5, unit="kip per e-fold of rest time")
        else:
            e.update(f_set=round(rng.choice([-1, 1]) * rng.uniform(0.4, 1.2), 3),
                     tau=round(rng.uniform(0.5, 1.5), 3), s_max=1.0, unit="fraction of approach to f_set")
    elif cat == "actuator_lag":
        if shape == "second_order":
            e.update(zeta=round(rng.uniform(0.25, 0.5), 3), s_max=0.25, unit="1/wn (s)")
        else:
            e.update(s_max=0.6, unit="tau or delay (s)")
    elif cat == "asymmetry":
        e.update(s_max={"sigma0_dir": 3.0, "sigma2_dir": 0.5, "vs_dir": 2.0}[shape],
                 unit={"sigma0_dir": "sigma0_fwd/sigma0 - 1 (bwd = sigma0/(1+s))",
                       "sigma2_dir": "sigma2 +s fwd, -s bwd (kip s/in)",
                       "vs_dir": "vs_fwd/vs - 1 (bwd = vs/(1+s))"}[shape])
    elif cat == "velocity":
        if shape == "rate_state_log":
            e.update(sign=rng.choice([-1, 1]), v_ref=round(rng.uniform(0.1, 0.4), 3), s_max=0.3,
                     unit="Fc *= 1 + sign*s*ln(1+|v|/v_ref)")
        elif shape == "power_strengthening":
            e.update(n=round(rng.uniform(0.4, 0.7), 3), s_max=1.5, unit="Fc += s |v|^n (kip)")
        else:
            e.update(s_max=1.6, unit="Stribeck exponent = 2 - s")
    elif cat == "pretension":
        e.update(s_max={"saturating": 3.0, "hardening": 1.5, "static_scales": 2.0}[shape],
                 unit={"saturating": "dFc/(1+s|dFc|), 1/kip", "hardening": "dFc + s dFc|dFc|, 1/kip",
                       "static_scales": "Fs *= 1 + s (Fc/b - 1)"}[shape])
    elif cat == "self_energizing":
        if shape == "capstan_rotation":
            e.update(s_max=1.0, unit="g *= exp(s x sgn v), 1/in")
        else:
            e.update(E0=round(rng.uniform(15, 40), 1), tau_cool=round(rng.uniform(8, 25), 1), s_max=0.6,
                     unit="g *= 1 - s (1 - exp(-E/E0)), E dissipated energy (kip in) with cooling")
    elif cat == "transition_shape":
        if shape == "dahl_exponent":
            e.update(i_dir=rng.choice([-1, 1]), s_max=1.6, unit="Dahl exponent i = exp(i_dir*s)")
        elif shape == "elastoplastic":
            e.update(beta=round(rng.uniform(0.4, 0.8), 3), s_max=1.0,
                     unit="weight of the Dupont elasto-plastic path (z_ba = beta z_ss) in parallel with LuGre")
        else:
            e.update(spread=round(rng.uniform(0.3, 0.9), 3), s_max=1.0,
                     unit="weight of the Maxwell-slip (Iwan) path in parallel with LuGre")
    return e


def rms_diff(recs, eff, s):
    num, cnt = 0.0, 0
    for r in recs:
        Fe = simulate(r["x"], r["a1"], r["a2"], r["f0"], eff, s, v=r["v"])
        num += sum((a - b) ** 2 for a, b in zip(Fe, r["Fbase"]))
        cnt += len(Fe)
    return math.sqrt(num / cnt)


def calibrate(recs, eff, target):
    lo, hi = 0.0, eff["s_max"]
    r_hi = rms_diff(recs, eff, hi)
    if r_hi <= target:
        return hi, r_hi
    s, r = hi, r_hi
    for _ in range(12):
        s = 0.5 * (lo + hi)
        r = rms_diff(recs, eff, s)
        if abs(r - target) < 0.04 * target:
            break
        if r > target:
            hi = s
        else:
            lo = s
    return s, r


PLAN = [  # category, shapes (one per trial), input kinds (R = replay, C = custom)
    ("backlash", ["deadzone_gap", "engagement_ramp", "deadzone_gap"], "RRC"),
    ("residual_static", ["exp_relaxation", "log_creep", "drift_to_offset"], "CCC"),
    ("actuator_lag", ["first_order", "pure_delay", "second_order"], "RRR"),
    ("asymmetry", ["sigma0_dir", "sigma2_dir", "vs_dir"], "RRR"),
    ("velocity", ["rate_state_log", "power_strengthening", "stribeck_exponent"], "RRC"),
    ("pretension", ["saturating", "hardening", "static_scales"], "RRC"),
    ("self_energizing", ["capstan_rotation", "thermal_fade", "capstan_rotation"], "RRC"),
    ("transition_shape", ["dahl_exponent", "elastoplastic", "maxwell_slip"], "RRC"),
    ("none", ["", "", "", "", "", ""], "RRRRCC"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=7007)
    ap.add_argument("--out", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = ap.parse_args()
    t_start = time.time()
    rng = random.Random(args.seed)
    measured = [load(f) for f in FILES]
    trials = []
    for cat, shapes, kinds in PLAN:
        strengths = ["weak", "strong", rng.choice(["weak", "strong"])]
        rng.shuffle(strengths)
        for i, (shape, kind) in enumerate(zip(shapes, kinds)):
            trials.append(dict(category=cat, shape=shape or "none", input_kind=kind,
                               strength=None if cat == "none" else strengths[i % 3]))
    rng.shuffle(trials)
    noise_opts = [(0.02, "white"), (0.06, "white"), (0.02, 0.9), (0.06, 0.95)]
    key = {"seed": args.seed, "trials": []}
    lines = []
    for idx, tr in enumerate(trials):
        tid = "t%02d" % (idx + 1)
        trng = random.Random("%d-%s" % (args.seed, tid))
        if tr["input_kind"] == "R":
            fa, fb = trng.sample(range(6), 2)
            recs = [dict(measured[fa]), dict(measured[fb])]
            ik = "replay"
        else:
            recs = [custom_input(trng), custom_input(trng)]
            ik = "custom"
        for r in recs:
            r["v"] = velocity(r["x"])
            r["Fbase"] = simulate(r["x"], r["a1"], r["a2"], r["f0"], None, 0.0, v=r["v"])
        params = {}
        if tr["category"] != "none":
            # strength label below is set from the achieved effect RMS (weak < 0.35 kip)
            eff = effect_spec(tr["category"], tr["shape"], trng)
            target = trng.uniform(0.15, 0.3) if tr["strength"] == "weak" else trng.uniform(0.45, 0.8)
            s, achieved = calibrate(recs, eff, target)
            params = {k: v for k, v in eff.items() if k not in ("category", "shape")}
            params.update(s=round(s, 5), target_effect_rms_kip=round(target, 3),
                          effect_rms_kip=round(achieved, 4))
            for r in recs:
                r["Fclean"] = simulate(r["x"], r["a1"], r["a2"], r["f0"], eff, s, v=r["v"])
                r["eff_rms"] = math.sqrt(sum((a - b) ** 2 for a, b in zip(r["Fclean"], r["Fbase"])) / N)
            tr["strength"] = "weak" if achieved < 0.35 else "strong"
            params["effect_rms_A_B_kip"] = [round(recs[0]["eff_rms"], 4), round(recs[1]["eff_rms"], 4)]
        else:
            eff = None
            for r in recs:
                r["Fclean"] = r["Fbase"]
        nrms, colour = noise_opts[trng.randrange(4)]
        os.makedirs(os.path.join(args.out, "cases", tid), exist_ok=True)
        for lab, r in zip("AB", recs):
            nz = noise(trng, N, nrms, colour)
            F = [r["f0"]] + [f32(qz(r["Fclean"][k] + nz[k], Q_F)) for k in range(1, N)]
            r["l1"], r["l2"] = load_cells(trng, r["Fclean"])
            write_record(os.path.join(args.out, "cases", tid, lab + ".json"), r, F)
        params["inputs"] = {lab: (r["src"] if r["src"] != "custom" else r["desc"]) for lab, r in zip("AB", recs)}
        params["noise_colour"] = "white" if colour == "white" else "AR(1) phi=%s" % colour
        key["trials"].append(dict(id=tid, category=tr["category"], shape=tr["shape"],
                                  strength=tr["strength"] or "none", noise_rms_kip=nrms,
                                  input_kind=ik, parameters=params))
        lines.append("%s cases/%s/A.json cases/%s/B.json" % (tid, tid, tid))
        print(tid, tr["category"], tr["shape"], tr["strength"], ik, params.get("effect_rms_kip"),
              "%.1fs" % (time.time() - t_start), file=sys.stderr)
    with open(os.path.join(args.out, "key.json"), "w") as fh:
        json.dump(key, fh, indent=1)
    with open(os.path.join(args.out, "trials.txt"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("done in %.1f s" % (time.time() - t_start), file=sys.stderr)


if __name__ == "__main__":
    main()
