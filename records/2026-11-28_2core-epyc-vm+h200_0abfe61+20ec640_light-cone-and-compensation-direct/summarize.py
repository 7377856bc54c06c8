import json,sys,glob,collections
d=sys.argv[1]; pat=sys.argv[2] if len(sys.argv)>2 else '%s-%d.jsonl'
res=collections.defaultdict(list)
for f in sorted(glob.glob(d+'/*.jsonl')):
    name=f.split('/')[-1][:-6]
    for line in open(f):
        j=json.loads(line)
        res[(j['scene'],name.rsplit('-',1)[0])].append((name.rsplit('-',1)[1],j['median_ms']['light_update'],j['stages_ms'].get('Compensation',0),j['median_ms']['full_update']))
for k in sorted(res):
    print(k, ' '.join('r%s: move %.1f comp %.1f full %.1f'%v for v in res[k]))
