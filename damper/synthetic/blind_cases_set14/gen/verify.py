#!/usr/bin/env python3
"""Verify blind test set 14 (Python 3 standard library only).

  python3 gen/verify.py

Checks
  1. the base-model parameters of gen.py equal those of the model YAML;
  2. gen.py's base model reproduces `hybridsim damper predict --no-fit` on the six measured
     semi-active tests (max |dF|);
  3. every cases/tNN/{A,B}.json parses, has the keys/columns/dt of the measured files, a uniform time
     column, 6-26 s length, a start rest >= 0.2 s and an EXACT final rest >= 1.5 s (all inputs
     constant), a noise-free sample 0 (= key F0), and the velocity-column quirk (~1/125.4);
  4. every record: `damper predict --no-fit` equals gen.py's base model (max |dF| < 1e-6 kip);
     'none' trials: measured - tool prediction is white noise of the key's SD (RMS/SD in [0.9, 1.1]);
  5. every effect shape reduces exactly to the base model at p = 0;
  6. effect trials: the ratio RMS(F_effect - F_base)/noise recomputed from the files and the key is
     within 1 % of its target and in the weak/strong band, the observed force is F_effect + noise
     of the key's SD, and the trial plan (6 none, 3 per category with distinct shapes, 12/12) holds.
Last line: the summary.
"""
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import gen  # noqa: E402

TOOL = os.environ.get("HYBRIDSIM", "/work/runs/bin25/hybridsim")
CFG = os.environ.get("BRFD_CONFIG", "/work/runs/brfd-semiactive.yaml")
KEYS = ["data", "dt", "sampling freq", "displacement units", "time units", "friction force units",
        "actuator force units"]

failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL:", msg, flush=True)
    return cond


