"""The bench's and the demo's figures (tools/bench/plot.py): matplotlib with the Agg backend, no
display; each figure has the axes labels, units and legend a reader expects, and is written as a
PNG of the expected size."""
import math

from bench import plot, report

PNG_MAGIC = b'\x89PNG\r\n\x1a\n'


def png_size(path):
    with open(path, 'rb') as f:
        head = f.read(24)
    assert head[:8] == PNG_MAGIC
    return int.from_bytes(head[16:20], 'big'), int.from_bytes(head[20:24], 'big')


def legend_texts(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_no_display_needed():
    import matplotlib
    assert matplotlib.get_backend().lower() == 'agg'


SENS = {
    'old': {'topics': {'/scan': {'wall_hz': 40.0}, '/imu': {'wall_hz': 100.0},
                       '/rrbot/camera1/image_raw': {'wall_hz': 4.7}, '/real_sense/depth/image_raw': {'wall_hz': 3.8}},
            'loadavg': [1.5, 1.0, 0.5]},
    'new': {'topics': {'/scan': {'wall_hz': 40.0}, '/imu': {'wall_hz': 100.0},
                       '/rrbot/camera1/image_raw': {'wall_hz': 12.5}, '/real_sense/depth/image_raw': {'wall_hz': 10.2}},
            'loadavg': [1.9, 1.1, 0.6]},
}


def test_sensor_rates(tmp_path):
    rows = report.sensor_rate_rows(SENS)
    load = {report.SENSOR_PATH_NAMES[k]: v['loadavg'][0] for k, v in SENS.items()}
    fig = plot.sensor_rates_figure(rows, load)
    ax = fig.axes[0]
    assert 'Hz' in ax.get_ylabel()
    assert [t.get_text() for t in ax.get_xticklabels()] == ['/scan', '/imu', 'camera 800x800', 'depth camera 640x480']
    texts = legend_texts(ax)
    assert any(t.startswith(report.SENSOR_PATH_NAMES['old']) and '1.50' in t for t in texts)
    assert any(t.startswith(report.SENSOR_PATH_NAMES['new']) for t in texts)
    assert 'declared rate' in texts and 'target' in texts
    bars = [p.get_height() for p in ax.patches]
    assert 12.5 in bars and 4.7 in bars  # each path's camera rate is drawn
    path = plot.sensor_rates(str(tmp_path / 'rates.png'), rows, load)
    assert png_size(path) == (750, 500)


def test_hinge_step(tmp_path):
    samples = [(i * 0.01, 0.3 * min(1.0, i / 20.0)) for i in range(100)]
    figures = {'rise_time_s': 0.16, 'overshoot_pct': 0.0, 'settling_time_s': 0.2, 'final_rad': 0.3}
    fig = plot.hinge_step_figure(samples, figures, 0.3)
    ax = fig.axes[0]
    assert ax.get_xlabel() == 'time after the step (s)' and ax.get_ylabel() == 'hinge angle (rad)'
    assert legend_texts(ax) == ['left hinge (P 10, D 0.5)', 'command 0.3 rad', '±2 % band']
    assert png_size(plot.hinge_step(str(tmp_path / 'h.png'), samples, figures, 0.3)) == (640, 430)


def test_turning_circles(tmp_path):
    circle = {'reference_m': 1.0, 'measured_m': 1.05, 'steering_rad': 0.3, 'error_pct': 5.0,
              'trajectory': [(0.0, 0.0), (0.5, 0.2), (0.9, 0.6)]}
    fig = plot.turning_circles_figure({'parallel': [circle], 'ackermann': [circle]})
    assert [ax.get_title() for ax in fig.axes] == ['parallel steering: rear-axle path',
                                                   'ackermann steering: rear-axle path']
    assert all(ax.get_xlabel() == 'x (m)' and ax.get_ylabel() == 'y (m)' for ax in fig.axes)
    assert legend_texts(fig.axes[0])[-1] == 'bicycle model, R = L / tan δ'
    assert 'R 1.05 m vs 1.00 m' in legend_texts(fig.axes[0])[0]
    assert plot.turning_circles_figure({}) is None
    assert png_size(plot.turning_circles(str(tmp_path / 't.png'), {'parallel': [circle]})) == (600, 600)


def test_room_path(tmp_path):
    shapes = [[(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)]]
    path = [(0.0, 0.1, 0.1, 0.0), (1.0, 0.5, 0.4, 0.3)]
    fig = plot.room_path_figure(shapes, path)
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ('x (m)', 'y (m)')
    assert legend_texts(ax) == ['walls, objects', 'path', 'start', 'end']
    assert png_size(plot.room_path(str(tmp_path / 'd.png'), shapes, path)) == (900, 720)


def test_occupancy_image_colours_unknown_free_and_occupied():
    image = plot.occupancy_image([-1, 0, 64, 65, 100, 0], 3, 2)
    assert image.shape == (2, 3, 4)
    assert (image[:, :, 3] == 1).all()
    assert tuple(image[0, 0, :3]) == plot.MAP_COLOURS['unknown']
    assert tuple(image[0, 1, :3]) == tuple(image[0, 2, :3]) == tuple(image[1, 2, :3]) == plot.MAP_COLOURS['free']
    assert tuple(image[1, 0, :3]) == tuple(image[1, 1, :3]) == plot.MAP_COLOURS['occupied']


def test_room_map(tmp_path):
    grid = {'data': [-1, 0, 100, 0] * 25, 'width': 10, 'height': 10, 'resolution': 0.05,
            'origin': (-0.25, -0.25, 0.3)}
    walls = [(0.5, y / 10) for y in range(-5, 6)]
    path = [(0.0, 0.0, 0.0, 0.0), (1.0, 0.3, 0.1, 0.2)]
    fig = plot.room_map_figure(grid, walls, path)
    ax = fig.axes[0]
    assert (ax.get_xlabel(), ax.get_ylabel()) == ('x (m)', 'y (m)')
    assert legend_texts(ax) == ['map: occupied', 'map: free', 'map: unknown', "the world's walls at the laser's height",
                                'path', 'start', 'end']
    # the map, rotated 0.3 rad about its corner, is inside the view, and so are the walls and the path
    assert ax.get_xlim()[0] <= -0.25 - 0.5 * math.sin(0.3) and ax.get_xlim()[1] >= 0.5
    assert ax.get_ylim()[0] <= -0.25 and ax.get_ylim()[1] >= 0.5
    assert len(ax.get_images()) == 1
    assert png_size(plot.room_map(str(tmp_path / 'm.png'), grid, walls, path, 'a title')) == (900, 720)
