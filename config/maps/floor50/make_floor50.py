#!/usr/bin/env python3
"""Generates the 50 m x 50 m floor for the scale benchmark (floor50.pgm + floor50.yaml,
map_server trinary, 0.05 m cells) and its 1 km route of repeated loops
(route_1km.txt). Deterministic: running it again rewrites the same bytes.
Run from anywhere: python3 config/maps/floor50/make_floor50.py

Layout (world metres, origin at the bottom-left corner):
  - a grid of corridors 2 m wide with centre lines x = 5, 25, 45 and y = 5, 25, 45:
    an outer ring (160 m around) and a central cross;
  - four 18 x 18 m blocks between the corridors, each with a ring of offices 4.5 m
    deep (doors onto the corridors) around a core; offices along the outside walls;
  - corridor clutter (cabinets, pillars, bins, poles) and room furniture as in the office.
The route alternates two 160 m tours from (5, 5): A = the outer ring counter-clockwise,
B = a figure of eight through the central cross; A B A B A B then half of A: 1040 m.
"""

import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import map_gen  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SEED = 50050
SIZE_M = 50.0
CENTRES = (5.0, 25.0, 45.0)  # corridor centre lines, both axes
HALF_WIDTH_M = 1.0
ROOM_DEPTH_M = 4.5
ROUTE_CLEARANCE_M = 0.5

TOUR_A = [(5.0, 5.0), (45.0, 5.0), (45.0, 45.0), (5.0, 45.0), (5.0, 5.0)]
TOUR_B = [(5.0, 5.0), (25.0, 5.0), (25.0, 45.0), (45.0, 45.0), (45.0, 25.0), (5.0, 25.0),
          (5.0, 5.0)]
ROUTE = TOUR_A + (TOUR_B[1:] + TOUR_A[1:]) * 2 + TOUR_B[1:] + TOUR_A[1:3]
CLEARANCE_ROUTE = TOUR_A + TOUR_B[1:]  # every segment the route drives, once
# An 87 m tour: the south-west block's ring (80 m), closed, then 7 m more.
TOUR_SW = [(5.0, 5.0), (25.0, 5.0), (25.0, 25.0), (5.0, 25.0), (5.0, 5.0), (12.0, 5.0)]


def splits(rng, a, b, lo, hi):
    """Cut positions dividing [a, b] into pieces lo .. hi long (the last may be longer)."""
    cuts, s = [], a
    while b - s > hi:
        s += rng.uniform(lo, hi)
        if b - s < lo:
            break
        cuts.append(round(s / 0.05) * 0.05)
    return cuts


def room_row(g, rng, doors, rooms, walls, along, across):
    """A row of rooms along one corridor wall.

    along = (a, b): the span along the wall; across = (c0, c1): from the corridor wall c0
    into the rooms up to c1; `walls` = 'h' when the corridor wall is horizontal. Partition
    walls at irregular spacing, one door per room in the corridor wall.
    """
    a, b = along
    c0, c1 = across
    cuts = [a] + splits(rng, a, b, 3.0, 5.5) + [b]
    for s0, s1 in zip(cuts, cuts[1:]):
        if s0 != a:
            if walls == "h":
                g.vwall(s0, min(c0, c1), max(c0, c1))
            else:
                g.hwall(s0, min(c0, c1), max(c0, c1))
        d0 = rng.uniform(s0 + 0.4, s1 - 1.3)
        doors.append((walls, c0, d0, d0 + 0.9))
        if walls == "h":
            rooms.append((s0, min(c0, c1), s1, max(c0, c1)))
        else:
            rooms.append((min(c0, c1), s0, max(c0, c1), s1))


