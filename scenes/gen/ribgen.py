"""Small helpers for writing RIB scenes from Python (used by the scene generators here)."""
import math


def fmt(v):
    return ("%.6g" % v) if isinstance(v, float) else str(v)


def patch(p00, p10, p01, p11):
    """Patch "bilinear" with corners in RenderMan order (u0v0, u1v0, u0v1, u1v1)."""
    pts = " ".join(fmt(c) for p in (p00, p10, p01, p11) for c in p)
    return 'Patch "bilinear" "P" [%s]\n' % pts


def box(cx, cy, cz, sx, sy, sz):
    """Six outward-facing bilinear patches of an axis-aligned box centred at (cx, cy, cz)."""
    x0, x1 = cx - sx / 2, cx + sx / 2
    y0, y1 = cy - sy / 2, cy + sy / 2
    z0, z1 = cz - sz / 2, cz + sz / 2
    faces = [
        ((x0, y0, z0), (x1, y0, z0), (x0, y1, z0), (x1, y1, z0)),  # -z
        ((x1, y0, z1), (x0, y0, z1), (x1, y1, z1), (x0, y1, z1)),  # +z
        ((x0, y0, z1), (x0, y0, z0), (x0, y1, z1), (x0, y1, z0)),  # -x
        ((x1, y0, z0), (x1, y0, z1), (x1, y1, z0), (x1, y1, z1)),  # +x
        ((x0, y1, z0), (x1, y1, z0), (x0, y1, z1), (x1, y1, z1)),  # +y
        ((x0, y0, z1), (x1, y0, z1), (x0, y0, z0), (x1, y0, z0)),  # -y
    ]
    return "".join(patch(*f) for f in faces)


def sphere(radius, nu=16, nv=8):
    """A sphere of bilinear patches (latitude-longitude), centred at the origin."""
    def pt(i, j):
        phi = 2 * math.pi * i / nu
        theta = math.pi * j / nv - math.pi / 2
        return (radius * math.cos(theta) * math.cos(phi), radius * math.sin(theta),
                radius * math.cos(theta) * math.sin(phi))
    out = []
    for j in range(nv):
        for i in range(nu):
            out.append(patch(pt(i, j), pt(i + 1, j), pt(i, j + 1), pt(i + 1, j + 1)))
    return "".join(out)


def motion(times, requests):
    """MotionBegin [times] with one request per key."""
    assert len(times) == len(requests)
    return "MotionBegin [%s]\n%sMotionEnd\n" % (
        " ".join(fmt(t) for t in times), "".join("  " + r + "\n" for r in requests))


def points(seq, digits=5):
    """Points as RIB numbers, rounded: "x y z x y z ..."."""
    return " ".join(fmt(round(c, digits)) for p in seq for c in p)


def attribute_block(surface, color, body):
    """AttributeBegin, a surface shader line, a Color, the body, AttributeEnd."""
    return "AttributeBegin\n%s\nColor [%s]\n%sAttributeEnd\n" % (surface, " ".join(fmt(c) for c in color), body)


def write_scene(name, text):
    """Writes scenes/<name> (the folder above scenes/gen)."""
    import os
    with open(os.path.join(os.path.dirname(__file__), "..", name), "w") as f:
        f.write(text)


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def camera_transform(eye, x, y, z):
    """Transform: world -> the camera at `eye` with axes x, y, z (row vectors, left-handed)."""
    m = [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(eye, x), -dot(eye, y), -dot(eye, z), 1]
    return "Transform [%s]\n" % " ".join(fmt(round(v, 9)) for v in m)
