"""score4.py KEY RUNDIR [RUNDIR...]: blind scoring (correct = exactly the hidden category, or none
for none, and for effects the printed NRMSE at least halved)."""
import json, re, sys, collections
key = json.load(open(sys.argv[1]))
# Key formats of the blind sets: {id: trial} (set 4) or {"trials": [{"id"|"trial": ..., ...}]}
# (set 5); noise and input under either name.
if isinstance(key, dict) and isinstance(key.get('trials'), list):
    key = {k.get('id', k.get('trial')): k for k in key['trials']}
for k in key.values():
    k.setdefault('noise_rms_kip', k.get('noise_rms'))
    k.setdefault('input_kind', k.get('motion'))
runs = []
for d in sys.argv[2:]:
    res = {}
    for l in open(d + '/summary.txt'):
        t, rest = l.split(' ', 1)
        m = re.match(r'effects=(\S+) nrmse_before=(\S+) nrmse_after=(\S+)', rest)
        if m: res[t] = (m.group(1), float(m.group(2)), float(m.group(3)))
    runs.append(res)
tot = [0]*len(runs); fp = [0]*len(runs); named_any = [0]*len(runs)
percat = collections.defaultdict(lambda: [0]*len(runs)); ncat = collections.Counter()
for t in sorted(key, key=lambda t: (key[t]['category'], t)):
    k = key[t]; cat = k['category']; ncat[cat] += 1
    line = "%-16s %s %-6s %-5s %-9s %-26s" % (cat, t, k.get('strength'), k.get('noise_rms_kip'), str(k.get('input_kind'))[:9], str(k.get('shape'))[:26])
    for i, r in enumerate(runs):
        if t not in r:
            line += " | (missing)"; continue
        named, b, a = r[t]
        corr = (named == cat) if cat == 'none' else (named == cat and a <= 0.5*b)
        if cat == 'none' and named != 'none': fp[i] += 1
        tot[i] += corr; percat[cat][i] += corr
        line += " | %-30s %.4f->%.4f %s" % (named[:30], b, a, 'ok' if corr else ('gap' if named == cat else 'X'))
    print(line)
for c in sorted(ncat): print(c, ncat[c], percat[c])
print('correct', tot, 'of', len(key), 'false_positive', fp)
