"""Pure sensor maths (no master, no physics): lidar beam geometry and range reporting, the
pinhole camera's intrinsics and renderer matrices, depth linearisation, plane drawing, point
clouds, noise models, the IMU's kinematics and the update schedules."""
import math

import numpy as np
import pybullet as pb
import pytest

from racebot_sim_bridge.kinematics.rotations import rpy_to_quaternion
from racebot_sim_bridge.sensors.camera import OPTICAL_FROM_SENSOR, PinholeCamera, mask_depth
from racebot_sim_bridge.sensors.imu_reading import ImuKinematics, quaternion_to_matrix
from racebot_sim_bridge.sensors.noise import GaussianNoise, ImageNoise, make_noise
from racebot_sim_bridge.sensors.ray import ScanGeometry
from racebot_sim_bridge.sensors.schedule import RateMeter, RenderBudget, UpdateSchedule
from racebot_sim_bridge.description.urdf_model import RaySpec

HOKUYO = RaySpec(samples=1081, resolution=1, min_angle=-2.3561944902, max_angle=2.3561944902,
                 range_min=0.1, range_max=10.0, range_resolution=0.01,
                 noise_type='gaussian', noise_mean=0.0, noise_stddev=0.01)


# -- lidar ------------------------------------------------------------------------------------
def test_scan_angles_as_gazebo_fills_them():
    g = ScanGeometry(HOKUYO)
    assert g.count == 1081 and g.beams == 1081
    assert g.angle_increment == pytest.approx((2 * 2.3561944902) / 1080)
    yaws = np.arctan2(g.directions[:, 1], g.directions[:, 0])
    assert yaws[0] == pytest.approx(-2.3561944902) and yaws[-1] == pytest.approx(2.3561944902)
    assert yaws[540] == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(np.linalg.norm(g.directions, axis=1), 1.0)
    assert np.allclose(g.directions[:, 2], 0.0)


def test_resolution_multiplies_the_range_count():
    spec = RaySpec(samples=100, resolution=2, min_angle=-1, max_angle=1, range_min=0.1, range_max=5)
    g = ScanGeometry(spec)
    assert g.count == 200
    assert g.angle_increment == pytest.approx(2.0 / 199)


def test_single_beam_and_vertical_layers():
    one = ScanGeometry(RaySpec(samples=1, min_angle=0.3, max_angle=0.3, range_min=0.1, range_max=5))
    assert one.count == 1 and one.angle_increment == 0.0
    layered = ScanGeometry(RaySpec(samples=3, min_angle=-0.5, max_angle=0.5, vertical_samples=2,
                                   vertical_min_angle=-0.1, vertical_max_angle=0.1, range_min=0.1, range_max=5))
    assert layered.beams == 6
    elevations = np.arcsin(layered.directions[:, 2])
    assert np.allclose(elevations, [-0.1] * 3 + [0.1] * 3)


def test_bad_ranges_are_refused():
    with pytest.raises(ValueError):
        ScanGeometry(RaySpec(samples=10, range_min=5, range_max=1))


def test_beams_run_from_range_min_to_range_max_in_the_world():
    g = ScanGeometry(HOKUYO)
    rot = quaternion_to_matrix(rpy_to_quaternion(0, 0, math.pi / 2))  # sensor facing world +y
    start, end = g.endpoints((1.0, 2.0, 0.3), rot)
    assert np.allclose(start[540], (1.0, 2.1, 0.3))
    assert np.allclose(end[540], (1.0, 12.0, 0.3))
    assert np.allclose(np.linalg.norm(end - start, axis=1), 9.9)


def test_hits_become_ranges_and_misses_infinity():
    g = ScanGeometry(HOKUYO)
    r = g.ranges_from_hits([0.0, 0.5, 1.0, 0.3], [True, True, False, True])
    assert r[0] == pytest.approx(0.1) and r[1] == pytest.approx(5.05) and math.isinf(r[2])
    assert r[3] == pytest.approx(0.1 + 0.3 * 9.9)


def test_report_masks_as_rep_117_and_noise_stays_within_limits():
    g = ScanGeometry(HOKUYO)
    raw = np.array([math.inf, 10.0, 0.1, 0.05, 5.0, 9.9999, 0.1001])
    clean = g.report(raw)
    assert clean[0] == math.inf and clean[1] == math.inf
    assert clean[2] == -math.inf and clean[3] == -math.inf
    assert clean[4] == 5.0
    noisy = g.report(np.full(20000, 5.0), GaussianNoise(0.0, 0.01, np.random.default_rng(1)))
    assert abs(noisy.mean() - 5.0) < 0.001 and noisy.std() == pytest.approx(0.01, rel=0.05)
    edge = g.report(raw, GaussianNoise(0.0, 1.0, np.random.default_rng(2)))
    assert 0.1 <= edge[5] <= 10.0 and 0.1 <= edge[6] <= 10.0  # clamped, never masked by noise
    assert edge[0] == math.inf and edge[3] == -math.inf   # masked readings get no noise


