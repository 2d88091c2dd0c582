"""Write the force-layout benchmark graph: 10,000 nodes, 40,000 edges with uniformly random
endpoints (no self-loops; repeated pairs are kept), from a fixed seed, stdlib only.

Writes data/graph_10k.csv (header `source,target`) and data/graph_10k.gv (the same graph in DOT,
every node declared so isolated ones are kept), next to this script.

Usage: python3 benches/make_graph.py
"""
import os
import random

NODES, EDGES, SEED = 10_000, 40_000, 20_051

here = os.path.dirname(os.path.abspath(__file__))
data = os.path.join(here, "data")
os.makedirs(data, exist_ok=True)
rng = random.Random(SEED)
edges = []
while len(edges) < EDGES:
    s, t = rng.randrange(NODES), rng.randrange(NODES)
    if s != t:
        edges.append((s, t))
with open(os.path.join(data, "graph_10k.csv"), "w") as f:
    f.write("source,target\n")
    for s, t in edges:
        f.write(f"{s},{t}\n")
with open(os.path.join(data, "graph_10k.gv"), "w") as f:
    f.write("graph G {\n")
    for v in range(NODES):
        f.write(f"  {v};\n")
    for s, t in edges:
        f.write(f"  {s} -- {t};\n")
    f.write("}\n")
print(f"wrote {NODES} nodes, {len(edges)} edges to {data}")
