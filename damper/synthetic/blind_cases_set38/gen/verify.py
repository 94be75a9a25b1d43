#!/usr/bin/env python3
"""Verify blind set 38: layout, replica == black box, 'none' = base + noise exactly, effect
trials = truth(key params) + noise exactly and on their strength targets. Ends with
VERIFY PASS or the list of failures."""
import csv
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import model  # noqa: E402
import records  # noqa: E402
from shapes import SHAPES, CATEGORIES  # noqa: E402

ROOT = os.path.dirname(HERE)
BB = "/work/runs/binhead/hybridsim"
CONFIG = "/work/main/configs/brfd-semiactive.yaml"
KEYS = ["data", "dt", "sampling freq", "displacement units", "time units",
        "friction force units", "actuator force units"]
STRONG = (8.5, 11.5)
WEAK = (2.7, 3.8)
fails = []


def fail(msg):
    fails.append(msg)
    print("FAIL:", msg)


def half_ulp8(y):
    """Half a unit in the 8th significant digit (the CSV's rounding)."""
    if y == 0:
        return 5e-13
    return 0.5 * 10 ** (math.floor(math.log10(abs(y))) - 7)


def check_layout(tid, name, obj):
    if list(obj.keys()) != KEYS:
        fail("%s/%s keys %s" % (tid, name, list(obj.keys())))
    for k, v in records.META.items():
        if obj.get(k) != v:
            fail("%s/%s meta %s=%r" % (tid, name, k, obj.get(k)))
    d = obj["data"]
    n = len(d)
    if not (9 * 1024 <= n - 1 <= 25 * 1024):
        fail("%s/%s duration %.3f s" % (tid, name, (n - 1) / 1024))
    for i, r in enumerate(d):
        if len(r) != 8:
            fail("%s/%s row %d has %d columns" % (tid, name, i, len(r)))
            break
        if r[0] != i / 1024:
            fail("%s/%s time column at %d" % (tid, name, i))
            break
        if any(not isinstance(u, (int, float)) or u != u or abs(u) == float("inf") for u in r):
            fail("%s/%s non-finite at %d" % (tid, name, i))
            break
    x = [r[1] for r in d]
    F = [r[2] for r in d]
    a1 = [r[4] for r in d]
    a2 = [r[5] for r in d]
    if max(abs(u) for u in x) > 1.3:
        fail("%s/%s |disp| %.4f > 1.3" % (tid, name, max(abs(u) for u in x)))
    v = model.drum_velocity(x)
    if max(abs(u) for u in v) > 4.0:
        fail("%s/%s speed %.3f > 4 in/s" % (tid, name, max(abs(u) for u in v)))
    tr = max(max(abs(u - a1[0]) for u in a1), max(abs(u - a2[0]) for u in a2))
    if tr > 0.06:
        fail("%s/%s actuator travel %.4f > 0.06" % (tid, name, tr))
    tail = x[-int(1.5 * 1024):]
    if max(tail) - min(tail) > 0.002:
        fail("%s/%s no final rest" % (tid, name))
    # force on the measured quantisation grid (k * q, float32-rounded)
    worst = max(abs(f / records.Q_FORCE - round(f / records.Q_FORCE)) for f in F)
    if worst > 1e-3:
        fail("%s/%s force off grid (%.2e steps)" % (tid, name, worst))
    # velocity column quirk (~1/125 of in/s)
    num = sum(vi * r[3] for vi, r in zip(v, d))
    den = sum(r[3] * r[3] for r in d)
    fac = num / den if den > 0 else 0
    if not (110 < fac < 140):
        fail("%s/%s velocity-column factor %.1f" % (tid, name, fac))
    return x, F, a1, a2, tr, max(abs(u) for u in v)


def run_blackbox(path, outdir):
    cmd = [BB, "damper", "predict", "--config", CONFIG, "--no-fit", "--test", path,
           "--out", outdir, "--no-figure"]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    base = os.path.splitext(os.path.basename(path))[0]
    csvp = os.path.join(outdir, base + "_predict.csv")
    if not os.path.exists(csvp):
        return p.returncode, None
    with open(csvp) as fh:
        rows = list(csv.reader(fh))
    return p.returncode, [float(r[6]) for r in rows[1:]]