# -- camera -----------------------------------------------------------------------------------
def test_intrinsics_from_hfov_and_size():
    cam = PinholeCamera(800, 800, 1.3962634, 0.02, 300)
    f = 400 / math.tan(1.3962634 / 2)
    # camera_info as gazebo_ros_camera_utils writes it: cx = (w + 1) / 2, cy = (h + 1) / 2
    assert cam.K() == pytest.approx([f, 0, 400.5, 0, f, 400.5, 0, 0, 1])
    assert cam.P(0.07) == pytest.approx([f, 0, 400.5, -f * 0.07, 0, f, 400.5, 0, 0, 0, 1, 0])
    # the plugin's <focalLength>, <Cx>, <Cy> are reported as set; 0 means unset
    assert cam.reported_intrinsics(500.0, 10.0, 0.0) == (500.0, 10.0, 400.5)
    assert cam.K(cam.reported_intrinsics(500.0, 10.0, 20.0)) == [500.0, 0, 10.0, 0, 500.0, 20.0, 0, 0, 1]
    depth = PinholeCamera(640, 480, math.radians(60), 0.05, 8)
    assert depth.f == pytest.approx(320 / math.tan(math.radians(30)))
    assert (depth.cx, depth.cy) == (319.5, 239.5)
    # square pixels: the vertical field of view follows from the height
    assert math.tan(depth.vfov / 2) == pytest.approx(240 / depth.f)


def test_project_the_optical_axis_and_a_point_off_it():
    cam = PinholeCamera(640, 480, math.radians(60), 0.05, 8)
    assert cam.project((0, 0, 2)) == pytest.approx((319.5, 239.5))
    u, v = cam.project((0.5, -0.25, 2))
    assert u == pytest.approx(319.5 + cam.f * 0.25) and v == pytest.approx(239.5 - cam.f * 0.125)


def test_renderer_matrices_match_pybullets():
    cam = PinholeCamera(640, 480, math.radians(60), 0.05, 8)
    ref = pb.computeProjectionMatrixFOV(math.degrees(cam.vfov), 640 / 480, 0.05, 8)
    assert cam.projection_matrix() == pytest.approx(list(ref), rel=1e-6, abs=1e-9)
    q = rpy_to_quaternion(0.1, -0.2, 0.7)
    rot = quaternion_to_matrix(q)
    eye = np.array([1.0, -2.0, 0.5])
    ref_view = pb.computeViewMatrix(eye.tolist(), (eye + rot[:, 0]).tolist(), rot[:, 2].tolist())
    assert cam.view_matrix(eye, rot) == pytest.approx(list(ref_view), abs=1e-6)


def test_depth_buffer_linearisation():
    cam = PinholeCamera(4, 4, 1.0, 0.05, 8.0)
    n, f = 0.05, 8.0
    for z in (0.05, 0.4, 1.0, 7.99):
        d = (1 / n - 1 / z) / (1 / n - 1 / f)  # what the depth buffer holds for eye depth z
        assert cam.linear_depth(d) == pytest.approx(z, rel=1e-6)


def test_depth_mask_like_openni_kinect():
    out = mask_depth(np.array([0.3, 0.4, 0.41, 4.99, 5.0, 7.0], dtype=np.float32), 0.4, 5.0)
    assert np.isnan(out[[0, 1, 4, 5]]).all()
    assert out[2] == pytest.approx(0.41) and out[3] == pytest.approx(4.99)


def test_points_and_plane_depth_are_consistent_with_the_pinhole():
    cam = PinholeCamera(64, 48, math.radians(60), 0.05, 8)
    depth = np.full((48, 64), 2.0, dtype=np.float32)
    pts = cam.points(depth)
    assert pts[24, 40, 2] == pytest.approx(2.0)
    assert cam.project(pts[24, 40]) == pytest.approx((40, 24), abs=1e-4)
    # a camera 0.5 m above the floor, looking along +x: the floor below the horizon
    rot = np.eye(3)
    t = cam.plane_depth(cam.rays_optical_3d(), (0, 0, 0.5), rot, (0, 0, 0), (0, 0, 1))
    assert np.isinf(t[:24]).all()  # at and above the horizon row the rays never reach the floor
    v = 40
    expected = 0.5 * cam.f / (v - cam.cy)  # depth along the axis where row v meets the floor
    assert t[v, 10] == pytest.approx(expected, rel=1e-5)
    # the sensor frame's x is the optical z
    assert OPTICAL_FROM_SENSOR @ np.array([1, 0, 0]) == pytest.approx([0, 0, 1])


# -- noise ------------------------------------------------------------------------------------
def test_noise_models():
    assert make_noise('none', 0, 0.5) is None
    assert make_noise('gaussian', 0, 0) is None
    assert make_noise('gaussian', 0, 0.5, enabled=False) is None
    n = make_noise('Gaussian', 0.1, 0.5, rng=np.random.default_rng(3))
    x = n.apply(np.zeros(50000))
    assert x.mean() == pytest.approx(0.1, abs=0.01) and x.std() == pytest.approx(0.5, rel=0.02)
    with pytest.raises(ValueError):
        make_noise('poisson', 0, 1)
    with pytest.raises(ValueError):
        make_noise('gaussian', 0, -1)


