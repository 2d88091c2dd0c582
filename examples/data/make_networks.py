"""Writes the network and hierarchy examples from the `vega-datasets` npm package (BSD-3-Clause).

Usage: npm install --no-save vega-datasets@2 && python3 make_networks.py node_modules/vega-datasets/data

- flare.json, flare-dependencies.json: the Flare visualization toolkit's class hierarchy
  (id, parent, name, size in bytes) and its import dependencies (source/target ids), as published.
- miserables-nodes.csv / miserables-links.csv: co-occurrence of the characters of Les Misérables
  (Knuth, The Stanford GraphBase), split into a node table and an edge table.
- us-airports.csv / us-flights.csv: the 30 US airports with the most flights in the sample and the
  flight counts between them.
"""

import csv
import json
import shutil
import sys
from collections import Counter
from pathlib import Path

src = Path(sys.argv[1])
out = Path(__file__).parent

shutil.copy(src / "flare.json", out / "flare.json")
shutil.copy(src / "flare-dependencies.json", out / "flare-dependencies.json")

mis = json.loads((src / "miserables.json").read_text())
names = [n["name"] for n in mis["nodes"]]
with open(out / "miserables-nodes.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["name", "group"])
    for n in mis["nodes"]:
        w.writerow([n["name"], n["group"]])
with open(out / "miserables-links.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["source", "target", "scenes"])
    for link in mis["links"]:
        w.writerow([names[link["source"]], names[link["target"]], link["value"]])

routes = list(csv.DictReader(open(src / "flights-airport.csv")))
traffic = Counter()
for r in routes:
    traffic[r["origin"]] += int(r["count"])
    traffic[r["destination"]] += int(r["count"])
top = [code for code, _ in traffic.most_common(30)]
keep = set(top)
airports = {a["iata"]: a for a in csv.DictReader(open(src / "airports.csv"))}
with open(out / "us-airports.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["iata", "name", "city", "state", "latitude", "longitude", "flights"])
    for code in top:
        a = airports[code]
        w.writerow([code, a["name"], a["city"], a["state"], a["latitude"], a["longitude"], traffic[code]])
with open(out / "us-flights.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["origin", "destination", "flights"])
    for r in routes:
        if r["origin"] in keep and r["destination"] in keep:
            w.writerow([r["origin"], r["destination"], r["count"]])

# Flare's package dependencies: how many imports of classes in one package each other package
# makes (an edge from the providing package to the using one), for the layered layout.
flare = {n["id"]: n for n in json.loads((src / "flare.json").read_text())}


def flare_package(i):
    parts = []
    i = flare[i].get("parent")
    while i:
        parts.append(flare[i]["name"])
        i = flare[i].get("parent")
    return "/".join(reversed(parts[:-1])) or "flare"


imports = Counter()
for d in json.loads((src / "flare-dependencies.json").read_text()):
    # In this file `source` is the imported class and `target` the class importing it.
    provider, user = flare_package(d["source"]), flare_package(d["target"])
    if provider != user:
        imports[(provider, user)] += 1
with open(out / "flare-package-imports.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["provider", "user", "imports"])
    for (provider, user), count in sorted(imports.items()):
        w.writerow([provider, user, count])
