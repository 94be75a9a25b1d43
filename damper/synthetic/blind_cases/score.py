import json,re,sys
key={k['trial']:k for k in json.load(open(__import__('os').path.join(__import__('os').path.dirname(__file__), 'key.json')))}
def load(d):
    res={}
    for l in open(d+'/summary.txt'):
        t,rest=l.split(' ',1)
        m=re.match(r'effects=(\S+) nrmse_before=(\S+) nrmse_after=(\S+)',rest)
        res[t]=(m.group(1),float(m.group(2)),float(m.group(3)))
    return res
runs=[load(d) for d in sys.argv[1:]]
tot=[0]*len(runs); fp=[0]*len(runs)
import collections
percat=collections.defaultdict(lambda:[0]*len(runs)); ncat=collections.Counter()
for t in sorted(key, key=lambda t:(key[t]['category'],t)):
    k=key[t]; cat=k['category']; ncat[cat]+=1
    line="%-16s %s %-6s %-4s %-6s"%(cat,t,k.get('strength'),k.get('noise_kip'),k.get('motion','')[:6])
    for i,r in enumerate(runs):
        named,b,a=r[t]
        corr=(named==cat) if cat=='none' else (named==cat and a<=0.5*b)
        if cat=='none' and named!='none': fp[i]+=1
        tot[i]+=corr; percat[cat][i]+=corr
        line+=" | %-28s %.4f->%.4f %s"%(named[:28],b,a,'ok' if corr else ('gap' if named==cat else 'X'))
    print(line)
for c in sorted(ncat): print(c, ncat[c], percat[c])
print('correct',tot,'of',len(key),'fp',fp)
