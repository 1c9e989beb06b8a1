"""racebot_gazebo/worlds/room_mini.world against the original world's numbers (docs:
/work/shared/reference/RACEBOT.md, "World"): SDF 1.6, the physics block, the ground plane, the
17 walls of the static model room1, the free-standing objects, and a clear spawn point at (0, 0).

Plain xml.etree and plane geometry; needs no ROS master and no simulator module. Every footprint
is taken in the ground plane: all poses here are x, y, yaw (roll and pitch are checked to be 0).
"""
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
WORLD = REPO / "racebot_gazebo" / "worlds" / "room_mini.world"

ROOM_POSE = (-2.73, -1.05, 0.0)
WALL_THICKNESS = 0.15
WALL_HEIGHT = 2.5
# wall link: (x, y, yaw) in the room frame, length
WALLS = {
    "Wall_0": (3.875, -0.8, 0, 6),
    "Wall_1": (6.8, 2.875, 1.5708, 7.5),
    "Wall_2": (0, 6.55, 3.14159, 13.75),
    "Wall_3": (-6.8, 0, -1.5708, 13.25),
    "Wall_4": (-3, -6.55, 0, 7.75),
    "Wall_5": (0.8, -3.25, 1.5708, 6.75),
    "Wall_6": (-2.67763, 0.061278, 3.13835, 1.23276),
    "Wall_7": (-6.15527, 0.072556, 0, 0.15),
    "Wall_8": (-6.45151, 0.072556, 3.14159, 0.75),
    "Wall_10": (-3.67001, 3.80845, -1.5708, 1.25),
    "Wall_11": (0.379989, 3.25845, 0, 8.25),
    "Wall_12": (4.42999, 3.68345, 1.5708, 1),
    "Wall_13": (0.379989, 4.10845, 3.14159, 8.25),
    "Wall_16": (-4.77196, -3.2131, -1.5708, 2.75),
    "Wall_17": (-3.09696, -4.5131, 0, 3.5),
    "Wall_18": (-1.42196, -3.2131, 1.5708, 2.75),
    "Wall_19": (-3.22196, -1.9131, 3.14159, 3.75),
}
# the outer boundary, in order around the room
OUTER_WALLS = ("Wall_0", "Wall_1", "Wall_2", "Wall_3", "Wall_4", "Wall_5")

# model: (world x, world y, static, a collision shape of the stated size)
OBJECTS = {
    "cube_20k": (-8.709, 4.198, False, ("box", (0.5, 0.5, 0.5))),
    "construction_barrel": (-8.910, -1.610, False, ("cylinder", (0.29, 0.9))),
    "frc2016_ball": (-9.155, -5.247, False, ("sphere", (0.127,))),
    "grey_tote": (-2.343, -6.330, False, ("box", (0.678, 0.413, 0.016))),
    "warehouse_robot": (2.125, -0.464, True, ("box", (0.555, 1.023, 0.409))),
    "first_2015_trash_can": (-8.654, 0.037, False, ("cylinder", (0.27, 0.8))),
    "first_2015_trash_can_0": (3.398, 5.127, False, ("cylinder", (0.27, 0.8))),
    "cinder_block_2": (-9.063, -7.052, False, ("box", (0.194, 0.397, 0.025))),
    "cinder_block_wide": (3.691, 1.209, False, ("box", (0.387, 0.387, 0.025))),
    "cinder_block": (-5.101, 4.387, False, ("box", (0.435, 0.034, 0.203))),
    "drc_practice_blue_cylinder": (-3.653, 4.320, True, ("cylinder", (0.15, 1.0))),
    "drc_practice_blue_cylinder_0": (-1.908, 0.817, True, ("cylinder", (0.15, 1.0))),
}

SPAWN = (0.0, 0.0)
# the car's footprint (0.28 m chassis, 0.18 m track plus tyres) fits in this circle
CAR_RADIUS = 0.2


@pytest.fixture(scope="module")
def sdf():
    return ET.parse(WORLD).getroot()


@pytest.fixture(scope="module")
def world(sdf):
    worlds = sdf.findall("world")
    assert len(worlds) == 1
    return worlds[0]


@pytest.fixture(scope="module")
def models(world):
    return {m.get("name"): m for m in world.findall("model")}


def floats(text):
    return [float(v) for v in text.split()]


def pose_of(element):
    """(x, y, z, yaw) of an element's <pose>; roll and pitch must be 0."""
    text = element.findtext("pose")
    x, y, z, roll, pitch, yaw = floats(text) if text else [0.0] * 6
    assert (roll, pitch) == (0.0, 0.0), element.get("name")
    return x, y, z, yaw


def compose(a, b):
    """Planar pose a * b, each (x, y, yaw)."""
    ax, ay, ayaw = a
    bx, by, byaw = b
    c, s = math.cos(ayaw), math.sin(ayaw)
    return ax + c * bx - s * by, ay + s * bx + c * by, ayaw + byaw


def is_static(model):
    return (model.findtext("static") or "false").strip() in ("1", "true")


