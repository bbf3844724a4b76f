#!/usr/bin/env python3
"""Writes a benchmark scene to stdout: an n x n grid of small spheres over a reflective floor,
lit by two lights. The grid always covers the same 8 x 8 area and every length in it (radius,
height jitter) scales with the spacing, so grids of 1k and 1M spheres are the same picture at
different detail: what changes with n is only how many objects a ray must be tested against.

usage: sphere_grid.py N      (N spheres, rounded to a square)
"""
import sys

n = int(sys.argv[1])
side = max(1, round(n ** 0.5))
step = 8.0 / side
out = [
    "<scene>",
    '  <ambient-light colour="#202020"/>',
    '  <point-light x="-4" y="6" z="0" colour="#FFFFFF" intensity="400" name="key"/>',
    '  <point-light x="5" y="3" z="2" colour="#8080FF" intensity="150" name="fill"/>',
    '  <plane x="0" y="-1" z="0" nx="0" ny="1" nz="0" colour="#404040" reflectivity="0.5"/>',
]
for i in range(side):
    for j in range(side):
        out.append(
            '  <sphere x="%.6f" y="%.6f" z="%.6f" radius="%.6f" colour="#%02X80%02X"/>'
            % (
                -4 + (i + 0.5) * step,
                -1 + 0.5 * step + 0.3 * step * ((i * 7 + j * 3) % 5) / 5,
                6 + (j + 0.5) * step,
                0.4 * step,
                i * 255 // side,
                j * 255 // side,
            )
        )
out.append("</scene>")
sys.stdout.write("\n".join(out) + "\n")
