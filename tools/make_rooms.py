#!/usr/bin/env python3
"""Generates the OBJ geometry of the shipped rooms (rooms/l-hall.obj, rooms/two-rooms.obj, rooms/classroom.obj).

Each room is air cells on a rectilinear grid (coordinate cuts along x, y and z): a face between an air
cell and a solid cell (or the outside) becomes a quad facing into the air. Because every face is cut at
the same global coordinates, neighbouring faces share their edges exactly (no T-junctions), so the mesh
is closed, and the room volume is the sum of the air cells: a closed form the tests check against.
Output is deterministic: run `python3 tools/make_rooms.py` from the repository root and commit the files.
Python 3 standard library only.
"""
import os
import sys

ROOMS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "rooms")


def cuts(*ranges_and_points, step=None):
    """Sorted unique coordinates: the given points, plus uniform cuts of at most `step` between them."""
    pts = sorted(set(round(p, 9) for p in ranges_and_points))
    if step is None:
        return pts
    out = []
    for a, b in zip(pts, pts[1:]):
        n = max(1, int(-(-(b - a) // step)))  # ceil
        out += [round(a + (b - a) * i / n, 9) for i in range(n)]
    return out + [pts[-1]]


def inside(box, p):
    return all(box[0][i] < p[i] < box[1][i] for i in range(3))


class Grid:
    """Cells of a rectilinear grid, each air or solid; emits the air/solid faces as quads."""

    def __init__(self, xs, ys, zs, is_air):
        self.c = (xs, ys, zs)
        self.is_air = is_air
        self.air = {}
        for i in range(len(xs) - 1):
            for j in range(len(ys) - 1):
                for k in range(len(zs) - 1):
                    centre = ((xs[i] + xs[i + 1]) / 2, (ys[j] + ys[j + 1]) / 2, (zs[k] + zs[k + 1]) / 2)
                    self.air[(i, j, k)] = is_air(centre)

    def volume(self):
        xs, ys, zs = self.c
        return sum((xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * (zs[k + 1] - zs[k])
                   for (i, j, k), a in self.air.items() if a)

    def faces(self):
        """(axis, sign, plane index, cell index, quad corners as grid indices); sign = direction of
        the normal (into the air cell) along `axis`."""
        out = []
        for cell, a in sorted(self.air.items()):
            if not a:
                continue
            for axis in range(3):
                for sign in (-1, 1):
                    nb = list(cell)
                    nb[axis] += sign
                    if self.air.get(tuple(nb), False):
                        continue
                    # The face lies on the cell's side towards the neighbour; its normal points back
                    # into the cell, i.e. along -sign.
                    plane = cell[axis] + (1 if sign > 0 else 0)
                    b, c = (axis + 1) % 3, (axis + 2) % 3  # e_b x e_c = e_axis
                    corners = []
                    for db, dc in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        g = [0, 0, 0]
                        g[axis] = plane
                        g[b] = cell[b] + db
                        g[c] = cell[c] + dc
                        corners.append(tuple(g))
                    if -sign < 0:
                        corners.reverse()
                    out.append((axis, -sign, plane, cell, corners))
        return out

    def point(self, g):
        return tuple(self.c[a][g[a]] for a in range(3))


def write_obj(path, header, grid, faces_by_group, extra_quads=()):
    """faces_by_group: {group: [corner lists]}; extra_quads: [(group, [points])] given as coordinates."""
    index = {}
    lines = ["# " + h for h in header]
    verts = []

    def vid(p):
        if p not in index:
            index[p] = len(verts) + 1
            verts.append(p)
        return index[p]

    body = []
    groups = dict(faces_by_group)
    for g, quads in extra_quads:
        groups.setdefault(g, []).extend(quads)
    quad_count = 0
    for g in sorted(groups):
        body.append("g " + g)
        for q in groups[g]:
            pts = [grid.point(c) if isinstance(c[0], int) else c for c in q]
            body.append("f " + " ".join(str(vid(p)) for p in pts))
            quad_count += 1
    lines += ["v %s %s %s" % tuple(fmt(x) for x in p) for p in verts]
    lines += body
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return quad_count


def fmt(x):
    s = ("%.6f" % x).rstrip("0").rstrip(".")
    return "0" if s == "-0" else s


def write_rooms_with_opening(name, header, grid, group, opening_group, opening, volume_closed_form):
    """Groups the grid's faces by `group`, adds the opening quad as its own group, checks the volume against
    the closed form and writes rooms/NAME.obj. Returns main()'s summary tuple."""
    groups = {}
    for axis, normal, plane, cell, corners in grid.faces():
        groups.setdefault(group(axis, normal, plane, cell), []).append(corners)
    assert abs(grid.volume() - volume_closed_form) < 1e-6, (grid.volume(), volume_closed_form)
    quads = write_obj(os.path.join(ROOMS, name + ".obj"), header, grid, groups, [(opening_group, [opening])])
    return name + ".obj", quads, volume_closed_form, sorted(set(groups) | {opening_group})


def l_hall():
    # An L-shaped hall: arm 1 is [0,24]x[0,12], arm 2 is [0,12]x[12,24], 7 m high. A 1 m high stage
    # fills x in [18,24] of arm 1; four 0.5 x 0.5 m columns stand floor to ceiling.
    H, STAGE_X, STAGE_H = 7.0, 18.0, 1.0
    columns = [(8.0, 3.0), (8.0, 9.0), (3.0, 16.0), (9.0, 16.0)]
    half = 0.25
    col_boxes = [((x - half, y - half, 0.0), (x + half, y + half, H)) for x, y in columns]
    stage = ((STAGE_X, 0.0, 0.0), (24.0, 12.0, STAGE_H))
    arm1 = ((0.0, 0.0, 0.0), (24.0, 12.0, H))
    arm2 = ((0.0, 12.0, 0.0), (12.0, 24.0, H))

    def is_air(p):
        if not (inside(arm1, p) or inside(arm2, p)):
            return False
        return not inside(stage, p) and not any(inside(b, p) for b in col_boxes)

    col_x = [c for x, _ in columns for c in (x - half, x + half)]
    col_y = [c for _, y in columns for c in (y - half, y + half)]
    xs = cuts(0.0, 12.0, STAGE_X, 24.0, *col_x, step=2.0)
    ys = cuts(0.0, 12.0, 24.0, *col_y, step=2.0)
    zs = cuts(0.0, STAGE_H, H, step=1.5)
    grid = Grid(xs, ys, zs, is_air)

    def group(axis, normal, plane, cell):
        p = grid.point((plane, 0, 0) if axis == 0 else (0, plane, 0) if axis == 1 else (0, 0, plane))[axis]
        centre = [(grid.c[a][cell[a]] + grid.c[a][cell[a] + 1]) / 2 for a in range(3)]
        for bx in col_boxes:  # faces on a column's sides
            if axis < 2 and abs(p - (bx[0][axis] if normal < 0 else bx[1][axis])) < 1e-9:
                other = 1 - axis
                if bx[0][other] < centre[other] < bx[1][other]:
                    return "columns"
        if axis == 2:
            if normal < 0:
                return "ceiling"
            if abs(p - STAGE_H) < 1e-9:
                return "stage-floor"
            return "seating" if centre[1] > 14.0 else "floor"
        if axis == 0 and normal < 0 and abs(p - STAGE_X) < 1e-9 and centre[2] < STAGE_H:
            return "stage-front"
        if axis == 1 and normal < 0 and abs(p - 24.0) < 1e-9:
            return "rear-wall"
        return "walls"

    groups = {}
    for axis, normal, plane, cell, corners in grid.faces():
        groups.setdefault(group(axis, normal, plane, cell), []).append(corners)
    volume_closed_form = (24 * 12 + 12 * 12) * H - (24 - STAGE_X) * 12 * STAGE_H - len(columns) * (2 * half) ** 2 * H
    assert abs(grid.volume() - volume_closed_form) < 1e-6, (grid.volume(), volume_closed_form)
    header = ["l-hall: generated by tools/make_rooms.py; do not edit by hand.",
              "L-shaped hall [0,24]x[0,12] + [0,12]x[12,24], 7 m high, stage x in [18,24] 1 m high,",
              "four 0.5 x 0.5 m columns at (8,3) (8,9) (3,16) (9,16). Faces face into the room.",
              "volume = 432*7 - 72 - 4*0.25*7 = %s m^3" % fmt(volume_closed_form)]
    quads = write_obj(os.path.join(ROOMS, "l-hall.obj"), header, grid, groups)
    return "l-hall.obj", quads, volume_closed_form, sorted(groups)


def two_rooms():
    # Room A [0,6]x[0,5]x[0,3] and room B [6.2,10.2]x[0,4]x[0,3] behind a 0.2 m partition (x in [6,6.2])
    # with a 0.9 x 2.1 m doorway (y in [1,1.9], z in [0,2.1]); the opening rectangle sits at x = 6.1.
    H, WALL0, WALL1, MID = 3.0, 6.0, 6.2, 6.1
    door = ((WALL0, 1.0, 0.0), (WALL1, 1.9, 2.1))
    a = ((0.0, 0.0, 0.0), (WALL0, 5.0, H))
    b = ((WALL1, 0.0, 0.0), (10.2, 4.0, H))

    def is_air(p):
        return inside(a, p) or inside(b, p) or inside(door, p)

    # Coarse cuts that keep the doorway one cell, so that the opening is one explicit rectangle.
    xs = cuts(0.0, 2.0, 4.0, WALL0, MID, WALL1, 8.2, 10.2)
    ys = cuts(0.0, 1.0, 1.9, 3.0, 4.0, 5.0)
    zs = cuts(0.0, 2.1, H)
    grid = Grid(xs, ys, zs, is_air)

    def group(axis, normal, plane, cell):
        centre = [(grid.c[k][cell[k]] + grid.c[k][cell[k] + 1]) / 2 for k in range(3)]
        if inside(door, centre):
            return "doorway-reveal"
        prefix = "a-" if centre[0] < WALL0 else "b-"
        if axis == 2:
            return prefix + ("floor" if normal > 0 else "ceiling")
        return prefix + "walls"

    # The opening: one quad at the partition's mid-plane, facing +x (from room A into room B).
    opening = [(MID, 1.0, 0.0), (MID, 1.9, 0.0), (MID, 1.9, 2.1), (MID, 1.0, 2.1)]
    volume_closed_form = 6 * 5 * H + 4 * 4 * H + 0.2 * 0.9 * 2.1
    header = ["two-rooms: generated by tools/make_rooms.py; do not edit by hand.",
              "Room A [0,6]x[0,5]x[0,3], room B [6.2,10.2]x[0,4]x[0,3], partition x in [6,6.2] with a",
              "doorway y in [1,1.9], z in [0,2.1]; group 'doorway' is the opening at x = 6.1.",
              "volume = 90 + 48 + 0.378 = %s m^3 (the opening bounds nothing)" % fmt(volume_closed_form)]
    return write_rooms_with_opening("two-rooms", header, grid, group, "doorway", opening, volume_closed_form)


def classroom():
    # A classroom [0,9]x[0,7]x[0,3.2] and a corridor [-1.5,10.5]x[7.2,9.2]x[0,3.2] behind a 0.2 m wall
    # (y in [7,7.2]) with a 0.9 x 2.1 m door (x in [7,7.9], z in [0,2.1]); the opening rectangle sits at
    # y = 7.1. The front wall (board) is x = 0, the windows y = 0, the rear wall x = 9.
    H, WALL0, WALL1, MID = 3.2, 7.0, 7.2, 7.1
    door = ((7.0, WALL0, 0.0), (7.9, WALL1, 2.1))
    room = ((0.0, 0.0, 0.0), (9.0, WALL0, H))
    corridor = ((-1.5, WALL1, 0.0), (10.5, 9.2, H))

    def is_air(p):
        return inside(room, p) or inside(corridor, p) or inside(door, p)

    xs = cuts(-1.5, 0.0, 3.5, 7.0, 7.9, 9.0, 10.5)
    ys = cuts(0.0, 3.5, WALL0, MID, WALL1, 9.2)
    zs = cuts(0.0, 2.1, H)
    grid = Grid(xs, ys, zs, is_air)

    def group(axis, normal, plane, cell):
        centre = [(grid.c[k][cell[k]] + grid.c[k][cell[k] + 1]) / 2 for k in range(3)]
        if inside(door, centre):
            return "door-reveal"
        if centre[1] > WALL0:
            return "corridor-" + (("floor" if normal > 0 else "ceiling") if axis == 2 else "walls")
        if axis == 2:
            return "class-floor" if normal > 0 else "class-ceiling"
        if axis == 0:
            return "class-front-wall" if normal > 0 else "class-rear-wall"
        return "class-windows" if normal > 0 else "class-walls"

    # The opening: one quad at the wall's mid-plane, facing +y (from the classroom into the corridor).
    opening = [(7.9, MID, 0.0), (7.0, MID, 0.0), (7.0, MID, 2.1), (7.9, MID, 2.1)]
    volume_closed_form = 9 * 7 * H + 12 * 2 * H + 0.9 * 0.2 * 2.1
    header = ["classroom: generated by tools/make_rooms.py; do not edit by hand.",
              "Classroom [0,9]x[0,7]x[0,3.2], corridor [-1.5,10.5]x[7.2,9.2]x[0,3.2], wall y in [7,7.2] with a",
              "door x in [7,7.9], z in [0,2.1]; group 'door' is the opening at y = 7.1.",
              "volume = 201.6 + 76.8 + 0.378 = %s m^3 (the opening bounds nothing)" % fmt(volume_closed_form)]
    return write_rooms_with_opening("classroom", header, grid, group, "door", opening, volume_closed_form)


def main():
    for name, quads, volume, groups in (l_hall(), two_rooms(), classroom()):
        print("%s: %d quads (%d triangles), volume %s m^3, groups %s" %
              (name, quads, 2 * quads, fmt(volume), ", ".join(groups)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
