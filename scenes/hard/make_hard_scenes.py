#!/usr/bin/env python3
"""Writes the hard-case scenes of issue 6 (scenes/hard/*.obj + .mtl).

Run from anywhere: python3 scenes/hard/make_hard_scenes.py. Every face is a planar convex
polygon listed counter-clockwise seen from its lit (front) side. The tests in
tests/unit/hard_*_test.cc load these files and state the closed form each one checks.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


class Obj:
    def __init__(self, header):
        self.lines = ["# " + l if l else "#" for l in header.strip().split("\n")]
        self.n = 0

    def face(self, obj, mtl, pts):
        self.lines.append(f"o {obj}")
        self.lines.append(f"usemtl {mtl}")
        for p in pts:
            self.lines.append("v " + " ".join(f"{c:.17g}" for c in p))
        self.lines.append("f " + " ".join(str(self.n + k + 1) for k in range(len(pts))))
        self.n += len(pts)

    def rect(self, obj, mtl, corner, du, dv):
        """Parallelogram corner, corner+du, corner+du+dv, corner+dv; front = du x dv."""
        c = corner
        self.face(obj, mtl, [c, add(c, du), add(add(c, du), dv), add(c, dv)])

    def write(self, name, mtl_name):
        """Header comment first, then mtllib, then the geometry."""
        header = [l for l in self.lines if l.startswith("#")]
        body = [l for l in self.lines if not l.startswith("#")]
        with open(os.path.join(HERE, name), "w") as f:
            f.write("\n".join(header + [f"mtllib {mtl_name}"] + body) + "\n")


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def write_mtl(name, header, materials):
    lines = ["# " + l for l in header.strip().split("\n")]
    for m, kd, ke in materials:
        lines += [f"newmtl {m}", f"Kd {kd} {kd} {kd}"]
        if ke:
            lines.append(f"Ke {ke} {ke} {ke}")
    with open(os.path.join(HERE, name), "w") as f:
        f.write("\n".join(lines) + "\n")


def box(o, mtl, x0, x1, y0, y1, z0, z1, prefix="", s=1.0, skip=()):
    """The six faces of an axis-aligned box, facing inward; s scales coordinates."""
    X, Y, Z = (x1 - x0) * s, (y1 - y0) * s, (z1 - z0) * s
    lo = (x0 * s, y0 * s, z0 * s)
    faces = {
        "floor": (lo, (X, 0, 0), (0, Y, 0)),
        "ceiling": ((lo[0], lo[1], lo[2] + Z), (0, Y, 0), (X, 0, 0)),
        "wall_x0": (lo, (0, Y, 0), (0, 0, Z)),
        "wall_x1": ((lo[0] + X, lo[1], lo[2]), (0, 0, Z), (0, Y, 0)),
        "wall_y0": (lo, (0, 0, Z), (X, 0, 0)),
        "wall_y1": ((lo[0], lo[1] + Y, lo[2]), (X, 0, 0), (0, 0, Z)),
    }
    for name, (c, du, dv) in faces.items():
        if name not in skip:
            o.rect(prefix + name, mtl, c, du, dv)


def white_rooms():
    write_mtl("white_room.mtl", "Closed white rooms (furnace): every surface reflects rho and glows Ke = 1\n"
              "(E = pi W/m^2), so B = E / (1 - rho) = pi / (1 - rho) everywhere.",
              [("white99", 0.99, 1), ("white999", 0.999, 1)])
    for tag, mtl, rho in (("099", "white99", 0.99), ("0999", "white999", 0.999)):
        o = Obj(f"Hard case: closed white room 4 x 3 x 2.5 m, rho = {rho} on every face, every face\n"
                f"glowing Ke = 1. Invariant (furnace): B = pi / (1 - rho) = {math.pi / (1 - rho):.6g} W/m^2 on\n"
                "every patch; Jacobi needs ~ln(tol)/ln(rho) sweeps, CG far fewer.\n"
                "Test: tests/unit/hard_room_test.cc (HardRoom.*).")
        box(o, mtl, 0, 4, 0, 3, 0, 2.5)
        o.write(f"white_room_rho{tag}.obj", "white_room.mtl")


def wedges():
    write_mtl("wedge.mtl", "Two plates sharing an edge: grey, no emission needed for view factors\n"
              "(the lamp material makes the scene valid).", [("white", 0.5, 0), ("lamp", 0.5, 1)])
    for deg in (90, 10):
        phi = math.radians(deg)
        o = Obj(f"Hard case: rectangle a (1 x 1.3, floor, facing +z) and rectangle b (0.7 x 1.3)\n"
                f"sharing the edge x = z = 0, y in [0, 1.3], at an opening angle of {deg} degrees, both\n"
                "facing into the wedge. Closed form: Howell's two rectangles with a common edge at\n"
                "angle phi (testing::AngledRectangles; C-14 at 90 degrees). F_ab = "
                f"see hard_geometry_test.cc.\nTest: tests/unit/hard_geometry_test.cc (HardWedge.*).")
        o.rect("a", "white", (0, 0, 0), (1, 0, 0), (0, 1.3, 0))
        d = (0.7 * math.cos(phi), 0, 0.7 * math.sin(phi))
        o.rect("b", "lamp", (0, 0, 0), (0, 1.3, 0), d)
        o.write(f"wedge_{deg}.obj", "wedge.mtl")


def slivers():
    write_mtl("slivers.mtl", "Closed unit box: white rho 0.5; the wall y = 1 is a lamp (rho 0.5, Ke 1).",
              [("white", 0.5, 0), ("lamp", 0.5, 1)])
    o = Obj("Hard case: closed unit box whose floor is ten 1 x 0.001 slivers (aspect 1:1000) plus one\n"
            "large piece, and whose ceiling holds a tiny 0.001 x 0.001 patch (1e-6 of the face)\n"
            "framed by two 0.001 x 0.5 slivers and two large halves. Mesh: one patch per face.\n"
            "The wall y = 1 glows (only it: monte_carlo traces every other column).\n"
            "Invariants: closed box, so every row sums to 1; reciprocity A_i F_ij = A_j F_ji.\n"
            "Test: tests/unit/hard_geometry_test.cc (HardSliver.*).")
    t = 0.001
    for k in range(10):
        o.rect(f"sliver{k}", "white", (0, k * t, 0), (1, 0, 0), (0, t, 0))
    o.rect("floor_rest", "white", (0, 10 * t, 0), (1, 0, 0), (0, 1 - 10 * t, 0))
    # ceiling z = 1 facing -z: du = +y, dv = +x
    o.rect("tiny", "white", (0.5, 0.5, 1), (0, t, 0), (t, 0, 0))
    o.rect("ceil_left", "white", (0, 0, 1), (0, 1, 0), (0.5, 0, 0))
    o.rect("ceil_right", "white", (0.5 + t, 0, 1), (0, 1, 0), (0.5 - t, 0, 0))
    o.rect("ceil_front", "white", (0.5, 0, 1), (0, 0.5, 0), (t, 0, 0))
    o.rect("ceil_back", "white", (0.5, 0.5 + t, 1), (0, 0.5 - t, 0), (t, 0, 0))
    box(o, "white", 0, 1, 0, 1, 0, 1, skip=("floor", "ceiling", "wall_y1"))
    o.rect("wall_y1", "lamp", (0, 1, 0), (1, 0, 0), (0, 0, 1))
    o.write("slivers.obj", "slivers.mtl")


def leak():
    write_mtl("leak_two_rooms.mtl", "White walls, a lamp (radiance 10) in room A only.",
              [("white", 0.5, 0), ("lamp", 0.0, 10)])
    g = 1e-4
    o = Obj("Hard case: rooms A (x in [0,1]) and B (x in [1,2]), 1 m high and deep, lit only by a lamp\n"
            "in A. The dividing wall is two coincident back-to-back faces at x = 1 (coplanar, opposite\n"
            f"normals) that stop a hairline gap g = {g} m above the floor; room A's floor also carries a\n"
            "coplanar overlapping 'rug' face. Bound: light can reach B only through the gap, so the\n"
            "power arriving on B's surfaces is at most max_A(B) * g * 1 m (radiance <= B/pi through an\n"
            "opening of area g * 1 m). Test: tests/unit/hard_geometry_test.cc (HardLeak.*).")
    box(o, "white", 0, 1, 0, 1, 0, 1, prefix="a_", skip=("wall_x1",))
    box(o, "white", 1, 2, 0, 1, 0, 1, prefix="b_", skip=("wall_x0",))
    o.rect("a_rug", "white", (0.2, 0.2, 0), (0.6, 0, 0), (0, 0.6, 0))
    o.rect("a_divider", "white", (1, 0, g), (0, 0, 1 - g), (0, 1, 0))   # faces -x, into A
    o.rect("b_divider", "white", (1, 0, g), (0, 1, 0), (0, 0, 1 - g))   # faces +x, into B
    o.rect("a_lamp", "lamp", (0.4, 0.4, 0.99), (0, 0.2, 0), (0.2, 0, 0))  # faces -z
    o.write("leak_two_rooms.obj", "leak_two_rooms.mtl")


def tiny_emitter():
    write_mtl("tiny_emitter.mtl", "Receiver and emitter both rho 0.5; the emitter has radiance 1e6.",
              [("white", 0.5, 0), ("lamp", 0.5, 1e6)])
    o = Obj("Hard case: a 0.01 x 0.01 emitter (1e-4 of the scene area) of radiance 1e6 (E = pi e6\n"
            "W/m^2), centred 0.5 above a 1 x 1 receiver and facing it. Closed form: power reflected by\n"
            "the receiver = rho A_e F_er E (B-3 by corner superposition, integrated over the emitter),\n"
            "plus a second bounce below 1e-5 relative. Test: tests/unit/hard_light_test.cc (HardLight.TinyBrightEmitterMatchesEtimesF).")
    o.rect("receiver", "white", (-0.5, -0.5, 0), (1, 0, 0), (0, 1, 0))
    o.rect("emitter", "lamp", (-0.005, -0.005, 0.5), (0, 0.01, 0), (0.01, 0, 0))
    o.write("tiny_emitter.obj", "tiny_emitter.mtl")


def opening_room():
    write_mtl("opening_room.mtl", "Walls rho 0.7; the sky panel is black (rho 0) and glows Ke = 1.",
              [("white", 0.7, 0), ("sky", 0.0, 1)])
    o = Obj("Hard case: a closed 2 m room lit only through a 0.2 x 0.2 window in the wall x = 0, by a\n"
            "0.2 x 0.2 black sky panel (Ke = 1, E = pi) 0.1 m outside, directly opposite the window.\n"
            "Closed form: the power entering = E * A_w * F (C-11, identical opposed rectangles);\n"
            "energy conservation: entering = absorbed inside + leaving through the window.\n"
            "Test: tests/unit/hard_light_test.cc (HardLight.RoomLitThroughASmallOpening).")
    box(o, "white", 0, 2, 0, 2, 0, 2, skip=("wall_x0",))
    lo, hi = 0.9, 1.1
    # wall x = 0 facing +x: du = +y, dv = +z, split around the window into four convex pieces
    o.rect("wall_x0_left", "white", (0, 0, 0), (0, lo, 0), (0, 0, 2))
    o.rect("wall_x0_right", "white", (0, hi, 0), (0, 2 - hi, 0), (0, 0, 2))
    o.rect("wall_x0_below", "white", (0, lo, 0), (0, hi - lo, 0), (0, 0, lo))
    o.rect("wall_x0_above", "white", (0, lo, hi), (0, hi - lo, 0), (0, 0, 2 - hi))
    o.rect("sky", "sky", (-0.1, lo, lo), (0, hi - lo, 0), (0, 0, hi - lo))
    o.write("opening_room.obj", "opening_room.mtl")


def scaled_rooms():
    write_mtl("room_scale.mtl", "The scaled rooms' materials: white walls, a red wall, a ceiling lamp.",
              [("white", 0.7, 0), ("red", 0.5, 0), ("lamp", 0.7, 5)])
    for tag, s, unit in (("um", 1e-6, "micrometres"), ("km", 1e3, "kilometres")):
        o = Obj(f"Hard case: the same 5 x 4 x 3 room with a lamp and a block, in {unit} (coordinates =\n"
                f"metres x {s:g}). Invariant: B (W/m^2) does not depend on the unit; the micrometre and\n"
                "kilometre rooms must give the same B per patch (relative 1e-5).\n"
                "Test: tests/unit/hard_room_test.cc (HardScale.*).")
        box(o, "white", 0, 5, 0, 4, 0, 3, s=s, skip=("ceiling", "wall_x0"))
        o.rect("wall_x0", "red", (0, 0, 0), (0, 4 * s, 0), (0, 0, 3 * s))
        # ceiling z = 3 facing -z (du = +y, dv = +x), split around a 1 x 1 lamp at x, y in [2, 3]
        z = 3 * s
        o.rect("ceiling_a", "white", (0, 0, z), (0, 4 * s, 0), (2 * s, 0, 0))
        o.rect("ceiling_b", "white", (3 * s, 0, z), (0, 4 * s, 0), (2 * s, 0, 0))
        o.rect("ceiling_c", "white", (2 * s, 0, z), (0, 2 * s, 0), (1 * s, 0, 0))
        o.rect("ceiling_d", "white", (2 * s, 3 * s, z), (0, 1 * s, 0), (1 * s, 0, 0))
        o.rect("lamp", "lamp", (2 * s, 2 * s, z), (0, 1 * s, 0), (1 * s, 0, 0))
        # a 1 x 1 x 1 block on the floor, outward faces (no bottom)
        x0, y0 = 1.0, 1.0
        c = lambda x, y, zz: (x * s, y * s, zz * s)
        o.rect("block_top", "white", c(x0, y0, 1), (s, 0, 0), (0, s, 0))
        o.rect("block_x0", "white", c(x0, y0, 0), (0, 0, s), (0, s, 0))
        o.rect("block_x1", "white", c(x0 + 1, y0, 0), (0, s, 0), (0, 0, s))
        o.rect("block_y0", "white", c(x0, y0, 0), (s, 0, 0), (0, 0, s))
        o.rect("block_y1", "white", c(x0, y0 + 1, 0), (0, 0, s), (s, 0, 0))
        o.write(f"room_{tag}.obj", "room_scale.mtl")


if __name__ == "__main__":
    white_rooms()
    wedges()
    slivers()
    leak()
    tiny_emitter()
    opening_room()
    scaled_rooms()
