#!/usr/bin/env python3
"""Import cycles between files of the workbench (src/).

Run from the repository root: python3 scripts/import_cycles.py. Builds the
file-level import graph of src/: edges from `crate::a::b` paths (and
unqualified `a::b` paths where `a` is a top-level module), `super::` paths.
Reports strongly connected components (import cycles of any length)."""
import re, os, glob
files = glob.glob('src/**/*.rs', recursive=True)
top = {os.path.basename(p)[:-3] if p.endswith('.rs') else os.path.basename(p) for p in glob.glob('src/*')} - {'lib','main'}
def resolve(segs):
    base='src'; f=None
    for seg in segs:
        if os.path.exists(f'{base}/{seg}.rs'): f=f'{base}/{seg}.rs'; base=f'{base}/{seg}'
        elif os.path.exists(f'{base}/{seg}/mod.rs'): f=f'{base}/{seg}/mod.rs'; base=f'{base}/{seg}'
        else: break
    return f
deps={}
for f in files:
    text='\n'.join(l for l in open(f).read().split('\n') if not l.strip().startswith('//'))
    text=re.sub(r'#\[cfg\(test\)\]\s*mod tests.*', '', text, flags=re.S)
    d=set()
    local=set(re.findall(r'\bmod ([a-z_]+)', text))
    for m in re.finditer(r'(?<![A-Za-z_:])(crate::|super::)?((?:[a-z_]+::)*[a-z_]+)', text):
        pre, path = m.group(1), m.group(2).split('::')
        if pre=='crate::': g=resolve(path)
        elif pre=='super::':
            dirn=os.path.dirname(f) if not f.endswith('mod.rs') else os.path.dirname(os.path.dirname(f))
            rel=[s for s in dirn[4:].split('/') if s] if dirn!='src' else []
            g=resolve(rel+path)
        elif len(path)>1 and path[0] in top and path[0] not in local: g=resolve(path)
        else: g=None
        if g and g!=f: d.add(g)
    deps[f]=d
# Tarjan
idx={}; low={}; st=[]; on=set(); sccs=[]; c=[0]
def sc(v):
    idx[v]=low[v]=c[0]; c[0]+=1; st.append(v); on.add(v)
    for w in deps.get(v,()):
        if w not in idx: sc(w); low[v]=min(low[v],low[w])
        elif w in on: low[v]=min(low[v],idx[w])
    if low[v]==idx[v]:
        comp=[]
        while True:
            w=st.pop(); on.discard(w); comp.append(w)
            if w==v: break
        if len(comp)>1: sccs.append(comp)
for v in deps:
    if v not in idx: sc(v)
for s in sccs: print('cycle:', ' '.join(sorted(s)))
print('import cycles:', len(sccs))
raise SystemExit(1 if sccs else 0)
