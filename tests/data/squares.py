#!/usr/bin/python3
"""A RunProgram generator for the tests: for each request "detail datablock" on stdin, writes
RIB for `n x0 y0 size z [encoding]` (the datablock) squares in a row, then the end-of-answer byte
\\377. The encoding is "ascii" (the default), "gzip", or "binary" (RI Spec 3.2, Appendix C)."""
import gzip
import struct
import sys


def binary_string(s):
    return bytes([0o220 + len(s)]) + s.encode()


for line in sys.stdin:
    detail, _, block = line.strip().partition(" ")
    fields = block.split()
    n, x0, y0, size, z = (float(v) for v in fields[:5])
    encoding = fields[5] if len(fields) > 5 else "ascii"
    rib = []
    out = bytearray(b"\314\000" + binary_string("Patch")) if encoding == "binary" else None
    for i in range(int(n)):
        x = x0 + i * 2 * size
        P = (x, y0, z, x + size, y0, z, x, y0 + size, z, x + size, y0 + size, z)
        rib.append('Patch "bilinear" "P" [%g %g %g  %g %g %g  %g %g %g  %g %g %g]\n' % P)
        if out is not None:  # Patch (code 0) "bilinear" "P" and a float array of 12
            out += b"\246\000" + binary_string("bilinear") + binary_string("P")
            out += bytes([0o310, len(P)]) + struct.pack(">%df" % len(P), *P)
    if encoding == "binary":
        answer = bytes(out)
    elif encoding == "gzip":
        answer = gzip.compress("".join(rib).encode())
    else:
        answer = "".join(rib).encode()
    sys.stdout.buffer.write(answer + b"\xff")
    sys.stdout.buffer.flush()