def footprints(model):
    """Every collision of the model as ('rect', centre, yaw, half_x, half_y) or
    ('circle', centre, radius), in the world frame."""
    mx, my, _, myaw = pose_of(model)
    out = []
    for link in model.findall("link"):
        lx, ly, _, lyaw = pose_of(link)
        for collision in link.findall("collision"):
            cx, cy, _, cyaw = pose_of(collision)
            x, y, yaw = compose(compose((mx, my, myaw), (lx, ly, lyaw)), (cx, cy, cyaw))
            shape = collision.find("geometry")[0]
            if shape.tag == "box":
                sx, sy, _ = floats(shape.findtext("size"))
                out.append(("rect", (x, y), yaw, sx / 2, sy / 2))
            elif shape.tag in ("cylinder", "sphere"):
                out.append(("circle", (x, y), float(shape.findtext("radius"))))
    return out


def rect_corners(rect):
    _, (x, y), yaw, hx, hy = rect
    c, s = math.cos(yaw), math.sin(yaw)
    return [(x + c * u - s * v, y + s * u + c * v)
            for u, v in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))]


def distance_to(shape, point):
    """Distance from a point to a footprint, 0 inside it."""
    px, py = point
    if shape[0] == "circle":
        (x, y), r = shape[1], shape[2]
        return max(0.0, math.hypot(px - x, py - y) - r)
    _, (x, y), yaw, hx, hy = shape
    c, s = math.cos(yaw), math.sin(yaw)
    u, v = c * (px - x) + s * (py - y), -s * (px - x) + c * (py - y)
    return math.hypot(max(abs(u) - hx, 0.0), max(abs(v) - hy, 0.0))


def overlap(a, b):
    """Do two footprints intersect? (circle/circle, circle/rect, rect/rect by separating axes)"""
    if a[0] == "circle" and b[0] == "circle":
        return math.dist(a[1], b[1]) < a[2] + b[2]
    if a[0] == "circle" or b[0] == "circle":
        circle, rect = (a, b) if a[0] == "circle" else (b, a)
        return distance_to(rect, circle[1]) < circle[2]
    ca, cb = rect_corners(a), rect_corners(b)
    for yaw in (a[2], a[2] + math.pi / 2, b[2], b[2] + math.pi / 2):
        axis = (math.cos(yaw), math.sin(yaw))
        pa = [axis[0] * x + axis[1] * y for x, y in ca]
        pb = [axis[0] * x + axis[1] * y for x, y in cb]
        if max(pa) <= min(pb) or max(pb) <= min(pa):
            return False
    return True