def main():
    rng = random.Random(SEED)
    g = map_gen.Grid(SIZE_M, SIZE_M, 0.05)
    lo, hi = CENTRES[0] - HALF_WIDTH_M, CENTRES[-1] + HALF_WIDTH_M  # 4 .. 46
    for c in (0.05, SIZE_M - 0.05):
        g.hwall(c, 0.0, SIZE_M)
        g.vwall(c, 0.0, SIZE_M)
    for c in (lo, hi):
        g.hwall(c, 0.0, SIZE_M)
        g.vwall(c, 0.0, SIZE_M)
    g.rect(lo + 0.05, lo + 0.05, hi - 0.05, hi - 0.05, map_gen.FREE)

    doors, rooms, corridor_walls = [], [], []
    # Offices along the outside walls (the band between the outer ring and the boundary).
    room_row(g, rng, doors, rooms, "h", (lo, hi), (lo, 0.1))
    room_row(g, rng, doors, rooms, "h", (lo, hi), (hi, SIZE_M - 0.1))
    room_row(g, rng, doors, rooms, "v", (lo, hi), (lo, 0.1))
    room_row(g, rng, doors, rooms, "v", (lo, hi), (hi, SIZE_M - 0.1))
    corridor_walls += [("h", lo, lo, hi, +1), ("h", hi, lo, hi, -1), ("v", lo, lo, hi, +1),
                       ("v", hi, lo, hi, -1)]

    # The four blocks, each a ring of offices around a core.
    edges = [(CENTRES[i] + HALF_WIDTH_M, CENTRES[i + 1] - HALF_WIDTH_M) for i in range(2)]
    for bx0, bx1 in edges:
        for by0, by1 in edges:
            g.hwall(by0, bx0 - 0.05, bx1 + 0.05)
            g.hwall(by1, bx0 - 0.05, bx1 + 0.05)
            g.vwall(bx0, by0, by1)
            g.vwall(bx1, by0, by1)
            ix0, ix1, iy0, iy1 = bx0 + ROOM_DEPTH_M, bx1 - ROOM_DEPTH_M, by0 + ROOM_DEPTH_M, \
                by1 - ROOM_DEPTH_M
            g.hwall(iy0, bx0, bx1)
            g.hwall(iy1, bx0, bx1)
            g.vwall(ix0, iy0, iy1)
            g.vwall(ix1, iy0, iy1)
            room_row(g, rng, doors, rooms, "h", (bx0, bx1), (by0, iy0))
            room_row(g, rng, doors, rooms, "h", (bx0, bx1), (by1, iy1))
            room_row(g, rng, doors, rooms, "v", (iy0, iy1), (bx0, ix0))
            room_row(g, rng, doors, rooms, "v", (iy0, iy1), (bx1, ix1))
            rooms.append((ix0, iy0, ix1, iy1))  # the core, reached from no corridor
            corridor_walls += [("h", by0, bx0, bx1, -1), ("h", by1, bx0, bx1, +1),
                               ("v", bx0, by0, by1, -1), ("v", bx1, by0, by1, +1)]
    for kind, c, a, b in doors:
        (g.hdoor if kind == "h" else g.vdoor)(c, a, b)

    map_gen.draw_corridor_clutter(g, rng, corridor_walls, doors, CLEARANCE_ROUTE,
                                  ROUTE_CLEARANCE_M)
    map_gen.draw_room_furniture(g, rng, rooms, doors, CLEARANCE_ROUTE, ROUTE_CLEARANCE_M)
    map_gen.check_clearance(g, CLEARANCE_ROUTE, 0.45)
    g.write(HERE, "floor50")
    map_gen.write_route(os.path.join(HERE, "route_1km.txt"), ROUTE, [
        "50 m x 50 m floor (floor50.yaml): tours A (outer ring) and B (figure of eight through",
        "the central cross) alternated, A B A B A B, then half of A.",
        "Generated by make_floor50.py; %.1f m of polyline (corners are rounded when driven)."
        % map_gen.route_length(ROUTE),
        "x_m y_m in the map frame; the robot starts on the first point facing the second."])
    map_gen.write_route(os.path.join(HERE, "route_tour.txt"), TOUR_SW, [
        "50 m x 50 m floor (floor50.yaml): the south-west block's corridor ring once",
        "counter-clockwise, then 7 m of its first corridor again.",
        "Generated by make_floor50.py; %.1f m of polyline (corners are rounded when driven)."
        % map_gen.route_length(TOUR_SW),
        "x_m y_m in the map frame; the robot starts on the first point facing the second."])
    print("floor50: %d x %d cells, %d rooms, route %.1f m"
          % (g.cols, g.rows, len(rooms), map_gen.route_length(ROUTE)))


if __name__ == "__main__":
    main()
