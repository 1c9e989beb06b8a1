"""The racebot model rendered from racebot_description's xacro, checked against the original
project's numbers (docs: /work/shared/reference/RACEBOT.md, "Model").

Renders racecar.xacro with the xacro executable and the tutorial's own `--inorder` option, runs
urdfdom's check_urdf on the result and reads it with xml.etree. Needs no ROS master and no
simulator module. Sensor masses: camera 0.05, real_sense 0.05, lidar 0.1, imu 0.05 kg (as in the
original), so the car weighs 4 + 2 x 0.5 + 4 x 2 + 0.25 = 13.25 kg.
"""
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
XACRO_FILE = REPO / "racebot_description" / "urdf" / "ackermann" / "racecar.xacro"

WHEELS = ("left_front_wheel", "right_front_wheel", "left_rear_wheel", "right_rear_wheel")
HINGES = ("left_steering_hinge", "right_steering_hinge")

# joint name: (type, parent, child)
JOINTS = {
    "base_link2base_footprint": ("fixed", "base_footprint", "base_link"),
    "chassis_inertia_joint": ("fixed", "base_link", "base_inertia"),
    "left_steering_hinge_joint": ("revolute", "base_link", "left_steering_hinge"),
    "right_steering_hinge_joint": ("revolute", "base_link", "right_steering_hinge"),
    "left_front_wheel_joint": ("continuous", "left_steering_hinge", "left_front_wheel"),
    "right_front_wheel_joint": ("continuous", "right_steering_hinge", "right_front_wheel"),
    "left_rear_wheel_joint": ("continuous", "base_link", "left_rear_wheel"),
    "right_rear_wheel_joint": ("continuous", "base_link", "right_rear_wheel"),
    "camera_joint": ("fixed", "base_link", "camera"),
    "realsense_joint": ("fixed", "base_link", "real_sense"),
    "realsense_depth_joint": ("fixed", "real_sense", "realsense_depth"),
    "lidar_joint": ("fixed", "base_link", "lidar"),
    "imu_joint": ("fixed", "base_link", "imu"),
}
ACTUATED = {n for n, (t, _, _) in JOINTS.items() if t != "fixed"}

# link: mass (kg); links not listed have no <inertial>
MASSES = {
    "base_inertia": 4.0,
    "left_steering_hinge": 0.5, "right_steering_hinge": 0.5,
    "left_front_wheel": 2.0, "right_front_wheel": 2.0,
    "left_rear_wheel": 2.0, "right_rear_wheel": 2.0,
    "camera": 0.05, "real_sense": 0.05, "lidar": 0.1, "imu": 0.05,
}
TOTAL_MASS = 13.25

# sensor frames relative to their parent (RACEBOT.md rounds the first two to 4 decimals)
SENSOR_ORIGINS = {
    "camera_joint": ((0.14851, 0.0022, 0.0975), (0, 0, 0)),
    "realsense_joint": ((0.19864, 0.0038, 0.0520), (0, 0, 0)),
    "realsense_depth_joint": ((0, 0, 0), (-math.pi / 2, 0, -math.pi / 2)),
    "lidar_joint": ((0.093603, 0, 0.12377), (0, 0, 0)),
    "imu_joint": ((0, 0, 0.02), (0, 0, 0)),
}


def floats(text):
    return [float(v) for v in text.split()]


def find_xacro():
    # the xacro beside this interpreter (the project's venv), else the one on PATH
    beside = Path(sys.executable).parent / "xacro"
    return str(beside) if beside.exists() else shutil.which("xacro")