def inside_polygon(point, polygon):
    px, py = point
    inside = False
    for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1]):
        if (y1 > py) != (y2 > py) and px < x1 + (py - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


def wall_segment(room, name):
    """End points of a wall's centre line in the world frame, as the world file places it."""
    link = next(link for link in room.findall("link") if link.get("name") == name)
    collision = link.find("collision")
    frame = (0.0, 0.0, 0.0)
    for element in (room, link, collision):
        x, y, _, yaw = pose_of(element)
        frame = compose(frame, (x, y, yaw))
    length = floats(collision.findtext("geometry/box/size"))[0]
    return [compose(frame, (sign * length / 2, 0, 0))[:2] for sign in (-1, 1)]


def line_intersection(s1, s2):
    (x1, y1), (x2, y2) = s1
    (x3, y3), (x4, y4) = s2
    d = (x1 - x2) * (y3 - y4) - (y1 - y2) * (x3 - x4)
    t = ((x1 - x3) * (y3 - y4) - (y1 - y3) * (x3 - x4)) / d
    return x1 + t * (x2 - x1), y1 + t * (y2 - y1)


def on_segment(point, segment, tolerance=WALL_THICKNESS / 2 + 1e-3):
    (x1, y1), (x2, y2) = segment
    length = math.dist(segment[0], segment[1])
    ux, uy = (x2 - x1) / length, (y2 - y1) / length
    along = (point[0] - x1) * ux + (point[1] - y1) * uy
    across = -(point[0] - x1) * uy + (point[1] - y1) * ux
    return abs(across) < 1e-6 and -tolerance <= along <= length + tolerance


def outer_polygon(room):
    """Corners of the room: where consecutive outer walls' centre lines meet."""
    segments = [wall_segment(room, n) for n in OUTER_WALLS]
    corners = []
    for s1, s2 in zip(segments, segments[1:] + segments[:1]):
        corner = line_intersection(s1, s2)
        # the walls meet: the corner lies on both (building-editor walls reach half a
        # thickness past the corner; Wall_5 runs on past Wall_0 in a T)
        assert on_segment(corner, s1) and on_segment(corner, s2), (s1, s2)
        corners.append(corner)
    return corners


# ---------------------------------------------------------------------------------------------

def test_well_formed_sdf_1_6(sdf):
    assert sdf.tag == "sdf"
    assert sdf.get("version") == "1.6"


def test_physics(world):
    physics = world.findall("physics")
    assert len(physics) == 1
    p = physics[0]
    assert p.get("type") == "ode"
    assert float(p.findtext("max_step_size")) == pytest.approx(0.001)
    assert float(p.findtext("real_time_factor")) == pytest.approx(1.0)
    assert float(p.findtext("real_time_update_rate")) == pytest.approx(1000.0)
    assert floats(world.findtext("gravity")) == pytest.approx([0, 0, -9.8])


def test_sun(world):
    lights = {light.get("name"): light for light in world.findall("light")}
    assert lights["sun"].get("type") == "directional"


def test_ground_plane(models):
    ground = models["ground_plane"]
    assert is_static(ground)
    collision = ground.find("link/collision")
    assert floats(collision.findtext("geometry/plane/normal")) == [0, 0, 1]
    ode = collision.find("surface/friction/ode")
    assert float(ode.findtext("mu")) == pytest.approx(100)
    assert float(ode.findtext("mu2")) == pytest.approx(50)


def test_only_primitive_shapes_and_no_external_resources(world):
    shapes = {g[0].tag for g in world.iter("geometry")}
    assert shapes <= {"box", "cylinder", "sphere", "plane"}
    assert world.find(".//include") is None
    assert world.find(".//uri") is None


def test_room_is_static_at_its_pose(models):
    room = models["room1"]
    assert is_static(room)
    x, y, z, yaw = pose_of(room)
    assert (x, y, z, yaw) == pytest.approx(ROOM_POSE[:2] + (0.0, ROOM_POSE[2]))


def test_seventeen_walls(models):
    links = {link.get("name"): link for link in models["room1"].findall("link")}
    assert set(links) == set(WALLS)
    for name, (x, y, yaw, length) in WALLS.items():
        link = links[name]
        assert pose_of(link) == pytest.approx((x, y, 0.0, yaw), abs=1e-6), name
        for tag in ("collision", "visual"):
            element = link.find(tag)
            assert floats(element.findtext("geometry/box/size")) == pytest.approx(
                [length, WALL_THICKNESS, WALL_HEIGHT]), (name, tag)
            # standing on the floor: the box centre is half a wall height up
            assert pose_of(element)[2] == pytest.approx(WALL_HEIGHT / 2), (name, tag)
        assert link.find("visual/material/diffuse") is not None, name


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_object(models, name):
    x, y, static, (kind, dims) = OBJECTS[name]
    model = models[name]
    mx, my, _, _ = pose_of(model)
    assert (mx, my) == pytest.approx((x, y), abs=2e-3)
    assert is_static(model) == static
    shapes = [c.find("geometry")[0] for c in model.iter("collision")]
    if kind == "box":
        found = [floats(s.findtext("size")) for s in shapes if s.tag == "box"]
    elif kind == "cylinder":
        found = [[float(s.findtext("radius")), float(s.findtext("length"))]
                 for s in shapes if s.tag == "cylinder"]
    else:
        found = [[float(s.findtext("radius"))] for s in shapes if s.tag == "sphere"]
    assert any(f == pytest.approx(list(dims), abs=2e-3) for f in found), found
    # every collision stands on or above the floor
    for link in model.findall("link"):
        for collision in link.findall("collision"):
            shape = collision.find("geometry")[0]
            z = pose_of(model)[2] + pose_of(link)[2] + pose_of(collision)[2]
            half = {"box": lambda s: floats(s.findtext("size"))[2] / 2,
                    "cylinder": lambda s: float(s.findtext("length")) / 2,
                    "sphere": lambda s: float(s.findtext("radius"))}[shape.tag](shape)
            assert z - half >= -1e-6, (name, collision.get("name"))


@pytest.mark.parametrize("name", sorted(n for n, o in OBJECTS.items() if not o[2]))
def test_dynamic_object_mass_and_inertia(models, name):
    inertial = models[name].find("link/inertial")
    assert inertial is not None
    assert float(inertial.findtext("mass")) > 0
    ixx, iyy, izz = (float(inertial.findtext("inertia/" + k)) for k in ("ixx", "iyy", "izz"))
    # a physical inertia tensor: positive and obeying the triangle inequality
    assert min(ixx, iyy, izz) > 0
    assert ixx + iyy >= izz and iyy + izz >= ixx and izz + ixx >= iyy


def test_objects_inside_the_room_and_clear_of_walls(models):
    polygon = outer_polygon(models["room1"])
    walls = footprints(models["room1"])
    for name in OBJECTS:
        for fp in footprints(models[name]):
            assert inside_polygon(fp[1], polygon), name
            assert not any(overlap(fp, wall) for wall in walls), name


def test_spawn_point_inside_the_room(models):
    assert inside_polygon(SPAWN, outer_polygon(models["room1"]))


def test_spawn_point_clear_of_walls_and_objects(models):
    for name in ["room1"] + sorted(OBJECTS):
        for fp in footprints(models[name]):
            assert distance_to(fp, SPAWN) > CAR_RADIUS, (name, fp)
