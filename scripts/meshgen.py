"""Triangle meshes for scripts/make_configs.py: our own geometry, made here.

Three builders and their checks, Python standard library only, deterministic:

  Surface      closed surfaces on integer coordinates (units of 1/UNIT m, exact
               in binary floats and in the decimals written): boxes on a
               rectilinear grid welded into one solid (blocks), height-field
               solids (heightfield), joined without T-junctions, so that every
               edge belongs to exactly two triangles.
  TriMesh      a triangle mesh in metres (floats) and the swept or revolved
               shapes (revolve, lat_long_body, swept_bar, arc_bar).
  exact_hull   the convex hull of points on a grid of 1/scale, in exact
               integer arithmetic, triangulated face by face.

Writers: OBJ (shared vertices), ASCII STL and COLLADA (Y_UP, so that assimp
reads the coordinates unchanged). validate() checks that a mesh is closed,
consistently oriented outwards, one connected component, without degenerate
triangles, and tells whether it is convex.
"""

import bisect
import math

UNIT = 1024  # integer coordinates are multiples of 1/UNIT m

EMPTY, SOLID, CUSTOM = 0, 1, 2  # grid cell states of blocks()


def num(x, decimals=10):
    """A coordinate as text: exact for multiples of 1/1024 (of 2^-decimals in
    general) and for values rounded to 6 decimals; no trailing zeros, no
    negative zero."""
    s = ("%.*f" % (decimals, x)).rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def u(metres):
    """Metres to integer units, on the grid of 1/256 m (so that the centre of
    a box of such corners is still an integer)."""
    return 4 * int(round(metres * UNIT / 4))


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _newell(points):
    """Normal (not unit) of a planar polygon, by Newell's formula."""
    n = [0, 0, 0]
    for i, p in enumerate(points):
        q = points[(i + 1) % len(points)]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return tuple(n)


# ---- triangle meshes in metres ----------------------------------------------------

class TriMesh:
    """Vertices (metres) and triangles (vertex indices, counter-clockwise seen
    from outside)."""

    def __init__(self, vertices, triangles):
        self.vertices = list(vertices)
        self.triangles = list(triangles)

    def mapped(self, f):
        """The mesh with every vertex replaced by f(vertex), rounded to 6 decimals."""
        return TriMesh([tuple(round(c, 6) + 0.0 for c in f(v)) for v in self.vertices], self.triangles)

    def mean(self):
        k = len(self.vertices)
        return tuple(sum(v[i] for v in self.vertices) / k for i in range(3))

    def box(self):
        return ([min(v[i] for v in self.vertices) for i in range(3)],
                [max(v[i] for v in self.vertices) for i in range(3)])


