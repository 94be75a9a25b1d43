"""Print the effect size (RMS and max of truth-with-effect minus truth-without) per shape."""
import sys, math, time
import brfd_model as bm, inputs, effects
import os
P = bm.read_config(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'configs', 'brfd-semiactive.yaml'))
ins = [inputs.harmonic('harmonic0.015forward'), inputs.harmonic('harmonic0.03ea2backward'),
       inputs.broadband('harmonic0.03ea1backward', 'KocaeliMCE', 11)]
for d in ins:
    d['v'] = bm.drum_velocity(d['x']); d['x10'] = d['a1'][0]; d['x20'] = d['a2'][0]
base = [bm.simulate(P, d) for d in ins]
only = sys.argv[1:] 
for cat, shapes in effects.SHAPES.items():
    if only and cat not in only: continue
    for sh, (pw, ps) in shapes.items():
        line = '%-16s %-18s' % (cat, sh)
        for lab, p in (('W', pw), ('S', ps)):
            for d, b in zip(ins, base):
                t = time.time()
                o = bm.simulate(P, d, dict(cat=cat, shape=sh, p=p))
                diff = [a - c for a, c in zip(o, b)]
                rms = math.sqrt(sum(e * e for e in diff) / len(diff))
                line += ' %s %.3f/%.2f' % (lab, rms, max(abs(e) for e in diff))
        print(line, flush=True)
