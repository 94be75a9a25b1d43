"""score4.py KEY RUNDIR [RUNDIR...] [--cases CASESDIR]: blind scoring (correct = exactly the hidden
category, or none for none, and for effects the printed NRMSE at least halved).

With --cases (the trial folders, tNN/{A,B}.json in the measured format, and a key giving each
trial's noise SD as noise_kip / noise_rms_kip), a right name whose gap was not halved is marked
'gap*' when halving was impossible: half the NRMSE before lies below the noise floor, the mean
over the records of noise SD / population SD of the force (the NRMSE of a perfect model). The
count stays the official one; the floor is context."""
import json, re, sys, collections, statistics
cases_dir = None
if '--cases' in sys.argv:
    i = sys.argv.index('--cases'); cases_dir = sys.argv[i + 1]; del sys.argv[i:i + 2]
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

def noise_floor(t, k):
    """Mean over the trial's records of noise SD / SD of the force column (column 3), or None."""
    sd = k.get('noise_kip', k.get('noise_rms_kip'))
    if cases_dir is None or sd is None: return None
    import glob, os
    fl = []
    for f in sorted(glob.glob(os.path.join(cases_dir, t, '*.json'))):
        force = [row[2] for row in json.load(open(f))['data']]
        fl.append(float(sd) / statistics.pstdev(force))
    return sum(fl) / len(fl) if fl else None
impossible = [0] * len(runs)
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
        mark = 'ok' if corr else ('gap' if named == cat else 'X')
        if mark == 'gap':
            fl = noise_floor(t, k)
            if fl is not None and 0.5 * b < fl:
                mark = 'gap* (floor %.4f)' % fl; impossible[i] += 1
        line += " | %-30s %.4f->%.4f %s" % (named[:30], b, a, mark)
    print(line)
for c in sorted(ncat): print(c, ncat[c], percat[c])
print('correct', tot, 'of', len(key), 'false_positive', fp)
if cases_dir is not None:
    print('right name, gap not halvable (half the NRMSE before below the noise floor):', impossible)