@pytest.fixture(scope="module")
def urdf_text():
    xacro = find_xacro()
    assert xacro, "no xacro executable beside %s or on PATH" % sys.executable
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(
        p for p in (str(REPO), env.get("ROS_PACKAGE_PATH", "")) if p)
    # the tutorial's robot_description line passes --inorder: it must still be accepted
    run = subprocess.run([xacro, "--inorder", str(XACRO_FILE)], env=env,
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    return run.stdout


@pytest.fixture(scope="module")
def robot(urdf_text):
    return ET.fromstring(urdf_text)


@pytest.fixture(scope="module")
def links(robot):
    return {link.get("name"): link for link in robot.findall("link")}


@pytest.fixture(scope="module")
def joints(robot):
    return {joint.get("name"): joint for joint in robot.findall("joint")}


def origin(element):
    o = element.find("origin")
    if o is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    return tuple(floats(o.get("xyz", "0 0 0"))), tuple(floats(o.get("rpy", "0 0 0")))


def gazebo_blocks(robot, reference):
    return [g for g in robot.findall("gazebo") if g.get("reference") == reference]


def test_check_urdf_accepts_the_model(urdf_text, tmp_path):
    check = shutil.which("check_urdf")
    if check is None:
        pytest.skip("check_urdf not installed (Debian: liburdfdom-tools)")
    path = tmp_path / "racebot.urdf"
    path.write_text(urdf_text)
    run = subprocess.run([check, str(path)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "robot name is: racebot" in run.stdout
    assert "root Link: base_footprint" in run.stdout


def test_robot_name_and_links(robot, links):
    assert robot.get("name") == "racebot"
    expected = {"base_footprint", "base_link", "realsense_depth"} | set(MASSES)
    assert set(links) == expected


def test_joint_names_types_and_tree(joints):
    found = {name: (j.get("type"), j.find("parent").get("link"), j.find("child").get("link"))
             for name, j in joints.items()}
    assert found == JOINTS


def test_steering_hinges(joints):
    for side, y in (("left", 0.065), ("right", -0.065)):
        joint = joints["%s_steering_hinge_joint" % side]
        assert floats(joint.find("axis").get("xyz")) == [0, 0, 1]
        limit = joint.find("limit")
        assert float(limit.get("lower")) == pytest.approx(-0.6)
        assert float(limit.get("upper")) == pytest.approx(0.6)
        assert float(limit.get("effort")) == pytest.approx(5.0)
        assert float(limit.get("velocity")) == pytest.approx(1000.0)
        xyz, rpy = origin(joint)
        assert xyz == pytest.approx((0.13, y, 0.0))
        assert rpy == pytest.approx((0.0, 0.0, 0.0))


def test_wheel_joints(joints):
    for wheel in WHEELS:
        joint = joints[wheel + "_joint"]
        assert floats(joint.find("axis").get("xyz")) == [0, 1, 0]
        limit = joint.find("limit")
        assert float(limit.get("effort")) == pytest.approx(10.0)
        assert float(limit.get("velocity")) == pytest.approx(1000.0)


def test_wheel_shape_radius_0_032(links):
    for wheel in WHEELS:
        link = links[wheel]
        cylinder = link.find("collision/geometry/cylinder")
        assert float(cylinder.get("radius")) == pytest.approx(0.032)
        assert float(cylinder.get("length")) == pytest.approx(0.02)
        # the cylinder's axis (its z) is turned onto the spin axis y
        _, rpy = origin(link.find("collision"))
        assert rpy == pytest.approx((math.pi / 2, 0.0, 0.0), abs=1e-3)
        visual = link.find("visual/geometry/cylinder")
        assert float(visual.get("radius")) == pytest.approx(0.033)


def test_chassis_box_and_ride_height(links, joints):
    box = links["base_link"].find("collision/geometry/box")
    assert floats(box.get("size")) == pytest.approx([0.28, 0.10, 0.03])
    # base_link sits one wheel radius above the ground frame: the wheels touch z = 0
    xyz, rpy = origin(joints["base_link2base_footprint"])
    assert xyz == pytest.approx((0.0, 0.0, 0.032))
    assert rpy == pytest.approx((0.0, 0.0, 0.0))


def wheel_centres(joints):
    """Wheel centres in base_link, composing the joint origins (all without rotation)."""
    parent_of = {j.find("child").get("link"): j for j in joints.values()}
    centres = {}
    for wheel in WHEELS:
        x = y = z = 0.0
        link = wheel
        while link != "base_link":
            joint = parent_of[link]
            xyz, rpy = origin(joint)
            assert rpy == pytest.approx((0.0, 0.0, 0.0)), joint.get("name")
            x, y, z = x + xyz[0], y + xyz[1], z + xyz[2]
            link = joint.find("parent").get("link")
        centres[wheel] = (x, y, z)
    return centres


def test_wheelbase_0_26_and_track_0_18(joints):
    c = wheel_centres(joints)
    for side in ("left", "right"):
        assert c[side + "_front_wheel"][0] - c[side + "_rear_wheel"][0] == pytest.approx(0.26)
    for axle in ("front", "rear"):
        assert c["left_%s_wheel" % axle][1] - c["right_%s_wheel" % axle][1] == pytest.approx(0.18)
    for wheel in WHEELS:
        assert c[wheel][2] == pytest.approx(0.0)


def test_masses_and_inertias(links):
    found = {}
    for name, link in links.items():
        inertial = link.find("inertial")
        if inertial is None:
            continue
        found[name] = float(inertial.find("mass").get("value"))
        inertia = inertial.find("inertia")
        moments = [float(inertia.get(k)) for k in ("ixx", "iyy", "izz")]
        assert all(m > 0 for m in moments), name
    assert found == pytest.approx(MASSES)
    assert sum(found.values()) == pytest.approx(TOTAL_MASS)
    # no inertial on the ground frame (as the original) nor on the optical frame
    assert links["base_footprint"].find("inertial") is None
    assert links["realsense_depth"].find("inertial") is None

    base = links["base_inertia"].find("inertial/inertia")
    assert [float(base.get(k)) for k in ("ixx", "iyy", "izz")] == pytest.approx(
        [0.0264, 0.0294, 0.00364])
    for hinge in HINGES:
        inertia = links[hinge].find("inertial/inertia")
        assert [float(inertia.get(k)) for k in ("ixx", "iyy", "izz")] == pytest.approx(
            [1.35e-5, 1.35e-5, 2.5e-5])


def test_sensor_frames(joints, links):
    for name, (xyz, rpy) in SENSOR_ORIGINS.items():
        found_xyz, found_rpy = origin(joints[name])
        assert found_xyz == pytest.approx(xyz, abs=1e-4), name
        assert found_rpy == pytest.approx(rpy, abs=1e-4), name
    for link in ("camera", "real_sense", "realsense_depth", "lidar", "imu"):
        assert links[link].find("visual/geometry") is not None, link


def test_primitive_shapes_only(robot):
    shapes = {g[0].tag for g in robot.iter("geometry")}
    assert shapes <= {"box", "cylinder", "sphere"}


def test_six_effort_transmissions(robot):
    transmissions = robot.findall("transmission")
    assert len(transmissions) == 6
    driven = set()
    for t in transmissions:
        assert t.findtext("type") == "transmission_interface/SimpleTransmission"
        joint = t.find("joint")
        driven.add(joint.get("name"))
        assert joint.findtext("hardwareInterface") == "hardware_interface/EffortJointInterface"
        actuator = t.find("actuator")
        assert actuator.findtext("hardwareInterface") == "hardware_interface/EffortJointInterface"
        assert float(actuator.findtext("mechanicalReduction")) == 1.0
    assert driven == ACTUATED


def test_ros_control_plugin(robot):
    plugins = [p for g in robot.findall("gazebo") if g.get("reference") is None
               for p in g.findall("plugin")]
    assert len(plugins) == 1
    plugin = plugins[0]
    assert plugin.get("filename") == "libgazebo_ros_control.so"
    assert plugin.findtext("robotNamespace") == "/racebot"
    assert plugin.findtext("robotParam") == "robot_description"


def friction(robot, link):
    values = {}
    for block in gazebo_blocks(robot, link):
        for key in ("mu1", "mu2", "kp", "kd"):
            if block.find(key) is not None:
                values[key] = float(block.findtext(key))
    return values


def test_contact_friction(robot):
    for wheel in WHEELS:
        assert friction(robot, wheel) == pytest.approx(
            {"mu1": 2.0, "mu2": 2.0, "kp": 1e7, "kd": 1.0}), wheel
    base = friction(robot, "base_link")
    assert (base["mu1"], base["mu2"]) == (0.0, 0.0)


def sensor(robot, reference):
    sensors = [s for g in gazebo_blocks(robot, reference) for s in g.findall("sensor")]
    assert len(sensors) == 1, reference
    return sensors[0]


# reference link: (sensor type, update rate, plugin library, frame)
SENSORS = {
    "lidar": ("ray", 40.0, "libgazebo_ros_laser.so", "lidar"),
    "camera": ("camera", 30.0, "libgazebo_ros_camera.so", "camera"),
    "real_sense": ("depth", 20.0, "libgazebo_ros_openni_kinect.so", "realsense_depth"),
    "imu": ("imu", 100.0, "libgazebo_ros_imu_sensor.so", "imu"),
}


@pytest.mark.parametrize("reference", sorted(SENSORS))
def test_sensor_type_rate_plugin_frame(robot, reference):
    kind, rate, library, frame = SENSORS[reference]
    s = sensor(robot, reference)
    assert s.get("type") == kind
    assert float(s.findtext("update_rate")) == pytest.approx(rate)
    plugin = s.find("plugin")
    assert plugin.get("filename") == library
    assert plugin.findtext("frameName") == frame


def camera_topics(plugin, *keys):
    ns = plugin.findtext("cameraName").strip("/")
    return {"/%s/%s" % (ns, plugin.findtext(k)) for k in keys}


def test_lidar_scan(robot):
    s = sensor(robot, "lidar")
    assert s.findtext("plugin/topicName") == "/scan"
    horizontal = s.find("ray/scan/horizontal")
    assert int(horizontal.findtext("samples")) == 1081
    assert float(horizontal.findtext("min_angle")) == pytest.approx(-2.3561944902)
    assert float(horizontal.findtext("max_angle")) == pytest.approx(2.3561944902)
    rng = s.find("ray/range")
    assert float(rng.findtext("min")) == pytest.approx(0.1)
    assert float(rng.findtext("max")) == pytest.approx(10.0)
    assert float(rng.findtext("resolution")) == pytest.approx(0.01)
    assert float(s.findtext("ray/noise/mean")) == 0.0
    assert float(s.findtext("ray/noise/stddev")) == pytest.approx(0.01)


def test_camera_image(robot):
    s = sensor(robot, "camera")
    assert camera_topics(s.find("plugin"), "imageTopicName", "cameraInfoTopicName") == {
        "/rrbot/camera1/image_raw", "/rrbot/camera1/camera_info"}
    image = s.find("camera/image")
    assert (int(image.findtext("width")), int(image.findtext("height"))) == (800, 800)
    assert image.findtext("format") == "R8G8B8"
    assert float(s.findtext("camera/horizontal_fov")) == pytest.approx(1.3962634)


def test_depth_camera(robot):
    s = sensor(robot, "real_sense")
    assert camera_topics(s.find("plugin"), "imageTopicName", "cameraInfoTopicName",
                         "depthImageTopicName", "depthImageCameraInfoTopicName",
                         "pointCloudTopicName") == {
        "/real_sense/rgb/image_raw", "/real_sense/rgb/camera_info",
        "/real_sense/depth/image_raw", "/real_sense/depth/camera_info",
        "/real_sense/depth/points"}
    image = s.find("camera/image")
    assert (int(image.findtext("width")), int(image.findtext("height"))) == (640, 480)
    assert float(s.findtext("camera/horizontal_fov")) == pytest.approx(math.radians(60))
    assert float(s.findtext("camera/clip/near")) == pytest.approx(0.05)
    assert float(s.findtext("camera/clip/far")) == pytest.approx(8.0)


def test_imu(robot):
    s = sensor(robot, "imu")
    plugin = s.find("plugin")
    assert plugin.findtext("topicName") == "imu"
    assert float(plugin.findtext("updateRateHZ")) == pytest.approx(100.0)
    assert float(plugin.findtext("gaussianNoise")) == 0.0


def test_rosparam_set_takes_the_rendered_description(urdf_text, robot):
    # `rosparam set robot_description "$(xacro racecar.xacro)"` parses its value as YAML: a ': ' or
    # ' #' in a comment xacro keeps would stop it ("mapping values are not allowed here") or cut it
    import yaml
    value = yaml.safe_load(urdf_text)
    assert isinstance(value, str)
    assert [link.get("name") for link in ET.fromstring(value).findall("link")] == \
        [link.get("name") for link in robot.findall("link")]
