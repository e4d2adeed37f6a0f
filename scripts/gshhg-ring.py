#!/usr/bin/python3
"""Joins the shoreline pieces `gmt coast -M` dumps (GSHHG is stored in bins: a shoreline is cut at every bin
edge) into closed rings by their shared end points, and writes the longest ring as one GeoJSON LineString in
lon/lat (CRS84), coordinates as GMT printed them. Standard library only.

    gmt coast -R-7/-5.5/56.9/57.8 -Df -W -M -A0/1/1 > skye.txt
    scripts/gshhg-ring.py skye.txt gshhg_skye_lonlat > tests/data/gshhg_skye_lonlat.geojson
"""
import json
import sys


def pieces(path):
    out, cur = [], None
    with open(path) as f:
        for line in f:
            if line.startswith('>'):
                cur = []
                out.append(cur)
            elif line.strip() and cur is not None:
                x, y = line.split()[:2]
                cur.append((x, y))
    return [p for p in out if len(p) > 1]


def rings(segs):
    starts = {}
    for i, s in enumerate(segs):
        starts.setdefault(s[0], []).append(i)
    used, found = set(), []
    for i, s in enumerate(segs):
        if i in used:
            continue
        chain = list(s)
        used.add(i)
        while not (len(chain) > 3 and chain[-1] == chain[0]):
            nxt = [j for j in starts.get(chain[-1], []) if j not in used]
            if not nxt:
                break
            used.add(nxt[0])
            chain += segs[nxt[0]][1:]
        if len(chain) > 3 and chain[-1] == chain[0]:
            found.append(chain)
    return found


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: gshhg-ring.py GMT_COAST_DUMP NAME > OUT.geojson")
    found = rings(pieces(sys.argv[1]))
    if not found:
        sys.exit("gshhg-ring.py: no closed ring in " + sys.argv[1])
    ring = max(found, key=len)
    coords = [[float(x), float(y)] for x, y in ring]
    name = sys.argv[2]
    fc = {"type": "FeatureCollection", "name": name,
          "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}},
          "features": [{"type": "Feature",
                        "properties": {"name": name, "source": "GSHHG 2.3.7 full resolution (gmt coast -Df -W -M)"},
                        "geometry": {"type": "LineString", "coordinates": coords}}]}
    json.dump(fc, sys.stdout, separators=(',', ':'))
    sys.stdout.write('\n')
    print("%d rings, the longest %d vertices" % (len(found), len(coords)), file=sys.stderr)


main()
