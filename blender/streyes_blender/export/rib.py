"""Writing RIB text: requests, parameter lists and numbers.

Numbers are written with 9 significant digits, which is exact for Blender's 32-bit floats, so
that what stays still between frames is written the same in every frame (the frame-sequence
reader shares it only when the data are equal)."""

import math

import numpy as np


def num(x):
    x = float(x)
    if not math.isfinite(x):
        raise ValueError("not a finite number: %r" % x)
    return "%.9g" % (x + 0.0)  # + 0.0: -0 is written 0


def nums(values):
    if isinstance(values, np.ndarray):
        # Meshes: formatted in one pass (a few million numbers a second).
        values = values.astype(np.float64).ravel()
        if not np.isfinite(values).all():
            raise ValueError("not a finite number among %d values" % len(values))
        return " ".join(["%.9g" % v for v in (values + 0.0).tolist()])
    return " ".join(num(v) for v in values)


def ints(values):
    if isinstance(values, np.ndarray):
        return " ".join(map(str, values.astype(np.int64).ravel().tolist()))
    return " ".join(str(int(v)) for v in values)


def string(s):
    return '"' + str(s).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def array(values, kind=None):
    """A RIB array: numbers (floats or whole numbers), or strings."""
    if not isinstance(values, np.ndarray):
        values = list(values)
    if kind == "string" or (len(values) and isinstance(values[0], str)):
        return "[" + " ".join(string(v) for v in values) + "]"
    if kind == "int":
        return "[" + ints(values) + "]"
    return "[" + nums(values) + "]"


def matrix(m):
    """A 4x4 mathutils.Matrix (column vectors, as Blender) as RIB's 16 numbers (row vectors)."""
    return "[" + nums(m[r][c] for c in range(4) for r in range(4)) + "]"


class Writer:
    """Collects the lines of one RIB file, indenting blocks."""

    def __init__(self):
        self.lines = []
        self.depth = 0

    def comment(self, text):
        for line in str(text).splitlines() or [""]:
            self.lines.append("  " * self.depth + "# " + line)

    def write(self, request, *args):
        """A request and its arguments, already formatted (num, array, string, ...)."""
        self.lines.append("  " * self.depth + " ".join([request] + [a for a in args if a != ""]))

    def params(self, request, positional=(), params=None):
        """A request with positional arguments and a parameter list {declaration: value}; values are
        numbers, strings or sequences of either."""
        out = list(positional)
        for name, value in (params or {}).items():
            out.append(string(name))
            if isinstance(value, str):
                out.append("[" + string(value) + "]")
            elif isinstance(value, (list, tuple)):
                out.append(array(value))
            else:
                out.append("[" + num(value) + "]")
        self.write(request, *out)

    def begin(self, request, *args):
        self.write(request, *args)
        self.depth += 1

    def end(self, request):
        self.depth -= 1
        self.write(request)

    def text(self):
        return "\n".join(self.lines) + "\n"
