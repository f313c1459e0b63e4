#!/usr/bin/env python3
"""Writes the lab objects experiments/lab_objects.json follows (experiments/objects/):
a drawing as a drawing program saves it, and a printed part as a slicer takes it.

  python3 scripts/make-lab-objects.py

- plate.svg: an A6-sized Inkscape-style document in mm (viewBox), a layer group turned and moved
  by a transform, holding a rounded pentagonal plate drawn with lines and arcs, a circular hole
  in it (a <circle>), and a label; the outline followed is the plate.
- knob.stl: a binary STL in metres of a knob 10 mm high: a disk of 52 mm with three flats cut 20
  mm from its centre, extruded (outward-facing triangles, the caps fanned from the centre).
"""
import math
import pathlib
import struct

here = pathlib.Path(__file__).resolve().parent.parent / "experiments" / "objects"
here.mkdir(parents=True, exist_ok=True)


def plate_svg():
    # A pentagon of circumradius 30 mm with its corners rounded by 6 mm arcs.
    r, rounding, n = 30.0, 6.0, 5
    corners = [(r * math.cos(2 * math.pi * k / n - math.pi / 2), r * math.sin(2 * math.pi * k / n - math.pi / 2))
               for k in range(n)]
    d = []
    for k in range(n):
        p, q, s = corners[k - 1], corners[k], corners[(k + 1) % n]
        # Points `rounding` from the corner along each side, joined by an arc.
        def towards(a, b, dist):
            length = math.hypot(b[0] - a[0], b[1] - a[1])
            return (a[0] + (b[0] - a[0]) * dist / length, a[1] + (b[1] - a[1]) * dist / length)
        a, b = towards(q, p, rounding), towards(q, s, rounding)
        d.append(("M" if k == 0 else "L") + f" {a[0]:.4f},{a[1]:.4f}")
        d.append(f"A 8,8 0 0 1 {b[0]:.4f},{b[1]:.4f}")
    d.append("Z")
    text = f"""<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
     width="105mm" height="148mm" viewBox="0 0 105 148" version="1.1">
  <title>pentagonal plate, 60 mm across its corners, rounded</title>
  <g inkscape:groupmode="layer" inkscape:label="plate" id="layer1"
     transform="translate(52.5 74) rotate(12)">
    <path id="plate" style="fill:#cccccc;stroke:#000000;stroke-width:0.3" d="{' '.join(d)}"/>
    <circle id="hole" cx="0" cy="0" r="6" style="fill:#ffffff"/>
    <text x="-10" y="20" style="font-size:4px">PLATE</text>
  </g>
</svg>
"""
    (here / "plate.svg").write_text(text)


def knob_stl():
    radius, flat, height, steps = 26.0, 20.0, 10.0, 120
    outline = []
    for i in range(steps):
        a = 2 * math.pi * i / steps
        x, y = radius * math.cos(a), radius * math.sin(a)
        # Three flats, 120 degrees apart: a point beyond a flat's line moves onto it.
        for f in range(3):
            fa = 2 * math.pi * f / 3 + math.pi / 2
            nx, ny = math.cos(fa), math.sin(fa)
            excess = x * nx + y * ny - flat
            if excess > 0:
                x, y = x - excess * nx, y - excess * ny
        outline.append((x, y))
    tris = []
    n = len(outline)
    for i in range(n):
        a, b = outline[i], outline[(i + 1) % n]
        tris.append(((0, 0, 0), (b[0], b[1], 0), (a[0], a[1], 0)))
        tris.append(((0, 0, height), (a[0], a[1], height), (b[0], b[1], height)))
        tris.append(((a[0], a[1], 0), (b[0], b[1], 0), (b[0], b[1], height)))
        tris.append(((a[0], a[1], 0), (b[0], b[1], height), (a[0], a[1], height)))
    with open(here / "knob.stl", "wb") as out:
        out.write(b"knob, 52 mm with three flats, 10 mm high; metres".ljust(80, b" "))
        out.write(struct.pack("<I", len(tris)))
        for t in tris:
            out.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                out.write(struct.pack("<3f", *(c / 1000.0 for c in p)))
            out.write(struct.pack("<H", 0))


plate_svg()
knob_stl()
print(f"wrote {here / 'plate.svg'} and {here / 'knob.stl'}")
