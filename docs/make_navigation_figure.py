#!/usr/bin/env python3
"""Draws docs/navigation_grid.png from a `uwbsar map` output folder: the SAR mosaic (map.png)
beside the navigation grid (map.pgm, white free, black occupied, grey unknown) with the
corrected trajectory (trajectory.tum) in red, both at the grid's scale, with a 1 m scale bar.

Usage (the README's picture is the office run):
    uwbsar simulate --map config/maps/office/office.yaml \\
        --route config/maps/office/route_loops.txt --out /tmp/office_bag
    uwbsar map /tmp/office_bag --out /tmp/office_map
    .venv/bin/python docs/make_navigation_figure.py /tmp/office_map docs/navigation_grid.png
Needs Pillow and PyYAML (both come with evo in the test venv, test/requirements.txt).
"""
import math
import os
import sys

import yaml
from PIL import Image, ImageDraw


def read_tum(path):
    poses = []
    with open(path) as f:
        for line in f:
            v = line.split()
            if len(v) == 8 and not line.startswith("#"):
                poses.append((float(v[1]), float(v[2])))
    return poses


def main(folder, out_png, scale=2):
    with open(os.path.join(folder, "map.yaml")) as f:
        meta = yaml.safe_load(f)
    grid = Image.open(os.path.join(folder, meta["image"])).convert("RGB")
    res, (x0, y0) = meta["resolution"], meta["origin"][:2]
    w, h = grid.size
    grid = grid.resize((w * scale, h * scale), Image.NEAREST)
    with open(os.path.join(folder, "map_grid.yaml")) as f:
        mosaic_grid = yaml.safe_load(f)
    mosaic = Image.open(os.path.join(folder, "map.png")).convert("RGB")
    # The mosaic on the grid's frame: pixel (c, r) of the mosaic lies at x0_m + c res, y0_m - r res.
    m_res = mosaic_grid["resolution_m"]
    left = (x0 - (mosaic_grid["x0_m"] - 0.5 * m_res)) / m_res
    top = ((mosaic_grid["y0_m"] + 0.5 * m_res) - (y0 + h * res)) / m_res
    mosaic = mosaic.crop((round(left), round(top), round(left + w * res / m_res),
                          round(top + h * res / m_res))).resize(grid.size, Image.BILINEAR)
    path = read_tum(os.path.join(folder, "trajectory.tum"))

    def px(p):
        return ((p[0] - x0) / res * scale, (h - (p[1] - y0) / res) * scale)

    draw = ImageDraw.Draw(grid)
    draw.line([px(p) for p in path[::10]], fill=(220, 30, 30), width=2)
    start = px(path[0])
    draw.ellipse([start[0] - 6, start[1] - 6, start[0] + 6, start[1] + 6], outline=(0, 150, 0),
                 width=3)
    pad = 10
    figure = Image.new("RGB", (2 * grid.size[0] + 3 * pad, grid.size[1] + 4 * pad), "white")
    figure.paste(mosaic, (pad, pad))
    figure.paste(grid, (2 * pad + grid.size[0], pad))
    d = ImageDraw.Draw(figure)
    bar = 1.0 / res * scale  # 1 m
    y = grid.size[1] + 2 * pad
    d.line([(pad, y), (pad + bar, y)], fill="black", width=4)
    d.text((pad + bar + 6, y - 6), "1 m", fill="black")
    d.text((2 * pad + grid.size[0], y - 6),
           "map.pgm: free (white), occupied (black), unknown (grey); path red, start green",
           fill="black")
    figure.quantize(64).save(out_png, optimize=True)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