def test_image_noise_per_pixel_and_clamped():
    rng = np.random.default_rng(4)
    noise = ImageNoise(0.0, 0.007, 300 * 300 * 3, rng)
    img = np.full((300, 300, 3), 128, dtype=np.uint8)
    a, b = noise.apply(img), noise.apply(img)
    delta = a.astype(float) - 128
    assert delta.std() == pytest.approx(0.007 * 255, rel=0.05) and abs(delta.mean()) < 0.05
    assert (a != b).mean() > 0.3  # a fresh draw per frame
    dark = noise.apply(np.zeros((300, 300, 3), dtype=np.uint8))
    assert dark.min() == 0 and dark.dtype == np.uint8


# -- IMU --------------------------------------------------------------------------------------
def test_imu_at_rest_reads_gravity_up():
    imu = ImuKinematics((0, 0, -9.8))
    assert imu.measure(0.0, (0, 0, 0, 1), (0, 0, 0), (0, 0, 0)) is None  # priming
    m = imu.measure(0.01, (0, 0, 0, 1), (0, 0, 0), (0, 0, 0))
    assert m.linear_acceleration == pytest.approx([0, 0, 9.8])
    assert m.angular_velocity == pytest.approx([0, 0, 0])


def test_imu_tilted_accelerating_and_turning():
    imu = ImuKinematics((0, 0, -9.8))
    q = rpy_to_quaternion(0, 0, math.pi / 2)  # facing world +y
    imu.measure(1.0, q, (0, 1.0, 0), (0, 0, 0.5))
    m = imu.measure(1.1, q, (0, 1.2, 0), (0, 0, 0.5))  # 2 m/s^2 along world y = sensor x
    assert m.linear_acceleration == pytest.approx([2.0, 0, 9.8], abs=1e-9)
    assert m.angular_velocity == pytest.approx([0, 0, 0.5])
    rolled = rpy_to_quaternion(math.pi / 2, 0, 0)  # lying on its side: gravity along sensor y
    imu.reset()
    imu.measure(0, rolled, (0, 0, 0), (0, 0, 0))
    assert imu.measure(0.01, rolled, (0, 0, 0), (0, 0, 0)).linear_acceleration == pytest.approx([0, 9.8, 0], abs=1e-9)


# -- schedules --------------------------------------------------------------------------------
@pytest.mark.parametrize('rate', [30.0, 40.0, 100.0, 20.0, 7.0])
def test_schedule_keeps_the_declared_rate_on_a_1ms_step(rate):
    s = UpdateSchedule(rate, start=0.0)
    times = []
    for k in range(1, 10001):
        t = k * 0.001
        if s.due(t):
            s.advance(t)
            times.append(t)
    assert len(times) == pytest.approx(10 * rate, abs=1)
    assert max(np.diff(times)) <= 1.0 / rate + 0.0011


def test_schedule_restarts_after_time_goes_back_and_zero_rate_means_every_update():
    s = UpdateSchedule(10.0)
    assert s.due(0.5)
    s.advance(0.5)
    assert not s.due(0.55)
    assert s.due(0.01)  # a reset sent the clock back
    every = UpdateSchedule(0.0)
    for t in (0.001, 0.002):
        assert every.due(t)
        every.advance(t)


def test_render_budget_limits_the_share_of_wall_time():
    now = [0.0]
    budget = RenderBudget(0.5, lambda: now[0], burst=0.1)
    rendered = 0
    for _ in range(1000):  # a frame costs 0.1 s and is due every 0.01 s of wall time
        if budget.allow():
            budget.spend(0.1)
            rendered += 1
        now[0] += 0.01
    assert rendered == pytest.approx(50, abs=2)  # 10 s of wall time, half of it rendering
    free = RenderBudget(1.0, lambda: now[0])
    assert all(free.allow() for _ in range(10))


def test_render_budget_is_fair_between_a_fast_and_a_slow_camera():
    now = [0.0]
    budget = RenderBudget(0.5, lambda: now[0], burst=0.1)
    rendered = {'camera': 0, 'depth': 0}
    for ms in range(1, 20001):  # 20 s; the camera is due every 33 ms, the depth camera every 50 ms
        now[0] = ms / 1000.0
        for who, period in (('camera', 33), ('depth', 50)):
            if ms % period == 0 and budget.allow(who):
                budget.spend(0.08)
                rendered[who] += 1
    total = sum(rendered.values())
    assert total == pytest.approx(20 * 0.5 / 0.08, rel=0.1)  # half the wall time, 80 ms a frame
    assert min(rendered.values()) > 0.4 * total, rendered


def test_rate_meter():
    m = RateMeter()
    assert m.snapshot(0.0, 100.0) is None
    for _ in range(40):
        m.tick()
    m.skip()
    assert m.snapshot(1.0, 102.0) == (40.0, 20.0, 1)
