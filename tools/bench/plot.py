"""The bench's and the demo's figures, drawn with matplotlib (Agg backend: no display needed).

Each figure has a `*_figure(...)` builder returning a matplotlib Figure (tests read its labels and
legends) and a writer that saves it as a PNG and returns the path.
"""
import math

import matplotlib
import numpy as np
matplotlib.use('Agg')  # before anything imports pyplot: no display, ever
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

DPI = 100
REFERENCE_STYLE = dict(color='0.45', linestyle='--', linewidth=1.0)


def new_figure(width_in, height_in):
    fig = Figure(figsize=(width_in, height_in), dpi=DPI)
    FigureCanvasAgg(fig)
    return fig


def save(fig, path):
    fig.savefig(path, dpi=DPI)
    return path


def finish_axes(ax, title, xlabel, ylabel, legend_loc='best'):
    """One panel's title, axis labels, light grid and small legend, as every figure here has them."""
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(loc=legend_loc, fontsize='small')


# -- fidelity --------------------------------------------------------------------------------------
def turning_circles_figure(runs):
    """runs: {mode: [circle results]} -> one panel per steering mode; None without runs."""
    modes = [m for m in ('parallel', 'ackermann') if runs.get(m)]
    if not modes:
        return None
    fig = new_figure(6.0 * len(modes), 6.0)
    for i, mode in enumerate(modes):
        ax = fig.add_subplot(1, len(modes), i + 1)
        for c in runs[mode]:
            r = c['reference_m']
            # bicycle model: the rear axle middle starts at (-0.13, 0) heading +x, centre to its left
            cx, cy = -0.13, r
            angles = [a / 180.0 * math.pi for a in range(361)]
            ax.plot([cx + r * math.sin(a) for a in angles], [cy - r * math.cos(a) for a in angles],
                    **REFERENCE_STYLE)
            xs, ys = zip(*[(p[0], p[1]) for p in c['trajectory']])
            ax.plot(xs, ys, linewidth=2, label='δ %.1f rad: R %.2f m vs %.2f m (%+.1f %%)'
                    % (c['steering_rad'], c['measured_m'], r, c['error_pct']))
        ax.plot([], [], label='bicycle model, R = L / tan δ', **REFERENCE_STYLE)
        ax.set_aspect('equal', adjustable='datalim')
        finish_axes(ax, '%s steering: rear-axle path' % mode, 'x (m)', 'y (m)', 'upper right')
    fig.tight_layout()
    return fig


def turning_circles(path, runs):
    fig = turning_circles_figure(runs)
    return save(fig, path) if fig is not None else None


def hinge_step_figure(samples, figures, target):
    fig = new_figure(6.4, 4.3)
    ax = fig.add_subplot(1, 1, 1)
    t_end = samples[-1][0]
    ts, vs = zip(*samples)
    ax.plot(ts, vs, linewidth=2, label='left hinge (P 10, D 0.5)')
    ax.axhline(target, label='command %.1f rad' % target, **REFERENCE_STYLE)
    ax.axhspan(target * 0.98, target * 1.02, color='0.85', alpha=0.6, label='±2 % band')
    rise, over, settle = figures['rise_time_s'], figures['overshoot_pct'], figures['settling_time_s']
    ax.text(0.98, 0.05, 'rise 10-90 %%: %s\novershoot: %.1f %%\nsettling 2 %%: %s\nfinal: %.4f rad' % (
        '%.3f s' % rise if rise is not None else '-', over,
        '%.3f s' % settle if settle is not None else 'not within 2 %', figures['final_rad']),
        transform=ax.transAxes, ha='right', va='bottom', fontsize='small',
        bbox=dict(facecolor='white', edgecolor='0.7'))
    ax.set_xlim(0.0, t_end)
    finish_axes(ax, 'steering hinge step 0 → %.1f rad' % target, 'time after the step (s)', 'hinge angle (rad)',
                'center right')
    fig.tight_layout()
    return fig


def hinge_step(path, samples, figures, target):
    return save(hinge_step_figure(samples, figures, target), path)


