"""The method plugin_cost and controller_cost share: the spinner robot (tests/fixtures/gazebo_plugin_project's, a
body and one continuous joint), a ground-plane world, simulators stepped in interleaved rounds (side by side, so the
machine's drift falls on all alike), the check that a variant turned the joint, and the figures: the median over the
rounds of the wall time per update, and of each variant's above the variant 'none', in microseconds.
"""
import os
import time

from racebot_sim_bridge.description import sdf_reader

from . import common, stats

PROJECT = os.path.join(common.REPO, 'tests', 'fixtures', 'gazebo_plugin_project')
with open(os.path.join(PROJECT, 'spinner.urdf.in')) as _f:
    SPINNER = _f.read()  # the compiled plugin tests' robot; its rotor, limits and `extra` filled by robot()
WARM_UP_STEPS = 200  # the first updates allocate


def robot(extra):
    """The spinner with `extra` (its <gazebo> plugins, <transmission>s) and the benches' rotor and limits."""
    return SPINNER % {'mass': 0.5, 'izz': 0.002, 'effort': 3.0, 'velocity': 40.0, 'extra': extra}


def ground_world(tmp):
    """A world of a ground plane only, as sdf_reader loads it (written into `tmp`)."""
    os.makedirs(tmp, exist_ok=True)
    path = os.path.join(tmp, 'ground.world')
    with open(path, 'w') as f:
        f.write('<sdf version="1.6"><world name="default"><model name="ground_plane"><static>true</static>'
                '<link name="link"><collision name="c"><geometry><plane><normal>0 0 1</normal></plane></geometry>'
                '</collision></link></model></world></sdf>')
    return sdf_reader.load_world(path)


class ErrorsKept:
    """The simulator's and the plugins' log (rospy's calls too): errors kept, the rest dropped."""

    def __init__(self):
        self.errors = []

    def error(self, message):
        self.errors.append(message)

    logerr = error

    def warn(self, message):
        pass

    info = logwarn = loginfo = warn


def time_updates(sims, steps, rounds):
    """{variant: [us per update, one per round]} of `sims` ({variant: Simulator}), warmed up, then stepped `steps`
    updates each in each of `rounds` interleaved rounds."""
    for sim in sims.values():
        for _ in range(WARM_UP_STEPS):
            sim.step()
    per_update = {variant: [] for variant in sims}
    for _ in range(rounds):
        for variant, sim in sims.items():
            start = time.perf_counter()
            for _ in range(steps):
                sim.step()
            per_update[variant].append(1e6 * (time.perf_counter() - start) / steps)
    return per_update


def check_turning(sims, variants, velocity):
    """BenchError unless the spinner of each of `variants` turns at `velocity` rad/s: each did the work measured."""
    for variant in variants:
        turning = sims[variant].robots['spinner'].body.joints['spin_joint'].state().velocity
        if abs(turning - velocity) > 1e-3:
            raise common.BenchError('%s: the joint turns at %.4f rad/s, not %.1f' % (variant, turning, velocity))


def figures(per_update, steps, rounds):
    """The part's result: medians per update and above 'none', with their spreads."""
    base = per_update['none']
    overhead = {v: [t - b for t, b in zip(times, base)] for v, times in per_update.items() if v != 'none'}
    return {'steps': steps, 'rounds': rounds,
            'update_us': {v: stats.median(times) for v, times in per_update.items()},
            'overhead_us': {v: stats.median(values) for v, values in overhead.items()},
            'overhead_spread_us': {v: stats.spread(values) for v, values in overhead.items()}}
