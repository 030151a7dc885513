#!/usr/bin/env python3
"""Generates three building-scale floors with long tours: corridor rings of
50-100 m with offices off the corridors, a large hall, and routes that close a ring only
after 50 m or more. Each floor is a map_server trinary grid (0.05 m cells) plus a route
(waypoints). Deterministic: running it again rewrites the same bytes.
Run from anywhere: python3 config/maps/tours/make_tour_floors.py

Floors (world metres, origin at the bottom-left corner):
  ring_offices (36 x 22 m): one corridor ring 2 m wide, centre line the rectangle
    x = 4 .. 32, y = 4 .. 18 (84 m around), offices outside and inside the ring. The tour
    drives the ring once counter-clockwise and comes back along the first corridor 0.4 m
    off its first line (the walls at another distance): 92 m.
  hall_wing (40 x 24 m): a 14 m x 20 m hall (pillars, tables, stands) on the west, a
    corridor ring of offices on the east that opens into the hall at both ends. The tour
    leaves the hall's south-east corner, drives the ring, crosses the hall and re-enters
    the first corridor: 87 m.
  two_rings (34 x 20 m): two corridor rings (50 m each) sharing a middle corridor (a
    figure of eight). The tour closes the west ring after 50 m, then drives the east ring,
    which sends it down the middle corridor in the other direction (the left radar sees on
    the way back what the right one saw on the way out): 105 m.
"""

import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import map_gen  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROUTE_CLEARANCE_M = 0.5  # clutter and furniture keep this far from the route's centre line


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
    """A row of offices along one corridor wall: along = (a, b) the span along the wall,
    across = (c0, c1) from the corridor wall c0 into the rooms; walls = 'h' when the
    corridor wall is horizontal. Partitions every 3 - 5.5 m, one 0.9 m door per room."""
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


def ring_block(g, rng, doors, rooms, corridor_walls, x0, y0, x1, y1):
    """A block of offices inside a corridor ring: walls on its edges, two rows of rooms
    (south and north halves) with doors onto the ring."""
    g.hwall(y0, x0 - 0.05, x1 + 0.05)
    g.hwall(y1, x0 - 0.05, x1 + 0.05)
    g.vwall(x0, y0, y1)
    g.vwall(x1, y0, y1)
    ym = round((y0 + y1) / 2 / 0.05) * 0.05
    g.hwall(ym, x0, x1)
    room_row(g, rng, doors, rooms, "h", (x0, x1), (y0, ym))
    room_row(g, rng, doors, rooms, "h", (x0, x1), (y1, ym))
    corridor_walls += [("h", y0, x0, x1, -1), ("h", y1, x0, x1, +1), ("v", x0, y0, y1, -1),
                       ("v", x1, y0, y1, +1)]


def outer_offices(g, rng, doors, rooms, corridor_walls, lo_x, lo_y, hi_x, hi_y, w, h,
                  sides="sewn"):
    """Offices between the corridor ring's outer walls (lo_x .. hi_x, lo_y .. hi_y) and the
    building's outside walls (0 .. w, 0 .. h), on the given sides."""
    if "s" in sides:
        room_row(g, rng, doors, rooms, "h", (lo_x, hi_x), (lo_y, 0.1))
        corridor_walls.append(("h", lo_y, lo_x, hi_x, +1))
    if "n" in sides:
        room_row(g, rng, doors, rooms, "h", (lo_x, hi_x), (hi_y, h - 0.1))
        corridor_walls.append(("h", hi_y, lo_x, hi_x, -1))
    if "w" in sides:
        room_row(g, rng, doors, rooms, "v", (lo_y, hi_y), (lo_x, 0.1))
        corridor_walls.append(("v", lo_x, lo_y, hi_y, +1))
    if "e" in sides:
        room_row(g, rng, doors, rooms, "v", (lo_y, hi_y), (hi_x, w - 0.1))
        corridor_walls.append(("v", hi_x, lo_y, hi_y, -1))


def boundary(g, w, h):
    for y in (0.05, h - 0.05):
        g.hwall(y, 0.0, w)
    for x in (0.05, w - 0.05):
        g.vwall(x, 0.0, h)


def finish(g, rng, name, route, doors, rooms, corridor_walls, description):
    for kind, c, a, b in doors:
        (g.hdoor if kind == "h" else g.vdoor)(c, a, b)
    map_gen.draw_corridor_clutter(g, rng, corridor_walls, doors, route, ROUTE_CLEARANCE_M)
    map_gen.draw_room_furniture(g, rng, rooms, doors, route, ROUTE_CLEARANCE_M)
    map_gen.check_clearance(g, route, 0.45)
    g.write(HERE, name)
    map_gen.write_route(os.path.join(HERE, name + "_tour.txt"), route, description + [
        "Generated by make_tour_floors.py; %.1f m of polyline (corners are rounded when driven)."
        % map_gen.route_length(route),
        "x_m y_m in the map frame; the robot starts on the first point facing the second."])
    print("%s: %d x %d cells, %d rooms, route %.1f m"
          % (name, g.cols, g.rows, len(rooms), map_gen.route_length(route)))


RING_OFFICES_ROUTE = [(7.0, 4.0), (32.0, 4.0), (32.0, 18.0), (4.0, 18.0), (4.0, 4.4),
                      (16.0, 4.4)]