# -- sensors -----------------------------------------------------------------------------------------
def sensor_rates_figure(rows, load=None):
    """rows: [{'label', 'declared_hz', 'target_hz' (or None), 'paths': {path name: wall Hz or None}}]
    (one per topic) -> grouped bars of the wall-time rate per path, with each topic's declared
    rate and target; `load`: {path name: 1-min load average} for the legend."""
    names = []
    for row in rows:
        names += [n for n in row['paths'] if n not in names]
    fig = new_figure(7.5, 5.0)
    ax = fig.add_subplot(1, 1, 1)
    width = 0.8 / max(1, len(names))
    for j, name in enumerate(names):
        xs = [i - 0.4 + width * (j + 0.5) for i in range(len(rows))]
        hz = [row['paths'].get(name) or 0.0 for row in rows]
        label = name if not load or load.get(name) is None else '%s (load %.2f)' % (name, load[name])
        bars = ax.bar(xs, hz, width, label=label)
        ax.bar_label(bars, labels=['%.1f' % h for h in hz], fontsize='x-small', padding=2)
    for i, row in enumerate(rows):
        ax.hlines(row['declared_hz'], i - 0.45, i + 0.45, colors='black', linewidth=1.5,
                  label='declared rate' if i == 0 else None)
        if row.get('target_hz'):
            ax.hlines(row['target_hz'], i - 0.45, i + 0.45, colors='tab:red', linestyles='dotted', linewidth=1.5,
                      label='target' if not any(r.get('target_hz') for r in rows[:i]) else None)
    ax.set_xticks(range(len(rows)))
    ax.set_xticklabels([row['label'] for row in rows])
    ax.set_yscale('log')
    top = max([row['declared_hz'] for row in rows] + [h or 0.0 for row in rows for h in row['paths'].values()])
    ax.set_ylim(1.0, top * 2.0)  # room above the bars for their labels
    ax.set_ylabel('messages per wall second (Hz, log scale)')
    ax.set_xlabel('topic')
    ax.set_title('sensor rates in real time, every sensor subscribed')
    ax.grid(True, axis='y', which='both', alpha=0.3)
    ax.legend(loc='upper center', bbox_to_anchor=(0.5, -0.15), ncol=2, fontsize='small', frameon=False)
    fig.tight_layout()
    return fig


def sensor_rates(path, rows, load=None):
    return save(sensor_rates_figure(rows, load), path)


# -- demo ----------------------------------------------------------------------------------------------
def room_path_figure(shapes, path):
    """shapes: outlines [(x, y), ...] of the walls and objects; path: [(t, x, y, yaw), ...]."""
    fig = new_figure(9.0, 7.2)
    ax = fig.add_subplot(1, 1, 1)
    for k, s in enumerate(shapes):
        xs, ys = zip(*s)
        ax.plot(xs, ys, color='0.5', linewidth=1.5, label='walls, objects' if k == 0 else None)
    ax.plot([p[1] for p in path], [p[2] for p in path], color='tab:blue', linewidth=2, label='path')
    ax.plot([path[0][1]], [path[0][2]], 'o', color='tab:green', label='start')
    ax.plot([path[-1][1]], [path[-1][2]], 'o', color='tab:red', label='end')
    ax.set_aspect('equal', adjustable='datalim')
    finish_axes(ax, 'racebot demo: path in the room', 'x (m)', 'y (m)', 'upper right')
    fig.tight_layout()
    return fig


def room_path(path_png, shapes, path):
    return save(room_path_figure(shapes, path), path_png)


MAP_COLOURS = {'unknown': (0.82, 0.82, 0.82), 'free': (1.0, 1.0, 1.0), 'occupied': (0.0, 0.0, 0.0)}


def occupancy_image(data, width, height, occupied=65):
    """An OccupancyGrid's row-major values as a height x width x 4 RGBA array, opaque (row 0 the grid's first row,
    at its origin): unknown (-1) light grey, free (0 up to `occupied`) white, occupied (`occupied` or more) black.
    (RGBA: an RGB image drawn rotated fills the corners around it with black.)"""
    grid = np.asarray(data, dtype=np.int16).reshape(height, width)
    image = np.ones((height, width, 4))
    image[:, :, :3] = MAP_COLOURS['free']
    image[grid < 0, :3] = MAP_COLOURS['unknown']
    image[grid >= occupied, :3] = MAP_COLOURS['occupied']
    return image


