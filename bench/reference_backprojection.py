#!/usr/bin/python3
"""The paper authors' back-projection, as ../shared/REFERENCE.md describes it, timed on the
reference geometry so that uwbsar's imaging can be compared with it in the same run.

Per scan: an OpenCV fillPoly mask of the radar's annular sector (0.4-3 m, +-30 deg) on the whole
image, then R = |pixel - sensor| for the masked pixels, the compressed scan linearly
interpolated at R / bin size (numpy.interp), added to the pixels. Two radars (left, right), a
5 mm grid of 6 m x 7 m (the grid of BM_BackProjectScanPair). Prints ms per scan pair.

Usage: bench/reference_backprojection.py [PAIRS]   (Debian: python3-opencv, python3-numpy)
"""
import math
import sys
import time

import cv2
import numpy as np

C = 299792458.0
FS = 23.328e9
BIN_M = C / (2 * FS)
SAMPLES = 1000
RES_M = 0.005
MIN_R, MAX_R, HALF_FOV = 0.4, 3.0, math.radians(30.0)
X0, X1, Y0, Y1 = -2.0, 4.0, -3.5, 3.5


def sector_polygon(sx, sy, yaw, steps=32):
    """The annular sector as a polygon in pixel coordinates (column = +x, row = -y)."""
    angles = np.linspace(yaw - HALF_FOV, yaw + HALF_FOV, steps)
    outer = [(sx + MAX_R * math.cos(a), sy + MAX_R * math.sin(a)) for a in angles]
    inner = [(sx + MIN_R * math.cos(a), sy + MIN_R * math.sin(a)) for a in angles[::-1]]
    pts = [((x - X0) / RES_M, (Y1 - y) / RES_M) for x, y in outer + inner]
    return np.array(pts, dtype=np.int32)


def back_project(image, cols_x, rows_y, scan, sx, sy, yaw):
    mask = np.zeros(image.shape, dtype=np.uint8)
    cv2.fillPoly(mask, [sector_polygon(sx, sy, yaw)], 1)
    rows, cols = np.nonzero(mask)
    r = np.hypot(cols_x[cols] - sx, rows_y[rows] - sy)
    image[rows, cols] += np.interp(r / BIN_M, np.arange(scan.size), scan)


def main():
    pairs = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    cols = int(math.ceil((X1 - X0) / RES_M))
    rows = int(math.ceil((Y1 - Y0) / RES_M))
    image = np.zeros((rows, cols), dtype=np.float64)
    cols_x = X0 + (np.arange(cols) + 0.5) * RES_M
    rows_y = Y1 - (np.arange(rows) + 0.5) * RES_M
    rng = np.random.default_rng(1)
    scans = [rng.standard_normal(SAMPLES).astype(np.float32) for _ in range(2)]
    # The robot at (1, 0) heading +x; radars 0.1 m left and right, looking sideways.
    sensors = [(1.0, 0.1, math.pi / 2), (1.0, -0.1, -math.pi / 2)]
    start = time.perf_counter()
    for _ in range(pairs):
        for scan, (sx, sy, yaw) in zip(scans, sensors):
            back_project(image, cols_x, rows_y, scan, sx, sy, yaw)
    seconds = time.perf_counter() - start
    print(f"reference Python back-projection: {seconds / pairs * 1e3:.2f} ms per scan pair "
          f"({pairs} pairs, {cols} x {rows} pixels)")


if __name__ == "__main__":
    main()
