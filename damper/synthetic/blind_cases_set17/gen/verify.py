#!/usr/bin/env python3
"""Checks for blind test set 17 (Python standard library only).

1. base model (gen.base_model) == `hybridsim damper predict --no-fit` on the six measured
   semi-active tests and on all 60 generated records, to CSV precision (8 significant
   digits), for the predicted force, the derived drum velocity and the kinetic friction;
2. every trial's strength ratio (RMS over both records of (F_effect - F_base) / noise sd),
   recomputed from the written records and key.json, lies in its band (0 for 'none');
3. the residual (record force - F_effect) has the key's noise sd and zero mean;
4. every record is 6-25 s long, starts at rest and ends with >= 1.5 s of rest;
5. design bookkeeping: 8 categories x 3 distinct shapes, 12 weak / 12 strong / 6 none,
   noise sd in [0.02, 0.06] kip, about 1/3 of records with actuator motion in the first second.
Last line: summary.

Usage: verify.py [--no-predict]   (env HYBRIDSIM, BRFD_CONFIG, BRFD_SEMIACTIVE_DIR)
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

HYBRIDSIM = os.environ.get("HYBRIDSIM", "/work/runs/binhead/hybridsim")
CONFIG = os.environ.get("BRFD_CONFIG", "/work/runs/brfd-semiactive.yaml")

fails = []
notes = []


def fail(msg):
    fails.append(msg)
    print("FAIL:", msg)


def tol(ref):
    a = abs(ref)
    if a == 0:
        return 1e-12
    return 0.6 * 10 ** (math.floor(math.log10(a)) - 7) + 1e-13


def predict_csv(path, tmp):
    out = os.path.join(tmp, "o")
    r = subprocess.run(["nice", HYBRIDSIM, "damper", "predict", "--no-fit", "--config", CONFIG,
                        "--test", path, "--out", out, "--no-figure"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise RuntimeError("predict failed on %s: %s" % (path, r.stdout[-500:]))
    name = os.path.splitext(os.path.basename(path))[0]
    with open(os.path.join(out, name + "_predict.csv")) as fh:
        rd = csv.reader(fh)
        head = next(rd)
        cols = {h: i for i, h in enumerate(head)}
        rows = [[float(q) for q in r] for r in rd]
    for fn in os.listdir(out):
        os.remove(os.path.join(out, fn))
    return cols, rows


def compare_base(path, rows, tmp, label):
    v, fc, F = gen.base_model(rows)
    cols, pr = predict_csv(path, tmp)
    if len(pr) != len(rows):
        fail("%s: predict wrote %d rows for %d" % (label, len(pr), len(rows)))
        return None
    worst = {}
    for name, mine in (("predicted_force_kip", F), ("drum_vel_in_per_s", v), ("kinetic_friction_kip", fc)):
        ci = cols[name]
        bad = 0
        emax = 0.0
        for k in range(len(pr)):
            ref = pr[k][ci]
            e = abs(mine[k] - ref)
            emax = max(emax, e)
            if e > tol(ref):
                bad += 1
        worst[name] = emax
        if bad:
            fail("%s: %s differs from predict beyond CSV precision at %d samples (max %.3g)" %
                 (label, name, bad, emax))
    return worst, F


def main():
    do_predict = "--no-predict" not in sys.argv
    key = json.load(open(os.path.join(ROOT, "key.json")))
    tmp = tempfile.mkdtemp(prefix="blind17v_")
    n_pred = 0
    maxerr = 0.0
    if do_predict:
        for name in gen.TESTS:
            path = os.path.join(gen.DATA_DIR, name)
            rows = json.load(open(path))["data"]
            w, _ = compare_base(path, rows, tmp, name)
            n_pred += 1
            maxerr = max(maxerr, w["predicted_force_kip"])
        print("measured tests: base model == predict --no-fit on %d tests (max |dF| %.2g kip)" % (n_pred, maxerr))

    # ---------------------------------------------------------------- trials
    cats = {}
    counts = {"weak": 0, "strong": 0, "none": 0}
    n_early = 0
    n_rec = 0
    meta_ref = None
    with open(os.path.join(gen.DATA_DIR, gen.TESTS[0])) as fh:
        meta_ref = {k: v for k, v in json.load(fh).items() if k != "data"}
    for tid in sorted(key):
        e = key[tid]
        counts[e["strength"]] += 1
        if e["category"] != "none":
            cats.setdefault(e["category"], set()).add(e["shape"])
            if gen.SHAPE_CATEGORY.get(e["shape"]) != e["category"]:
                fail("%s: shape %s not in category %s" % (tid, e["shape"], e["category"]))
        sd = e["noise_kip"]
        if not (0.02 <= sd <= 0.06):
            fail("%s: noise sd %.4f outside [0.02, 0.06]" % (tid, sd))
        Fe_all, Fb_all = [], []
        res = []
        for lab in "AB":
            path = os.path.join(ROOT, "cases", tid, lab + ".json")
            src = json.load(open(path))
            rows = src["data"]
            n_rec += 1
            if [k for k in src if k != "data"] != list(meta_ref) or \
                    any(src[k] != meta_ref[k] for k in meta_ref):
                fail("%s/%s: metadata keys differ from the measured files" % (tid, lab))
            if any(len(r) != 8 for r in rows):
                fail("%s/%s: rows without 8 columns" % (tid, lab))
            n = len(rows)
            dur = rows[-1][0] - rows[0][0]
            if not (6.0 <= dur <= 25.0):
                fail("%s/%s: duration %.2f s" % (tid, lab, dur))
            if any(abs(rows[k][0] - k * gen.DT) > 1e-12 for k in range(n)):
                fail("%s/%s: time column not uniform 1024 Hz" % (tid, lab))
            # rest at the end (>= 1.5 s) and at the start (>= 0.3 s)
            ke = n - int(1.5 / gen.DT) - 1
            for (k0, k1, what) in ((ke, n, "final"), (0, int(0.3 / gen.DT), "initial")):
                xs = [rows[k][1] for k in range(k0, k1)]
                a1 = [rows[k][4] for k in range(k0, k1)]
                a2 = [rows[k][5] for k in range(k0, k1)]
                if max(xs) - min(xs) > 0.0004 or max(a1) - min(a1) > 3e-5 or max(a2) - min(a2) > 3e-5:
                    fail("%s/%s: no %s rest (drum span %.5f in)" % (tid, lab, what, max(xs) - min(xs)))
            # actuator motion within the first second?
            a_t = None
            for k in range(n):
                if abs(rows[k][4] - rows[0][4]) > 0.002 or abs(rows[k][5] - rows[0][5]) > 0.002:
                    a_t = k * gen.DT
                    break
            if a_t is None:
                fail("%s/%s: actuators never move" % (tid, lab))
            elif a_t < 1.0:
                n_early += 1
            # base model vs predict
            if do_predict:
                w, Fb = compare_base(path, rows, tmp, "%s/%s" % (tid, lab))
                n_pred += 1
                maxerr = max(maxerr, w["predicted_force_kip"])
            else:
                Fb = gen.base_model(rows)[2]
            rec = gen.rec_from_rows(rows)
            Fe = gen.simulate(rec, e["shape"], e["p"], e["params"])
            Fe_all.append(Fe)
            Fb_all.append(Fb)
            res.extend(rows[k][2] - Fe[k] for k in range(1, n))
        ratio = gen.rms_ratio(Fe_all, Fb_all, sd)
        if abs(ratio - e["ratio"]) > 1e-6 * max(1.0, ratio):
            fail("%s: recomputed ratio %.6f != key %.6f" % (tid, ratio, e["ratio"]))
        if e["strength"] == "none":
            if ratio != 0.0:
                fail("%s: 'none' trial with ratio %.3g" % (tid, ratio))
        else:
            lo, hi = gen.WEAK if e["strength"] == "weak" else gen.STRONG
            if not (lo <= ratio <= hi):
                fail("%s: ratio %.3f outside %s band [%g, %g]" % (tid, ratio, e["strength"], lo, hi))
        m = sum(res) / len(res)
        s = math.sqrt(sum((q - m) ** 2 for q in res) / (len(res) - 1))
        if abs(s / sd - 1) > 0.03 or abs(m) > 4 * sd / math.sqrt(len(res)) + 1e-4:
            fail("%s: residual sd %.5f / mean %.5f vs noise sd %.5f" % (tid, s, m, sd))
        print("%s  %-6s ratio %6.3f  residual sd/noise %.4f  mean %+.5f" %
              (tid, e["strength"], ratio, s / sd, m))
    if len(key) != 30:
        fail("%d trials, expected 30" % len(key))
    if counts != {"weak": 12, "strong": 12, "none": 6}:
        fail("strength counts %s" % counts)
    if len(cats) != 8 or any(len(v) != 3 for v in cats.values()):
        fail("categories/shapes: %s" % {k: sorted(v) for k, v in cats.items()})
    if not (15 <= n_early <= 25):
        fail("%d of %d records with actuator motion in the first second" % (n_early, n_rec))
    print("records with actuator motion within the first second: %d of %d" % (n_early, n_rec))
    try:
        os.rmdir(os.path.join(tmp, "o"))
    except OSError:
        pass
    try:
        os.rmdir(tmp)
    except OSError:
        pass
    if fails:
        print("VERIFY FAIL: %d problem(s); first: %s" % (len(fails), fails[0]))
        sys.exit(1)
    print("VERIFY PASS: base == predict --no-fit on %d files (max |dF| %.2g kip), 30 trials "
          "(12 weak, 12 strong, 6 none) ratios in band, residual sd == noise sd, %d records 6-25 s "
          "with >= 1.5 s final rest" % (n_pred, maxerr, n_rec))


if __name__ == "__main__":
    main()