def room_map_figure(grid, walls, path, title='racebot demo: the map gmapping made, and the path'):
    """grid: {'data' (row-major values), 'width', 'height', 'resolution', 'origin': (x, y, yaw) of the grid's
    corner in the world}; walls: (x, y) points of the world's walls at the laser's height; path: [(t, x, y, yaw),
    ...]. The map under the walls and the path, in world coordinates."""
    from matplotlib.patches import Patch
    from matplotlib.transforms import Affine2D
    fig = new_figure(9.0, 7.2)
    ax = fig.add_subplot(1, 1, 1)
    w, h, res = grid['width'], grid['height'], grid['resolution']
    x0, y0, yaw = grid['origin']
    image = ax.imshow(occupancy_image(grid['data'], w, h), origin='lower', extent=(0, w * res, 0, h * res),
                      interpolation='nearest', zorder=0)
    image.set_transform(Affine2D().rotate(yaw).translate(x0, y0) + ax.transData)
    if len(walls):
        ax.plot([p[0] for p in walls], [p[1] for p in walls], ',', color='tab:orange', alpha=0.6, zorder=1)
    ax.plot([p[1] for p in path], [p[2] for p in path], color='tab:blue', linewidth=2, zorder=2)
    ax.plot([path[0][1]], [path[0][2]], 'o', color='tab:green', zorder=3)
    ax.plot([path[-1][1]], [path[-1][2]], 'o', color='tab:red', zorder=3)
    c, s = math.cos(yaw), math.sin(yaw)
    corners = [(x0 + c * u - s * v, y0 + s * u + c * v) for u in (0, w * res) for v in (0, h * res)]
    xs = [p[0] for p in corners] + [p[1] for p in path] + [p[0] for p in walls]
    ys = [p[1] for p in corners] + [p[2] for p in path] + [p[1] for p in walls]
    ax.set_xlim(min(xs) - 0.2, max(xs) + 0.2)
    ax.set_ylim(min(ys) - 0.2, max(ys) + 0.2)
    ax.set_aspect('equal', adjustable='datalim')
    handles = [Patch(facecolor=MAP_COLOURS['occupied'], label='map: occupied'),
               Patch(facecolor=MAP_COLOURS['free'], edgecolor='0.5', label='map: free'),
               Patch(facecolor=MAP_COLOURS['unknown'], label='map: unknown'),
               ax.plot([], [], color='tab:orange', label="the world's walls at the laser's height")[0],
               ax.plot([], [], color='tab:blue', linewidth=2, label='path')[0],
               ax.plot([], [], 'o', color='tab:green', label='start')[0],
               ax.plot([], [], 'o', color='tab:red', label='end')[0]]
    ax.set_title(title)
    ax.set_xlabel('x (m)')
    ax.set_ylabel('y (m)')
    ax.grid(True, alpha=0.3)
    ax.legend(handles=handles, loc='lower right', fontsize='small')  # room_mini: outside the room there
    fig.tight_layout()
    return fig


def room_map(map_png, grid, walls, path, title=None):
    return save(room_map_figure(grid, walls, path, **({'title': title} if title else {})), map_png)


# -- fleet -----------------------------------------------------------------------------------------
def fleet_figure(fleet):
    """fleet: {str(n): {'robots', 'bridge_rtf', 'ceiling_rtf', 'spread'}} -> real-time factor against the number of
    robots, racebot beside bare PyBullet, with each median's spread."""
    runs = sorted(fleet.values(), key=lambda f: f['robots'])
    fig = new_figure(6.5, 4.5)
    ax = fig.add_subplot(1, 1, 1)
    n = [f['robots'] for f in runs]
    for key, label in (('ceiling_rtf', 'bare PyBullet (same bodies, same ray casts)'), ('rtf', 'racebot through ROS')):
        med = [f['spread'][key]['median'] for f in runs]
        lo = [m - f['spread'][key]['min'] for m, f in zip(med, runs)]
        hi = [f['spread'][key]['max'] - m for m, f in zip(med, runs)]
        ax.errorbar(n, med, yerr=[lo, hi], marker='o', capsize=3, label=label)
    for f in runs:
        ax.annotate('%.2f' % f['ratio'], (f['robots'], f['spread']['rtf']['median']), textcoords='offset points',
                    xytext=(4, -12), fontsize='small')
    ax.set_xscale('log', base=2)
    ax.set_xticks(n)
    ax.set_xticklabels([str(k) for k in n])
    finish_axes(ax, 'fleet: racebot / bare PyBullet (numbers: the ratio)',
                'differential-drive robots (laser 360 rays at 10 Hz, IMU at 50 Hz, each)',
                'real-time factor, as fast as possible')
    fig.tight_layout()
    return fig


def fleet(path, fleet_results):
    return save(fleet_figure(fleet_results), path)