def tool_predict(path, tmp):
    out = os.path.join(tmp, os.path.basename(os.path.dirname(path)) + "_" +
                       os.path.basename(path)[:-5])
    r = subprocess.run([TOOL, "damper", "predict", "--no-fit", "--config", CFG, "--test", path,
                        "--out", out, "--no-figure"], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("tool failed on %s: %s" % (path, r.stderr[-500:]))
    csvs = glob.glob(os.path.join(out, "*_predict.csv"))
    rows = list(csv.DictReader(open(csvs[0])))
    return [float(x["predicted_force_kip"]) for x in rows], r.stdout + r.stderr


def yaml_numbers(path):
    txt = open(path).read()
    vals = {}
    for k in ["sigma0_kip_per_in", "sigma1_kip_s_per_in", "sigma2_kip_s_per_in", "fs_fwd_kip",
              "fs_bwd_kip", "fc_fwd_kip", "fc_bwd_kip", "vs_in_per_s", "fc_floor_kip"]:
        m = re.search(r"^\s*%s:\s*([-0-9.eE+]+)" % k, txt, re.M)
        vals[k] = float(m.group(1))
    for k in ["slopes_kip_per_in", "scaling"]:
        m = re.search(r"^\s*%s:\s*\[([^\]]*)\]" % k, txt, re.M)
        vals[k] = [float(x) for x in m.group(1).split(",")]
    return vals


def main():
    key = json.load(open(os.path.join(ROOT, "key.json")))
    tmp = tempfile.mkdtemp(prefix="blind14_verify_")

    # 1. parameters
    y = yaml_numbers(CFG)
    ours = {"sigma0_kip_per_in": gen.S0, "sigma1_kip_s_per_in": gen.S1, "sigma2_kip_s_per_in": gen.S2,
            "fs_fwd_kip": gen.FS_F, "fs_bwd_kip": gen.FS_B, "fc_fwd_kip": gen.FC_F,
            "fc_bwd_kip": gen.FC_B, "vs_in_per_s": gen.VS, "fc_floor_kip": gen.FC_FLOOR,
            "slopes_kip_per_in": gen.M, "scaling": gen.C}
    for k, v in ours.items():
        check(y[k] == v, "parameter %s: gen %s != yaml %s" % (k, v, y[k]))

    # 2. measured tests
    meas_max = 0.0
    for fn in gen.SRC_FILES:
        path = os.path.join(gen.SRC_DIR, fn)
        A = json.load(open(path))["data"]
        F = gen.base_force([r[1] for r in A], [r[4] for r in A], [r[5] for r in A], A[0][2])
        pt, _ = tool_predict(path, tmp)
        d = max(abs(a - b) for a, b in zip(F, pt))
        meas_max = max(meas_max, d)
        print("measured %-30s max|F_gen - F_tool| = %.2e kip" % (fn, d))
    check(meas_max < 1e-6, "base model vs tool on measured tests: %.3g kip" % meas_max)

    # reference format
    ref = json.load(open(os.path.join(gen.SRC_DIR, gen.SRC_FILES[0])))

    # 6a. plan
    ids = ["t%02d" % i for i in range(1, 31)]
    check(sorted(key) == ids, "key ids")
    cats = {}
    for t in ids:
        k = key[t]
        cats.setdefault(k["category"], []).append(k)
    check(len(cats.get("none", [])) == 6, "6 none trials")
    for c in gen.CATEGORIES:
        lst = cats.get(c, [])
        check(len(lst) == 3, "3 trials in %s" % c)
        check(len({k["shape"] for k in lst}) == len(lst), "distinct shapes in %s" % c)
        for k in lst:
            check(gen.SHAPES[k["shape"]][0] == c, "shape %s in category %s" % (k["shape"], c))
    st = [key[t]["strength"] for t in ids if key[t]["category"] != "none"]
    check(st.count("strong") == 12 and st.count("weak") == 12, "12 strong / 12 weak")

    # 5. p = 0 reduction (on the first record of t01)
    A0 = json.load(open(os.path.join(ROOT, "cases", "t01", "A.json")))["data"]
    rec0 = gen.prep([r[1] for r in A0], [r[4] for r in A0], [r[5] for r in A0], A0[0][2])
    fb0 = gen.lugre_core(rec0["V"], rec0["G"], A0[0][2])
    red_max = 0.0
    for sh, v in gen.SHAPES.items():
        prm = dict(v[2])
        if sh.startswith("dir_"):
            for dn in ("forward", "backward"):
                prm["direction"] = dn
                f = gen.simulate(sh, rec0, 0.0, prm)
                red_max = max(red_max, max(abs(a - b) for a, b in zip(f, fb0)))
        else:
            f = gen.simulate(sh, rec0, 0.0, prm)
            red_max = max(red_max, max(abs(a - b) for a, b in zip(f, fb0)))
    check(red_max < 1e-12, "p = 0 reduction: %.3g" % red_max)

    syn_max = 0.0
    none_ratios = []
    eff_dev = []
    resid_ratios = []
    nrec = 0
    for t in ids:
        k = key[t]
        recs, bases, fobs = [], [], []
        for ri, rm in enumerate(k["records"]):
            path = os.path.join(ROOT, "cases", t, rm["file"])
            try:
                d = json.load(open(path))
            except Exception as e:  # noqa: BLE001
                check(False, "%s does not parse: %s" % (path, e))
                continue
            nrec += 1
            A = d["data"]
            n = len(A)
            # 3. format
            check(list(d.keys()) == KEYS, "%s keys" % path)
            for kk in KEYS[1:]:
                check(d[kk] == ref[kk], "%s %s" % (path, kk))
            check(all(len(r) == 8 for r in A), "%s: 8 columns" % path)
            check(all(isinstance(x, (int, float)) and math.isfinite(x) for r in A for x in r),
                  "%s finite numbers" % path)
            check(all(A[i][0] == i * gen.DT for i in range(n)), "%s time column" % path)
            dur = (n - 1) * gen.DT
            check(6.0 - 1e-9 <= dur <= 26.0 + 1e-9, "%s duration %.3f" % (path, dur))
            check(n == rm["n"], "%s length vs key" % path)
            D = [r[1] for r in A]
            X1 = [r[4] for r in A]
            X2 = [r[5] for r in A]
            F = [r[2] for r in A]
            nf = int(math.ceil(1.5 / gen.DT)) + 1
            for col in (D, X1, X2):
                check(len(set(col[-nf:])) == 1, "%s final exact rest" % path)
            ns = int(0.2 / gen.DT) + 1
            for col in (D, X1, X2):
                check(len(set(col[:ns])) == 1, "%s start rest" % path)
            check(F[0] == rm["F0_kip"], "%s sample 0 force = F0" % path)
            check(-1.0 <= F[0] <= 2.0, "%s F0 range" % path)
            V = gen.velocity(D)
            vc = [r[3] for r in A]
            num = sum(V[i] * vc[i + gen.VCOL_LAG] for i in range(n - gen.VCOL_LAG))
            den = sum(vc[i + gen.VCOL_LAG] ** 2 for i in range(n - gen.VCOL_LAG))
            check(120 < num / den < 131, "%s velocity-column quirk ratio %.1f" % (path, num / den))
            # 4. tool vs base
            rec = gen.prep(D, X1, X2, F[0])
            fb = gen.lugre_core(rec["V"], rec["G"], F[0])
            check(fb[0] == F[0], "%s base at sample 0" % path)
            pt, _ = tool_predict(path, tmp)
            dd = max(abs(a - b) for a, b in zip(fb, pt))
            syn_max = max(syn_max, dd)
            check(dd < 1e-6, "%s tool vs base %.3g" % (path, dd))
            recs.append(rec)
            bases.append(fb)
            fobs.append((F, pt))
        noise = k["noise_kip"]
        check(0.02 <= noise <= 0.06, "%s noise range" % t)
        if k["category"] == "none":
            res = [a - b for F, pt in fobs for a, b in zip(F[1:], pt[1:])]
            r = gen.rms(res) / noise
            none_ratios.append(r)
            check(0.9 <= r <= 1.1, "%s none: rms(meas - tool)/noise = %.3f" % (t, r))
            mean = sum(res) / len(res)
            check(abs(mean) < 5 * noise / math.sqrt(len(res)), "%s none: residual mean" % t)
            continue
        # 6. effect ratio
        prm = k["params"]
        diff, res = [], []
        for rec, fb, (F, pt) in zip(recs, bases, fobs):
            fe = gen.simulate(k["shape"], rec, k["p"], prm)
            check(fe[0] == F[0], "%s effect sample 0" % t)
            diff.extend(a - b for a, b in zip(fe, fb))
            res.extend(a - b for a, b in zip(F[1:], fe[1:]))
        ratio = gen.rms(diff) / noise
        tgt = k["target_ratio"]
        eff_dev.append(abs(ratio / tgt - 1))
        check(abs(ratio / tgt - 1) <= 0.01, "%s ratio %.4f vs target %.4f" % (t, ratio, tgt))
        check(abs(ratio - k["ratio"]) < 1e-6 * ratio, "%s ratio vs key" % t)
        band = (8.5, 11.5) if k["strength"] == "strong" else (2.7, 3.8)
        check(band[0] <= tgt <= band[1], "%s target in %s band" % (t, k["strength"]))
        rr = gen.rms(res) / noise
        resid_ratios.append(rr)
        check(0.9 <= rr <= 1.1, "%s rms(meas - F_effect)/noise = %.3f" % (t, rr))
        print("%s ratio %.3f target %.3f  resid/noise %.3f" % (t, ratio, tgt, rr), flush=True)

    status = "PASS" if not failures else "FAIL (%d problems)" % len(failures)
    print("SUMMARY: %s | %d trials, %d records parsed, format/rest/F0 OK | base vs `damper predict "
          "--no-fit`: measured tests max|dF| = %.1e kip, synthetic records max|dF| = %.1e kip | none: "
          "rms(meas-tool)/noise in [%.3f, %.3f] | effect ratios within %.2f %% of target | "
          "p=0 reduction max|dF| = %.1e" % (
              status, len(ids), nrec, meas_max, syn_max, min(none_ratios), max(none_ratios),
              100 * max(eff_dev), red_max))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
