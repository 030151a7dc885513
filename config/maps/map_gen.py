"""Drawing helpers shared by the floor-plan generators (office/make_office.py,
floor50/make_floor50.py): a map_server occupancy grid drawn in world metres,
written as a trinary PGM + YAML, plus a route (waypoints file) and a check of the
route's clearance against the drawn obstacles.

Plain Python 3 (no third-party modules), deterministic: the same script gives the
same bytes on every machine (random.Random with a fixed seed).
"""

import math
import os

FREE = 254
OCCUPIED = 0
UNKNOWN = 205


class Grid:
    """Cells of `resolution_m`, origin (0, 0) at the bottom-left corner of the map."""

    def __init__(self, width_m, height_m, resolution_m=0.05, fill=FREE):
        self.res = resolution_m
        self.cols = int(round(width_m / resolution_m))
        self.rows = int(round(height_m / resolution_m))
        # Stored bottom row first (row index grows with y); flipped when written.
        self.cells = bytearray([fill]) * (self.cols * self.rows)

    def _span(self, a_m, b_m, n):
        lo = max(0, int(round(min(a_m, b_m) / self.res)))
        hi = min(n, int(round(max(a_m, b_m) / self.res)))
        return lo, hi

    def rect(self, x0, y0, x1, y1, value=OCCUPIED):
        """Fills [x0, x1) x [y0, y1) (metres, cell edges rounded to the grid)."""
        c0, c1 = self._span(x0, x1, self.cols)
        r0, r1 = self._span(y0, y1, self.rows)
        for r in range(r0, r1):
            base = r * self.cols
            self.cells[base + c0:base + c1] = bytes([value]) * (c1 - c0)

    def hwall(self, y, x0, x1, thickness=0.1):
        self.rect(x0, y - thickness / 2, x1, y + thickness / 2)

    def vwall(self, x, y0, y1, thickness=0.1):
        self.rect(x - thickness / 2, y0, x + thickness / 2, y1)

    def hdoor(self, y, x0, x1, thickness=0.1):
        """An opening [x0, x1) in a horizontal wall at y."""
        self.rect(x0, y - thickness, x1, y + thickness, FREE)

    def vdoor(self, x, y0, y1, thickness=0.1):
        self.rect(x - thickness, y0, x + thickness, y1, FREE)

    def disc(self, cx, cy, r, value=OCCUPIED):
        """Cells whose centres lie within r of (cx, cy); at least the cell holding the centre."""
        c0, c1 = self._span(cx - r, cx + r + self.res, self.cols)
        r0, r1 = self._span(cy - r, cy + r + self.res, self.rows)
        for row in range(r0, r1):
            for col in range(c0, c1):
                x = (col + 0.5) * self.res
                y = (row + 0.5) * self.res
                if math.hypot(x - cx, y - cy) <= r:
                    self.cells[row * self.cols + col] = value
        col = int(cx / self.res)
        row = int(cy / self.res)
        if 0 <= col < self.cols and 0 <= row < self.rows:
            self.cells[row * self.cols + col] = value

    def occupied_centres(self):
        for row in range(self.rows):
            base = row * self.cols
            for col in range(self.cols):
                if self.cells[base + col] == OCCUPIED:
                    yield (col + 0.5) * self.res, (row + 0.5) * self.res

    def write(self, folder, stem, origin=(0.0, 0.0)):
        """Writes stem.pgm (binary P5, top row first) and stem.yaml (map_server, trinary);
        `origin` is the world position of the map's bottom-left corner."""
        pgm = os.path.join(folder, stem + ".pgm")
        with open(pgm + ".tmp", "wb") as f:
            f.write(b"P5\n%d %d\n255\n" % (self.cols, self.rows))
            for row in range(self.rows - 1, -1, -1):
                f.write(self.cells[row * self.cols:(row + 1) * self.cols])
        os.replace(pgm + ".tmp", pgm)
        yaml = os.path.join(folder, stem + ".yaml")
        with open(yaml + ".tmp", "w") as f:
            f.write("image: %s.pgm\nmode: trinary\nresolution: %.2f\norigin: [%r, %r, 0]\n"
                    "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\n"
                    % (stem, self.res, float(origin[0]), float(origin[1])))
        os.replace(yaml + ".tmp", yaml)


