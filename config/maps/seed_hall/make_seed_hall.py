#!/usr/bin/env python3
"""Generates seed_hall (seed_hall.pgm + seed_hall.yaml, map_server trinary, 0.05 m cells):
the project's own room after the UWB SAR paper's description of its test room (an indoor
hall with office chairs, study tables and TV stands with two metal poles). It is the
embedded default of `uwbsar demo` and `uwbsar run --emulate`; it is drawn by us, not
measured. Deterministic: running it again rewrites the same bytes.
Run from anywhere: python3 config/maps/seed_hall/make_seed_hall.py

Layout (world metres; the robot starts at the origin facing +x, as in the paper's run):
  - a hall 10.6 m x 3.45 m: walls at y = +1.60 and y = -1.85, x = -0.8 and x = 9.8
    (0.1 m thick), a 0.9 m door in the lower wall;
  - along both long walls, 1.0 - 1.8 m from the path: TV stands (two thin metal poles
    12 cm apart), office chairs (five legs on a 0.25 m circle), study tables (four legs),
    cabinets and a free-standing pole, at irregular spacing so that every metre looks
    different to the radar;
  - nothing within 0.4 m of the built-in routes (depart-return: 7.5 m along y = 0 and back;
    loop: the 7 m x 0.6 m rectangle above it).
"""

import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import map_gen  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
# World position of the map's bottom-left corner: the map spans x = -1.0 .. 10.0,
# y = -2.05 .. 1.80.
ORIGIN = (-1.0, -2.05)
WIDTH_M, HEIGHT_M = 11.0, 3.85
ROUTE_CLEARANCE_M = 0.4
ROUTES = [[(0.0, 0.0), (7.5, 0.0)],
          [(0.0, 0.0), (7.0, 0.0), (7.0, 0.6), (0.0, 0.6), (0.0, 0.0)]]


class WorldGrid:
    """map_gen.Grid drawn in world metres (the grid's own frame starts at ORIGIN)."""

    def __init__(self):
        self.grid = map_gen.Grid(WIDTH_M, HEIGHT_M)

    def rect(self, x0, y0, x1, y1, value=map_gen.OCCUPIED):
        self.grid.rect(x0 - ORIGIN[0], y0 - ORIGIN[1], x1 - ORIGIN[0], y1 - ORIGIN[1], value)

    def disc(self, x, y, r):
        self.grid.disc(x - ORIGIN[0], y - ORIGIN[1], r)


def leg(g, x, y):
    g.disc(x, y, 0.03)


def tv_stand(g, x, y):
    leg(g, x, y)
    leg(g, x + 0.12, y)


def chair(g, x, y):
    for k in range(5):
        a = 2.0 * math.pi * k / 5.0 + 0.3
        leg(g, x + 0.25 * math.cos(a), y + 0.25 * math.sin(a))


def table(g, x0, y0, x1, y1):
    for x in (x0, x1):
        for y in (y0, y1):
            leg(g, x, y)


def main():
    g = WorldGrid()
    # Walls and the door.
    g.rect(-0.85, 1.55, 9.85, 1.65)
    g.rect(-0.85, -1.90, 9.85, -1.80)
    g.rect(-0.85, -1.90, -0.75, 1.65)
    g.rect(9.75, -1.90, 9.85, 1.65)
    g.rect(5.0, -1.95, 5.9, -1.75, map_gen.FREE)
    # Left of the path (y > 0).
    tv_stand(g, 1.15, 1.20)
    tv_stand(g, 2.30, 1.25)
    chair(g, 3.40, 1.28)
    g.rect(4.40, 1.20, 5.00, 1.55)
    table(g, 5.50, 1.10, 6.90, 1.45)
    chair(g, 7.65, 1.30)
    g.rect(8.20, 1.25, 9.00, 1.55)
    leg(g, 9.40, 1.05)
    # Right of the path (y < 0).
    chair(g, 0.95, -1.35)
    table(g, 1.80, -1.75, 3.00, -1.10)
    leg(g, 3.60, -1.15)
    chair(g, 4.35, -1.40)
    tv_stand(g, 5.60, -1.15)
    g.rect(6.30, -1.80, 7.20, -1.40)
    table(g, 7.60, -1.75, 9.00, -1.10)
    chair(g, 9.35, -1.30)
    # The routes keep their clearance (checked in the grid's own frame).
    for route in ROUTES:
        local = [(x - ORIGIN[0], y - ORIGIN[1]) for x, y in route]
        map_gen.check_clearance(g.grid, local, ROUTE_CLEARANCE_M)
    g.grid.write(HERE, "seed_hall", ORIGIN)


if __name__ == "__main__":
    main()
