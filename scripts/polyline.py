"""Polyline helpers shared by the growth scripts (held_out_pairs.sh,
bridge_branch.sh): cracks as lists of [x, y] points in metres."""
import math


def on_polyline(p, poly):
    """Whether point p lies on the polyline (within 0.1 µm): a grown tip
    that ended on another crack (a junction)."""
    for a, b in zip(poly, poly[1:]):
        ax, ay = b[0] - a[0], b[1] - a[1]
        l2 = ax * ax + ay * ay
        t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay) / l2))
        if math.dist(p, (a[0] + t * ax, a[1] + t * ay)) < 1e-7:
            return True
    return False