def ring_offices():
    rng = random.Random(19001)
    w, h = 36.0, 22.0
    g = map_gen.Grid(w, h, 0.05)
    boundary(g, w, h)
    for c in (3.0, 19.0):
        g.hwall(c, 0.0, w)
    for c in (3.0, 33.0):
        g.vwall(c, 0.0, h)
    g.rect(3.05, 3.05, 32.95, 18.95, map_gen.FREE)
    doors, rooms, walls = [], [], []
    outer_offices(g, rng, doors, rooms, walls, 3.0, 3.0, 33.0, 19.0, w, h)
    ring_block(g, rng, doors, rooms, walls, 5.0, 5.0, 31.0, 17.0)
    finish(g, rng, "ring_offices", RING_OFFICES_ROUTE, doors, rooms, walls, [
        "ring_offices.yaml: the 84 m corridor ring once counter-clockwise, then the first",
        "corridor again 0.4 m off its first line."])


HALL_WING_ROUTE = [(11.0, 5.0), (37.0, 5.0), (37.0, 19.0), (10.0, 19.0), (10.0, 5.0),
              (20.0, 5.0)]


def hall_wing():
    rng = random.Random(19002)
    w, h = 40.0, 24.0
    g = map_gen.Grid(w, h, 0.05)
    boundary(g, w, h)
    # The hall: x = 0 .. 14, y = 2 .. 22; its east wall opens onto the two corridors.
    g.hwall(2.0, 0.0, 14.05)
    g.hwall(22.0, 0.0, 14.05)
    g.vwall(14.0, 2.0, 22.0)
    g.vdoor(14.0, 4.05, 5.95)
    g.vdoor(14.0, 18.05, 19.95)
    # The corridor ring: centre lines y = 5, y = 19, x = 37 (and the hall on the west).
    g.hwall(4.0, 14.0, 38.0)
    g.hwall(20.0, 14.0, 38.0)
    g.vwall(38.0, 4.0, 20.0)
    doors, rooms, walls = [], [], []
    room_row(g, rng, doors, rooms, "h", (14.0, 38.0), (4.0, 0.1))
    room_row(g, rng, doors, rooms, "h", (14.0, 38.0), (20.0, h - 0.1))
    room_row(g, rng, doors, rooms, "v", (4.0, 20.0), (38.0, w - 0.1))
    walls += [("h", 4.0, 14.0, 38.0, +1), ("h", 20.0, 14.0, 38.0, -1), ("v", 38.0, 4.0, 20.0, -1)]
    ring_block(g, rng, doors, rooms, walls, 16.0, 6.0, 36.0, 18.0)
    # Hall contents: square pillars, TV stands (two thin poles), tables along the walls.
    for px in (4.0, 7.0):
        for py in (6.0, 10.0, 14.0, 18.0):
            g.rect(px - 0.2, py - 0.2, px + 0.2, py + 0.2)
    for py in (9.0, 13.0, 16.0):
        g.rect(12.8, py, 13.4, py + 1.2)
    for sx, sy in ((2.0, 3.2), (5.5, 20.5), (9.0, 3.0), (12.5, 21.0), (1.2, 12.0)):
        g.disc(sx, sy, 0.04)
        g.disc(sx + 0.12, sy, 0.04)
    rooms.append((0.5, 2.5, 8.5, 21.5))  # furniture in the west part of the hall
    finish(g, rng, "hall_wing", HALL_WING_ROUTE, doors, rooms, walls, [
        "hall_wing.yaml: from the hall's south-east corner the corridor ring counter-clockwise,",
        "across the hall, and back into the first corridor."])


TWO_RINGS_ROUTE = [(9.0, 4.0), (17.0, 4.0), (17.0, 16.0), (4.0, 16.0), (4.0, 4.0),
                   (17.0, 4.0), (30.0, 4.0), (30.0, 16.0), (17.0, 16.0), (17.0, 7.0)]

TWO_RINGS_WEST = TWO_RINGS_ROUTE[:5] + [(14.0, 4.0)]


def two_rings():
    rng = random.Random(19003)
    w, h = 34.0, 20.0
    g = map_gen.Grid(w, h, 0.05)
    boundary(g, w, h)
    for c in (3.0, 17.0):
        g.hwall(c, 0.0, w)
    for c in (3.0, 31.0):
        g.vwall(c, 0.0, h)
    g.rect(3.05, 3.05, 30.95, 16.95, map_gen.FREE)
    doors, rooms, walls = [], [], []
    outer_offices(g, rng, doors, rooms, walls, 3.0, 3.0, 31.0, 17.0, w, h)
    ring_block(g, rng, doors, rooms, walls, 5.0, 5.0, 16.0, 15.0)
    ring_block(g, rng, doors, rooms, walls, 18.0, 5.0, 29.0, 15.0)
    finish(g, rng, "two_rings", TWO_RINGS_ROUTE, doors, rooms, walls, [
        "two_rings.yaml: the west ring (50 m), then the east ring, which comes down the",
        "shared middle corridor in the other direction."])
    # The short tour of the fast test: the west ring closed after 50 m (a part of the tour).
    map_gen.write_route(os.path.join(HERE, "two_rings_west.txt"), TWO_RINGS_WEST, [
        "two_rings.yaml: the west ring once (50 m), then 5 m of its first corridor again.",
        "Generated by make_tour_floors.py; %.1f m of polyline." % map_gen.route_length(
            TWO_RINGS_WEST),
        "x_m y_m in the map frame; the robot starts on the first point facing the second."])


def main():
    ring_offices()
    hall_wing()
    two_rings()


if __name__ == "__main__":
    main()