def main():
    t0 = time.time()
    with open(os.path.join(ROOT, "key.json")) as fh:
        key = json.load(fh)
    ids = ["t%02d" % k for k in range(1, 31)]
    if sorted(key) != ids:
        fail("key ids %s" % sorted(key))
    # ---- composition
    cats = {}
    nstr = {"strong": 0, "weak": 0, "none": 0}
    for tid in ids:
        e = key[tid]
        nstr[e["strength"]] += 1
        if e["category"] != "none":
            cats.setdefault(e["category"], []).append(e["shape"])
            if SHAPES[e["shape"]]["category"] != e["category"]:
                fail("%s shape/category mismatch" % tid)
        if not (0.02 <= e["noise_kip"] <= 0.06):
            fail("%s noise %.4f" % (tid, e["noise_kip"]))
    if nstr != {"strong": 12, "weak": 12, "none": 6}:
        fail("strength counts %s" % nstr)
    if sorted(cats) != sorted(CATEGORIES) or any(len(set(v)) != 3 for v in cats.values()):
        fail("categories/shapes %s" % cats)
    allsh = [s for v in cats.values() for s in v]
    if len(set(allsh)) != 24:
        fail("shapes not distinct")
    ok_case_dirs = sorted(os.listdir(os.path.join(ROOT, "cases")))
    if ok_case_dirs != ids:
        fail("case dirs %s" % ok_case_dirs)

    bb_worst = 0.0
    bb_worst_rel = 0.0
    segv = 0
    tmp = tempfile.mkdtemp(prefix="blind38v_")
    summary = []
    for tid in ids:
        e = key[tid]
        ss = 0.0
        nn = 0
        for name in ("A", "B"):
            path = os.path.join(ROOT, "cases", tid, name + ".json")
            if sorted(os.listdir(os.path.join(ROOT, "cases", tid))) != ["A.json", "B.json"]:
                fail("%s files %s" % (tid, os.listdir(os.path.join(ROOT, "cases", tid))))
            with open(path) as fh:
                obj = json.load(fh)
            x, F, a1, a2, tr, vmax = check_layout(tid, name, obj)
            n = len(F)
            rk = e["records"][name]
            if rk["samples"] != n:
                fail("%s/%s sample count vs key" % (tid, name))
            # ---- replica vs black box
            base = model.base_predict(x, a1, a2, F[0])
            od = os.path.join(tmp, tid + name)
            os.makedirs(od, exist_ok=True)
            rc, bb = run_blackbox(path, od)
            if rc != 0:
                segv += 1
            if bb is None or len(bb) != n:
                fail("%s/%s black box output missing/short (rc=%s)" % (tid, name, rc))
            else:
                w = max(abs(base[i] - bb[i]) / half_ulp8(bb[i]) for i in range(n))
                wr = max(abs(base[i] - bb[i]) / max(abs(bb[i]), 1e-3) for i in range(n))
                bb_worst = max(bb_worst, w)
                bb_worst_rel = max(bb_worst_rel, wr)
                if w > 1.01:
                    fail("%s/%s replica differs from black box by %.2f CSV half-ulps" % (tid, name, w))
            # ---- noise regeneration
            nrng = random.Random(rk["noise_seed"])
            noise = [nrng.gauss(0.0, e["noise_kip"]) for _ in range(n)]
            if F[0] != records.quant(rk["F_init_kip"] + noise[0], records.Q_FORCE) or F[0] != rk["F0_kip"]:
                fail("%s/%s first sample (initial condition) mismatch" % (tid, name))
            if e["category"] == "none":
                truth = base
            else:
                truth = model.simulate(x, a1, a2, F[0], e["shape"], e["params_exact"])
                if e["params_exact"]["amp"] > e["amp_bound"] + 1e-12 or e["params_exact"]["amp"] < 0:
                    fail("%s amplitude %.4g outside [0, %.4g]" % (tid, e["params_exact"]["amp"], e["amp_bound"]))
                q0 = dict(e["params_exact"])
                q0["amp"] = 0.0
                z0 = model.simulate(x, a1, a2, F[0], e["shape"], q0)
                if max(abs(z0[i] - base[i]) for i in range(n)) > 1e-9:
                    fail("%s/%s effect does not vanish at zero amplitude" % (tid, name))
            bad = sum(1 for i in range(1, n) if F[i] != records.quant(truth[i] + noise[i], records.Q_FORCE))
            if bad:
                fail("%s/%s %d samples != quant(truth + noise)" % (tid, name, bad))
            if e["category"] == "none" and bb is not None and len(bb) == n:
                # independent of the replica: record - black box is the noise (within a grid step)
                worst = max(abs(F[i] - bb[i] - noise[i]) for i in range(1, n))
                if worst > records.Q_FORCE / 2 + 1e-6:
                    fail("%s/%s record - black box - noise = %.2e" % (tid, name, worst))
            ss += sum((truth[i] - base[i]) ** 2 for i in range(n))
            nn += n
        ratio = math.sqrt(ss / nn) / e["noise_kip"]
        if e["category"] == "none":
            if ratio != 0.0:
                fail("%s none trial ratio %.3g" % (tid, ratio))
        else:
            lo, hi = STRONG if e["strength"] == "strong" else WEAK
            if abs(ratio / e["target"] - 1) > 1e-3 or not (lo <= ratio <= hi) or not (lo <= e["target"] <= hi):
                fail("%s ratio %.4f target %.4f band %s" % (tid, ratio, e["target"], (lo, hi)))
            if abs(ratio - e["ratio"]) > 1e-9 * max(1.0, ratio):
                fail("%s ratio %.6f != key %.6f" % (tid, ratio, e["ratio"]))
        summary.append((tid, ratio))
    print("trials checked: %d; records: %d" % (len(ids), 2 * len(ids)))
    print("replica vs black box: max |diff| = %.3f CSV half-ulps (8 significant digits); "
          "max relative diff (|F| floored at 1e-3 kip) = %.2e" % (bb_worst, bb_worst_rel))
    print("black box exit code 139 (segfault after writing its CSV) on %d of %d runs" % (segv, 2 * len(ids)))
    print("composition: 6 none, 12 strong, 12 weak; 8 categories x 3 distinct shapes")
    print("verify.py done in %.1f s" % (time.time() - t0))
    if fails:
        print("VERIFY FAILED: %d failure(s)" % len(fails))
        for f in fails:
            print("  -", f)
        sys.exit(1)
    print("VERIFY PASS")


if __name__ == "__main__":
    main()