def segment_distance(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    n2 = dx * dx + dy * dy
    t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / n2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def route_distance(route, x, y):
    """Distance from (x, y) to the polyline `route` (list of (x, y))."""
    return min(segment_distance(x, y, *route[i], *route[i + 1]) for i in range(len(route) - 1))


def route_length(route):
    return sum(math.hypot(route[i + 1][0] - route[i][0], route[i + 1][1] - route[i][1])
               for i in range(len(route) - 1))


def check_clearance(grid, route, clearance_m):
    """Raises if an occupied cell centre lies closer than clearance_m to the route polyline."""
    segments = sorted(set((route[i], route[i + 1]) for i in range(len(route) - 1)))
    for x, y in grid.occupied_centres():
        for a, b in segments:
            d = segment_distance(x, y, *a, *b)
            if d < clearance_m:
                raise SystemExit("occupied cell (%.3f, %.3f) is %.3f m from route segment %s-%s"
                                 % (x, y, d, a, b))


def write_route(path, route, header_lines):
    with open(path + ".tmp", "w") as f:
        for line in header_lines:
            f.write("# %s\n" % line)
        for x, y in route:
            f.write("%.2f %.2f\n" % (x, y))
    os.replace(path + ".tmp", path)


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
    walls every 3 - 5.5 m, one 0.9 m door per room in the corridor wall (appended to `doors`
    as draw_corridor_clutter expects), each room's box appended to `rooms`.
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


def near_door(doors, x, y, margin):
    """True when (x, y) lies within margin of one of `doors` (see draw_corridor_clutter)."""
    for kind, c, a, b in doors:
        if kind == "h" and a - margin <= x <= b + margin and abs(y - c) <= margin + 0.5:
            return True
        if kind == "v" and a - margin <= y <= b + margin and abs(x - c) <= margin + 0.5:
            return True
    return False


def free_of_route(route, clearance_m, x0, y0, x1, y1):
    """True when the box [x0, x1] x [y0, y1] keeps clearance_m from the route."""
    pts = [(x0, y0), (x0, y1), (x1, y0), (x1, y1), ((x0 + x1) / 2, (y0 + y1) / 2),
           ((x0 + x1) / 2, y0), ((x0 + x1) / 2, y1), (x0, (y0 + y1) / 2), (x1, (y0 + y1) / 2)]
    return all(route_distance(route, x, y) >= clearance_m for x, y in pts)


def draw_corridor_clutter(g, rng, walls, doors, route, clearance_m):
    """Items against corridor walls at irregular spacing: cabinets, pillars, bins, poles.

    walls: (orientation 'h' or 'v', wall coordinate, from, to, +1/-1 towards the corridor);
    doors: (orientation, wall coordinate, from, to) openings kept clear; nothing comes
    closer than clearance_m to the route polyline.
    """
    for kind, c, a, b, inward in walls:
        s = a + rng.uniform(0.3, 1.0)
        while s < b - 0.4:
            item = rng.choice(["cabinet", "cabinet", "pillar", "bin", "pole", "pole"])
            length = {"cabinet": rng.uniform(0.5, 1.1), "pillar": 0.3, "bin": 0.35,
                      "pole": 0.1}[item]
            depth = {"cabinet": rng.uniform(0.3, 0.45), "pillar": 0.3, "bin": 0.35,
                     "pole": rng.uniform(0.3, 0.42)}[item]
            s0, s1 = s, min(s + length, b - 0.1)
            if kind == "h":
                box = (s0, min(c, c + inward * depth), s1, max(c, c + inward * depth))
            else:
                box = (min(c, c + inward * depth), s0, max(c, c + inward * depth), s1)
            mid = ((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)
            if not near_door(doors, mid[0], mid[1], 0.15 + length / 2) and free_of_route(route, clearance_m, *box):
                if item in ("cabinet", "pillar"):
                    g.rect(*box)
                elif item == "bin":
                    g.disc(mid[0], mid[1], 0.17)
                else:  # a free-standing pole, depth = its distance from the wall
                    px = mid[0] if kind == "h" else c + inward * depth
                    py = c + inward * depth if kind == "h" else mid[1]
                    if route_distance(route, px, py) >= clearance_m:
                        g.disc(px, py, 0.05)
            s = s1 + rng.uniform(0.3, 1.1)


def draw_room_furniture(g, rng, rooms, doors, route, clearance_m):
    """Desks, shelves (against walls), chairs and plants in each room (x0, y0, x1, y1), clear
    of the doors and of the route."""
    for x0, y0, x1, y1 in rooms:
        placed = []
        area = (x1 - x0) * (y1 - y0)
        for _ in range(int(area * 3)):
            if len(placed) >= int(area / 1.5) + 2:
                break
            item = rng.choice(["desk", "desk", "shelf", "chair", "chair", "plant"])
            if item == "desk":
                w, h = (1.2, 0.6) if rng.random() < 0.5 else (0.6, 1.2)
            elif item == "shelf":
                w, h = (rng.uniform(0.8, 1.8), 0.4) if rng.random() < 0.5 else \
                    (0.4, rng.uniform(0.8, 1.8))
            else:
                w = h = 0.4 if item == "chair" else 0.3
            if item == "shelf":  # against a wall
                if w > h:
                    bx = rng.uniform(x0 + 0.15, x1 - 0.15 - w)
                    by = y0 + 0.1 if rng.random() < 0.5 else y1 - 0.1 - h
                else:
                    bx = x0 + 0.1 if rng.random() < 0.5 else x1 - 0.1 - w
                    by = rng.uniform(y0 + 0.15, y1 - 0.15 - h)
            else:
                if x1 - x0 - 0.6 - w <= 0 or y1 - y0 - 0.6 - h <= 0:
                    continue
                bx = rng.uniform(x0 + 0.3, x1 - 0.3 - w)
                by = rng.uniform(y0 + 0.3, y1 - 0.3 - h)
            box = (bx, by, bx + w, by + h)
            if any(box[0] < p[2] + 0.3 and p[0] < box[2] + 0.3 and box[1] < p[3] + 0.3 and
                   p[1] < box[3] + 0.3 for p in placed):
                continue
            if near_door(doors, (box[0] + box[2]) / 2, (box[1] + box[3]) / 2, 0.5 + max(w, h) / 2):
                continue
            if not free_of_route(route, clearance_m, *box):
                continue
            placed.append(box)
            if item in ("chair", "plant"):
                g.disc((box[0] + box[2]) / 2, (box[1] + box[3]) / 2, w / 2)
            else:
                g.rect(*box)
