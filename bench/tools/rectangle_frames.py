"""Right-handed to_world matrices for the rectangles of `glint convert`'s Mitsuba scenes.

`glint convert` (renderer/mitsuba_writer.cpp, exchange::quad_frame) writes a quad as Mitsuba's
rectangle with to_world columns x = (p2 - p0) / 2, y = (p1 - p0) / 2 and z = the unit normal
cross(p1 - p0, p2 - p0), which is -(x cross y): a mirroring matrix (determinant < 0). It puts
Glint's uvs and front side on Mitsuba's, and Mitsuba's `path` renders it as expected, but the
surface's frame (dp/du, dp/dv, n) is left-handed, and Mitsuba's particle tracer (`ptracer`)
then connects no light-path vertex on it to the camera: every such rectangle renders black.
Negating the x column gives the same points (the square [-1, 1]^2 is symmetric) and the same
normal (Mitsuba transforms (0, 0, 1) by the inverse transpose, (x cross y) / det, which keeps
its sign when x and det both flip) with a right-handed frame; only u is mirrored, and the bench
exports no textures. Plain Python (the ctest bench.rectangle_frames needs no numpy).
"""


def determinant3(m):
    """The determinant of the upper-left 3x3 block of a 4x4 matrix given as rows."""
    (a, b, c), (d, e, f), (g, h, i) = (row[:3] for row in m[:3])
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)


def right_handed(m):
    """The 4x4 matrix (rows) with its x column negated when its 3x3 block mirrors, else as is."""
    rows = [list(map(float, row)) for row in m]
    if determinant3(rows) < 0:
        for r in range(3):
            rows[r][0] = -rows[r][0]
    return rows
