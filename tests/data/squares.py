#!/usr/bin/python3
"""A RunProgram generator for the tests: for each request "detail datablock" on stdin, writes
RIB for `n x0 y0 size z` (the datablock) squares in a row, then the end-of-answer byte \\377."""
import sys

for line in sys.stdin:
    detail, _, block = line.strip().partition(" ")
    n, x0, y0, size, z = (float(v) for v in block.split())
    rib = []
    for i in range(int(n)):
        x = x0 + i * 2 * size
        rib.append('Patch "bilinear" "P" [%g %g %g  %g %g %g  %g %g %g  %g %g %g]\n'
                   % (x, y0, z, x + size, y0, z, x, y0 + size, z, x + size, y0 + size, z))
    sys.stdout.write("".join(rib))
    sys.stdout.flush()
    sys.stdout.buffer.write(b"\xff")
    sys.stdout.buffer.flush()