def validate(mesh, label):
    """Checks that `mesh` is a closed, outward-oriented surface of one
    connected component, with distinct vertices, every vertex used and no
    degenerate triangle. Returns whether it is convex. Raises ValueError
    naming `label` and the first problem."""
    if len(set(mesh.vertices)) != len(mesh.vertices):
        raise ValueError("%s: two vertices at the same position" % label)
    used = set()
    directed = {}
    for t, tri in enumerate(mesh.triangles):
        a, b, c = (mesh.vertices[i] for i in tri)
        longest = max(_dot(d, d) for d in (_sub(b, a), _sub(c, b), _sub(a, c)))
        n = _cross(_sub(b, a), _sub(c, a))
        if _dot(n, n) <= (1e-10 * longest) ** 2:
            raise ValueError("%s: triangle %d is degenerate" % (label, t))
        for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            if e in directed:
                raise ValueError("%s: edge %s used twice in one direction (triangles %d, %d)" % (label, e, directed[e], t))
            directed[e] = t
        used.update(tri)
    if len(used) != len(mesh.vertices):
        raise ValueError("%s: %d unused vertices" % (label, len(mesh.vertices) - len(used)))
    parent = list(range(len(mesh.triangles)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for (a, b), t in directed.items():
        if (b, a) not in directed:
            raise ValueError("%s: edge (%d, %d) of triangle %d is open" % (label, a, b, t))
        parent[root(t)] = root(directed[(b, a)])
    components = len({root(t) for t in range(len(mesh.triangles))})
    if components != 1:
        raise ValueError("%s: %d connected components" % (label, components))
    volume = sum(_dot(mesh.vertices[a], _cross(mesh.vertices[b], mesh.vertices[c])) for a, b, c in mesh.triangles)
    if volume <= 0:
        raise ValueError("%s: oriented inwards (volume %g)" % (label, volume / 6))
    # A closed, connected, outward-oriented surface is convex when every edge
    # is: the far corner of each triangle lies on or below the plane of the
    # triangle across each of its edges (within 1e-9 of the mesh's size).
    lo, hi = mesh.box()
    tol = 1e-9 * math.dist(lo, hi)
    for (a, b), t in directed.items():
        p, q, r = (mesh.vertices[i] for i in mesh.triangles[t])
        n = _cross(_sub(q, p), _sub(r, p))
        far = next(i for i in mesh.triangles[directed[(b, a)]] if i not in (a, b))
        if _dot(n, _sub(mesh.vertices[far], p)) > tol * math.sqrt(_dot(n, n)):
            return False
    return True


# ---- writers -----------------------------------------------------------------------

def obj_text(mesh, comment):
    lines = ["# " + line for line in comment.strip().splitlines()]
    lines += ["v %s %s %s" % tuple(num(c) for c in v) for v in mesh.vertices]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in mesh.triangles]
    return "\n".join(lines) + "\n"


def stl_text(mesh, name):
    """ASCII STL (one facet per triangle, unit normal)."""
    lines = ["solid " + name]
    for tri in mesh.triangles:
        a, b, c = (mesh.vertices[i] for i in tri)
        n = _cross(_sub(b, a), _sub(c, a))
        length = math.sqrt(_dot(n, n))
        lines.append("  facet normal %s %s %s" % tuple(num(round(x / length, 6)) for x in n))
        lines.append("    outer loop")
        lines += ["      vertex %s %s %s" % tuple(num(x) for x in v) for v in (a, b, c)]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid " + name)
    return "\n".join(lines) + "\n"


def dae_text(mesh, name, comment):
    """COLLADA 1.4.1 with one node and one triangle list. Y_UP, so that assimp
    applies no axis conversion: the file's coordinates are the loaded ones."""
    positions = " ".join(num(c) for v in mesh.vertices for c in v)
    indices = " ".join(str(i) for tri in mesh.triangles for i in tri)
    return "\n".join([
        '<?xml version="1.0" encoding="utf-8"?>',
        "<!-- %s -->" % comment.strip().replace("--", "-").replace("\n", " "),
        '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">',
        "  <asset>",
        "    <created>2000-01-01T00:00:00</created>",
        "    <modified>2000-01-01T00:00:00</modified>",
        '    <unit name="meter" meter="1"/>',
        "    <up_axis>Y_UP</up_axis>",
        "  </asset>",
        "  <library_geometries>",
        '    <geometry id="%s-mesh" name="%s">' % (name, name),
        "      <mesh>",
        '        <source id="%s-positions">' % name,
        '          <float_array id="%s-positions-array" count="%d">%s</float_array>' % (
            name, 3 * len(mesh.vertices), positions),
        "          <technique_common>",
        '            <accessor source="#%s-positions-array" count="%d" stride="3">' % (name, len(mesh.vertices)),
        '              <param name="X" type="float"/>',
        '              <param name="Y" type="float"/>',
        '              <param name="Z" type="float"/>',
        "            </accessor>",
        "          </technique_common>",
        "        </source>",
        '        <vertices id="%s-vertices">' % name,
        '          <input semantic="POSITION" source="#%s-positions"/>' % name,
        "        </vertices>",
        '        <triangles count="%d">' % len(mesh.triangles),
        '          <input semantic="VERTEX" source="#%s-vertices" offset="0"/>' % name,
        "          <p>%s</p>" % indices,
        "        </triangles>",
        "      </mesh>",
        "    </geometry>",
        "  </library_geometries>",
        "  <library_visual_scenes>",
        '    <visual_scene id="scene" name="scene">',
        '      <node id="%s" name="%s">' % (name, name),
        '        <instance_geometry url="#%s-mesh"/>' % name,
        "      </node>",
        "    </visual_scene>",
        "  </library_visual_scenes>",
        "  <scene>",
        '    <instance_visual_scene url="#scene"/>',
        "  </scene>",
        "</COLLADA>",
        ""])


# ---- closed surfaces on integer coordinates ----------------------------------------

class Surface:
    """Convex planar polygons (and triangles) on integer points, joined into
    one triangle mesh by mesh(): an edge of one polygon that has vertices of
    other polygons inside it (a T-junction, where merged faces of different
    sizes meet) gets those vertices, so that edges match exactly."""

    def __init__(self):
        self.points = []
        self.ids = {}
        self.faces = []  # vertex ids, counter-clockwise seen from outside

    def vid(self, p):
        p = (int(p[0]), int(p[1]), int(p[2]))
        i = self.ids.get(p)
        if i is None:
            i = self.ids[p] = len(self.points)
            self.points.append(p)
        return i

    def face(self, corners, outward):
        """A convex planar polygon (any winding), turned to face `outward`."""
        ids = [self.vid(p) for p in corners]
        if _dot(_newell([self.points[i] for i in ids]), outward) < 0:
            ids.reverse()
        self.faces.append(ids)

    def mesh(self):
        lines = {}  # (axis, the other two coordinates) -> sorted coordinates along axis
        for p in self.points:
            for a in range(3):
                lines.setdefault((a, p[(a + 1) % 3], p[(a + 2) % 3]), []).append(p[a])
        for values in lines.values():
            values.sort()
        points = list(self.points)
        triangles = []
        for ids in self.faces:
            loop = []
            for k, i in enumerate(ids):
                p, q = self.points[i], self.points[ids[(k + 1) % len(ids)]]
                loop.append(i)
                differ = [a for a in range(3) if p[a] != q[a]]
                if len(differ) != 1:
                    continue
                a = differ[0]
                values = lines[(a, p[(a + 1) % 3], p[(a + 2) % 3])]
                lo, hi = min(p[a], q[a]), max(p[a], q[a])
                inside = values[bisect.bisect_right(values, lo):bisect.bisect_left(values, hi)]
                if p[a] > q[a]:
                    inside.reverse()
                for c in inside:
                    r = list(p)
                    r[a] = c
                    loop.append(self.ids[tuple(r)])
            if len(loop) == len(ids):
                triangles += [(ids[0], ids[k], ids[k + 1]) for k in range(1, len(ids) - 1)]
                continue
            # T-junctions: a fan around an interior point of the face (which
            # is axis-aligned: faces with T-junctions are boxes' and walls').
            corners = [self.points[i] for i in ids]
            normal = _newell(corners)
            if sum(1 for c in normal if c != 0) != 1:
                raise ValueError("a face with T-junctions is not axis-aligned: %s" % corners)
            centre = tuple(sum(p[a] for p in corners) // len(corners) for a in range(3))
            c = len(points)
            points.append(centre)
            triangles += [(c, loop[k], loop[(k + 1) % len(loop)]) for k in range(len(loop))]
        return TriMesh([tuple(x / UNIT for x in p) for p in points], triangles)


def blocks(surface, boxes, max_size=None):
    """Adds the boundary of a union of boxes to `surface`. boxes: (lo, hi,
    state) with integer corners, later ones overriding earlier ones (EMPTY
    carves doors). Coplanar cell faces are merged into rectangles of at most
    `max_size` units a side (None: no limit). CUSTOM cells are solid but
    their faces toward empty space are left to the caller (heightfield)."""
    lines = [sorted({b[0][a] for b in boxes} | {b[1][a] for b in boxes}) for a in range(3)]
    n = [len(v) - 1 for v in lines]
    cells = bytearray(n[0] * n[1] * n[2])
    for lo, hi, state in boxes:
        r = [range(bisect.bisect_left(lines[a], lo[a]), bisect.bisect_left(lines[a], hi[a])) for a in range(3)]
        for i in r[0]:
            for j in r[1]:
                base = (i * n[1] + j) * n[2]
                for k in r[2]:
                    cells[base + k] = state

    def state(c):
        if any(c[a] < 0 or c[a] >= n[a] for a in range(3)):
            return EMPTY
        return cells[(c[0] * n[1] + c[1]) * n[2] + c[2]]

    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        for p in range(n[a] + 1):
            for sign in (1, -1):
                mask = [[False] * n[c] for _ in range(n[b])]
                for i in range(n[b]):
                    for j in range(n[c]):
                        below, above = [0, 0, 0], [0, 0, 0]
                        below[a], above[a] = p - 1, p
                        below[b] = above[b] = i
                        below[c] = above[c] = j
                        inner, outer = (state(below), state(above)) if sign > 0 else (state(above), state(below))
                        mask[i][j] = inner == SOLID and outer == EMPTY
                for i0, i1, j0, j1 in _rectangles(mask, lines[b], lines[c], max_size):
                    corners = []
                    for vb, vc in ((i0, j0), (i1, j0), (i1, j1), (i0, j1)):
                        q = [0, 0, 0]
                        q[a], q[b], q[c] = lines[a][p], lines[b][vb], lines[c][vc]
                        corners.append(q)
                    outward = [0, 0, 0]
                    outward[a] = sign
                    surface.face(corners, outward)


def _rectangles(mask, us, vs, max_size):
    """Greedy cover of the True cells of mask[i][j] by rectangles
    (i0, i1, j0, j1) of grid-line indices, each side at most max_size units."""
    limit = float("inf") if max_size is None else max_size
    nu, nv = len(mask), len(mask[0]) if mask else 0
    used = [[False] * nv for _ in range(nu)]
    out = []
    for i in range(nu):
        for j in range(nv):
            if not mask[i][j] or used[i][j]:
                continue
            j1 = j + 1
            while j1 < nv and mask[i][j1] and not used[i][j1] and vs[j1 + 1] - vs[j] <= limit:
                j1 += 1
            i1 = i + 1
            while (i1 < nu and us[i1 + 1] - us[i] <= limit
                   and all(mask[i1][k] and not used[i1][k] for k in range(j, j1))):
                i1 += 1
            for ii in range(i, i1):
                for k in range(j, j1):
                    used[ii][k] = True
            out.append((i, i1, j, j1))
    return out


def heightfield(surface, x0, x1, y0, y1, z0, nx, ny, height, bottom=False):
    """The solid {(x, y, z): x0 <= x <= x1, y0 <= y <= y1, z0 <= z <= h(x, y)}
    (integer units; height(x, y) in metres, > z0) on an nx x ny grid: the
    top (two triangles per cell), four vertical sides, and the bottom face
    when `bottom` (else it stands on a CUSTOM region of blocks())."""
    xs = [x0 + (x1 - x0) * i // nx for i in range(nx + 1)]
    ys = [y0 + (y1 - y0) * j // ny for j in range(ny + 1)]
    h = [[int(round(height(x / UNIT, y / UNIT) * UNIT)) for y in ys] for x in xs]
    if min(min(row) for row in h) < z0 + 8:
        raise ValueError("heightfield: the top comes within 8 units of the base")
    up = (0, 0, 1)
    for i in range(nx):
        for j in range(ny):
            p00, p10 = (xs[i], ys[j], h[i][j]), (xs[i + 1], ys[j], h[i + 1][j])
            p01, p11 = (xs[i], ys[j + 1], h[i][j + 1]), (xs[i + 1], ys[j + 1], h[i + 1][j + 1])
            if (i + j) % 2 == 0:
                surface.face([p00, p10, p11], up)
                surface.face([p00, p11, p01], up)
            else:
                surface.face([p00, p10, p01], up)
                surface.face([p10, p11, p01], up)
    for i in range(nx):
        for j, y, sign in ((0, y0, -1), (ny, y1, 1)):
            surface.face([(xs[i], y, z0), (xs[i + 1], y, z0), (xs[i + 1], y, h[i + 1][j]), (xs[i], y, h[i][j])],
                         (0, sign, 0))
    for j in range(ny):
        for i, x, sign in ((0, x0, -1), (nx, x1, 1)):
            surface.face([(x, ys[j], z0), (x, ys[j + 1], z0), (x, ys[j + 1], h[i][j + 1]), (x, ys[j], h[i][j])],
                         (sign, 0, 0))
    if bottom:
        surface.face([(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)], (0, 0, -1))


# ---- swept and revolved shapes (metres) ---------------------------------------------

def _oriented(vertices, triangles):
    """The mesh, its triangles flipped if they face inwards."""
    volume = sum(_dot(vertices[a], _cross(vertices[b], vertices[c])) for a, b, c in triangles)
    if volume < 0:
        triangles = [(a, c, b) for a, b, c in triangles]
    return TriMesh([tuple(round(x, 6) + 0.0 for x in v) for v in vertices], triangles)


def _rings(first_pole, rings, last_pole):
    """Triangles joining a pole (a vertex index or None), rings of equally
    many vertex indices and another pole; quads split along alternating
    diagonals."""
    tris = []
    m = len(rings[0])
    if first_pole is not None:
        tris += [(first_pole, rings[0][(j + 1) % m], rings[0][j]) for j in range(m)]
    for k in range(len(rings) - 1):
        a, b = rings[k], rings[k + 1]
        for j in range(m):
            j1 = (j + 1) % m
            if (j + k) % 2 == 0:
                tris += [(a[j], a[j1], b[j1]), (a[j], b[j1], b[j])]
            else:
                tris += [(a[j], a[j1], b[j]), (a[j1], b[j1], b[j])]
    if last_pole is not None:
        tris += [(last_pole, rings[-1][j], rings[-1][(j + 1) % m]) for j in range(m)]
    return tris


def revolve(profile, m):
    """The solid of revolution about z of a profile [(r, z), ...] that starts
    and ends on the axis (r = 0) and has r > 0 in between; m steps around."""
    vertices = [(0.0, 0.0, profile[0][1])]
    rings = []
    for r, z in profile[1:-1]:
        rings.append(list(range(len(vertices), len(vertices) + m)))
        vertices += [(r * math.cos(2 * math.pi * j / m), r * math.sin(2 * math.pi * j / m), z) for j in range(m)]
    vertices.append((0.0, 0.0, profile[-1][1]))
    return _oriented(vertices, _rings(0, rings, len(vertices) - 1))


def subdivide(polyline, max_length):
    """The polyline with each segment cut into equal pieces of at most max_length."""
    out = [polyline[0]]
    for p, q in zip(polyline, polyline[1:]):
        k = max(1, math.ceil(math.dist(p, q) / max_length))
        out += [tuple(p[i] + (q[i] - p[i]) * s / k for i in range(len(p))) for s in range(1, k + 1)]
    return out


def lat_long_body(radius, bands, m):
    """A star-shaped body: the point at radius(theta, phi) in each direction
    (theta from +z), on `bands` bands of latitude and m meridians."""
    vertices = [(0.0, 0.0, radius(0.0, 0.0))]
    rings = []
    for k in range(1, bands):
        theta = math.pi * k / bands
        rings.append(list(range(len(vertices), len(vertices) + m)))
        for j in range(m):
            phi = 2 * math.pi * j / m
            r = radius(theta, phi)
            vertices.append((r * math.sin(theta) * math.cos(phi), r * math.sin(theta) * math.sin(phi),
                             r * math.cos(theta)))
    vertices.append((0.0, 0.0, -radius(math.pi, 0.0)))
    return _oriented(vertices, _rings(0, rings, len(vertices) - 1))


def swept_bar(sections):
    """A bar through cross-sections (lists of equally many 3D points, convex
    polygons in order), closed by a flat cap at each end (fans)."""
    vertices = [p for s in sections for p in s]
    m = len(sections[0])
    rings = [list(range(k * m, (k + 1) * m)) for k in range(len(sections))]
    tris = _rings(None, rings, None)
    tris += [(rings[0][0], rings[0][j + 1], rings[0][j]) for j in range(1, m - 1)]
    tris += [(rings[-1][0], rings[-1][j], rings[-1][j + 1]) for j in range(1, m - 1)]
    return _oriented(vertices, tris)


# ---- exact convex hull --------------------------------------------------------------

def exact_hull(points, scale):
    """The convex hull of points whose coordinates are multiples of 1/scale,
    computed on the integers scale * p (exact): returns (vertices, triangles)
    with only the hull's corners as vertices and each face (a convex polygon
    of exactly coplanar corners) fanned from one corner, counter-clockwise
    seen from outside. O(n^4): for a few dozen points."""
    q = [tuple(int(round(c * scale)) for c in p) for p in points]
    q = sorted(set(q))
    n = len(q)
    faces = {}
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                normal = _cross(_sub(q[j], q[i]), _sub(q[k], q[i]))
                if normal == (0, 0, 0):
                    continue
                side = [_dot(normal, _sub(p, q[i])) for p in q]
                if all(s <= 0 for s in side):
                    pass
                elif all(s >= 0 for s in side):
                    normal = tuple(-c for c in normal)
                else:
                    continue
                on = tuple(sorted(l for l in range(n) if side[l] == 0))
                faces.setdefault(on, normal)
    corners = set()
    polygons = []
    for on, normal in sorted(faces.items()):
        loop = _polygon_corners([q[l] for l in on], on, normal)
        polygons.append(loop)
        corners.update(loop)
    index = {l: k for k, l in enumerate(sorted(corners))}
    vertices = [tuple(c / scale for c in q[l]) for l in sorted(corners)]
    triangles = []
    for loop in polygons:
        triangles += [(index[loop[0]], index[loop[k]], index[loop[k + 1]]) for k in range(1, len(loop) - 1)]
    return vertices, triangles


def _polygon_corners(pts, labels, normal):
    """The strict corners of the convex hull of coplanar integer points,
    counter-clockwise about `normal` (gift wrapping, exact)."""
    start = min(range(len(pts)), key=lambda k: pts[k])
    loop = [start]
    while True:
        cur = loop[-1]
        best = None
        for k in range(len(pts)):
            if k == cur:
                continue
            if best is None:
                best = k
                continue
            turn = _dot(_cross(_sub(pts[best], pts[cur]), _sub(pts[k], pts[cur])), normal)
            farther = _dot(_sub(pts[k], pts[cur]), _sub(pts[k], pts[cur])) > \
                _dot(_sub(pts[best], pts[cur]), _sub(pts[best], pts[cur]))
            if turn < 0 or (turn == 0 and farther):
                best = k
        if best == start:
            break
        loop.append(best)
    return [labels[k] for k in loop]
