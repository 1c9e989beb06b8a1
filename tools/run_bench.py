#!/usr/bin/env python3
"""make bench: racebot_sim_bridge against the physics ceiling (speed) and the kinematic model (fidelity).

    tools/run_bench.py [--quick] [--save] [--only PARTS] [--out DIR]   (devel/setup.bash sourced)

Prints the table (figure, ours, reference, target, met?), then each key figure beside the one kept
in the repository (tools/bench/last_figures.json) with the change and a verdict (REGRESSION when
worse beyond its tolerance and outside the kept spread), and writes under DIR (default out/bench):
bench.json (every raw figure, the machine, its load, the comparison), turning_circles.png,
hinge_step.png, sensor_rates.png (matplotlib), logs/.
Speed ratios are the median of at least three side-by-side pairs, printed with their spread
(min-max over the pairs).
--save writes this run's key figures into tools/bench/last_figures.json (commit it): the new
reference. Only when asked (see tools/bench/kept_figures.py for why); not with --quick.
--quick runs every part briefly (about 3 minutes on a 2-core machine) to show the bench works; its figures mean little
and are shown beside the kept ones without a verdict.
Exit status 0 when every part ran (whether or not each target is met), 1 when a part failed.

The parts that need ROS run as child processes of this script (--scenario NAME), each with its own
ROS master on a free port; see tools/bench/scenarios.py.
"""
import argparse
import cProfile
import json
import os
import platform
import pstats
import subprocess
import sys
import time
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from bench import common, kept_figures, stats  # noqa: E402  (tools/bench/, next to this script)

FULL = {
    'speed': dict(rounds=5, window_s=5.0, warmup_s=2.0, profile_s=5, memory_sim_s=600.0, memory_timeout_s=900),
    'realtime': dict(settle_s=3.0, parts=6, part_s=10.0, commands=1000, command_rate_hz=100.0),
    'sensors': dict(settle_s=5.0, window_s=30.0),
    'sensor_paths': ['old', 'new'],
    'startup_runs': 3,
    'fidelity': dict(speeds=[0.5, 1.0, 2.0], speed_settle_s=3.0, speed_measure_s=3.0, angles=[0.1, 0.2, 0.3],
                     circle_speed=0.5, circle_turns=1.1, circle_settle_s=4.0, lock_angles=[0.6, -0.6], lock_speed=2.0,
                     lock_s=30.0, timeout_s=600),
    'modes': ['parallel', 'ackermann'],
    'determinism_s': 20.0,
    'profile_steps': 5000,
    'fleet': dict(counts=[1, 2, 3, 4, 5, 6, 7, 8], rounds=3, window_s=4.0, warmup_s=1.5, profile_s=8.0),
    'big_world': dict(runs=3, world='auto', models=90, timeout_s=300),
    'plugins': dict(steps=20000, rounds=5),
    'controllers': dict(steps=20000, rounds=5),
}
QUICK = {
    'speed': dict(rounds=3, window_s=0.7, warmup_s=0.5, profile_s=0, memory_sim_s=10.0, memory_timeout_s=120),
    'realtime': dict(settle_s=0.5, parts=1, part_s=3.0, commands=100, command_rate_hz=100.0),
    'sensors': dict(settle_s=1.0, window_s=2.0),
    # the render worker only: the old path (TinyRenderer in the physics thread, ~sensors/render_worker false) is the
    # full run's comparison, and its code is the unit tests' (tests/unit/gazebo_plugins); a second launch with every
    # sensor subscribed was 40 s of the quick run's 330
    'sensor_paths': ['new'],
    'startup_runs': 0,
    'fidelity': dict(speeds=[1.0], speed_settle_s=1.0, speed_measure_s=1.0, angles=[0.3], circle_speed=0.5,
                     circle_turns=1.1, circle_max_s=3.0, circle_settle_s=1.0, lock_angles=[0.6], lock_speed=2.0,
                     lock_s=2.0, timeout_s=120),
    'modes': ['parallel'],
    'determinism_s': 2.0,
    'profile_steps': 500,
    'fleet': dict(counts=[1, 2], rounds=3, window_s=0.5, warmup_s=0.3),
    'big_world': dict(runs=1, world='generated', models=90, timeout_s=120),
    'plugins': dict(steps=1000, rounds=3),
    'controllers': dict(steps=1000, rounds=3),
}
SCENARIO_TIMEOUT_S = 1800


def run_scenario(name, params, out, timeout=SCENARIO_TIMEOUT_S):
    """Runs one ROS scenario in a child process with its own master; returns its result."""
    port = common.free_port()
    params = dict(params, port=port)
    result_file = os.path.join(out, 'tmp', '%s-%d.json' % (name, port))
    cmd = [common.python(), os.path.abspath(__file__), '--scenario', name, '--out', out, '--params',
           json.dumps(params), '--result', result_file]
    log = os.path.join(out, 'logs', 'scenario_%s_%d.log' % (name, port))
    with open(log, 'w') as f:
        code = subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, env=common.ros_env(port), timeout=timeout)
    try:
        with open(result_file) as f:
            reply = json.load(f)
    except (OSError, ValueError):
        with open(log) as f:
            tail = f.read()[-3000:]
        raise common.BenchError('scenario %s exited %s without a result; log %s:\n%s' % (name, code, log, tail))
    if not reply.get('ok'):
        raise common.BenchError('scenario %s failed:\n%s' % (name, reply.get('error')))
    return reply['result']


def child(args):
    """--scenario NAME: one measurement, its result (or error) as JSON in --result."""
    from bench import scenarios
    params = json.loads(args.params)
    try:
        reply = {'ok': True, 'result': scenarios.SCENARIOS[args.scenario](params, args.out)}
    except Exception:  # reported to the parent, which reports the part as failed
        reply = {'ok': False, 'error': traceback.format_exc()}
    with open(args.result, 'w') as f:
        json.dump(reply, f)
    os._exit(0)  # rospy's threads must not keep the process alive


# -- the parts ------------------------------------------------------------------------------------
def part_inprocess(cfg, out, results):
    from bench import inprocess, plot
    with common.quiet_stdout():
        samples, figures = inprocess.hinge_step(common.EMPTY_WORLD)
    figures['duration_s'] = inprocess.HINGE_STEP_DURATION
    plot.hinge_step(os.path.join(out, 'hinge_step.png'), samples, figures, inprocess.HINGE_STEP)
    # The simulator's own update without ROS: its speed and where its Python time goes.
    with common.quiet_stdout():
        car = inprocess.Car(common.ROOM_WORLD)
    try:
        car.step_until(0.5)
        n = cfg['profile_steps']
        rtfs = []
        for _ in range(stats.MIN_PAIRS):  # repeats: a median and its spread, as for the speed pairs
            start = time.perf_counter()
            for _ in range(n):
                car.sim.step()
            rtfs.append(n * car.sim.step_size / (time.perf_counter() - start))
        prof = cProfile.Profile()
        prof.enable()
        for _ in range(n):
            car.sim.step()
        prof.disable()
    finally:
        car.close()
    profile = pstats.Stats(prof)
    total = sum(v[2] for v in profile.stats.values())
    top = sorted(profile.stats.items(), key=lambda kv: -kv[1][2])[:12]
    results['inprocess'] = {
        'hinge': figures, 'hinge_samples': samples[::5], 'sim_rtf': stats.median(rtfs), 'sim_rtf_runs': rtfs,
        'profile_self_pct': [('%s:%d(%s)' % (os.path.basename(k[0]), k[1], k[2]), round(100.0 * v[2] / total, 1))
                             for k, v in top]}


def part_determinism(cfg, out, results):
    files = []
    for run in (1, 2):
        path = os.path.join(out, 'tmp', 'trajectory_%d.json' % run)
        run_scenario('determinism', {'sim_s': cfg['determinism_s'], 'trajectory_file': path}, out, timeout=600)
        with open(path) as f:
            files.append(json.load(f))
    a, b = files
    if len(a) != len(b) or not a:
        raise common.BenchError('the two runs recorded %d and %d samples' % (len(a), len(b)))
    diff = max(max(abs(p[1] - q[1]), abs(p[2] - q[2])) for p, q in zip(a, b))
    results['determinism'] = {'sim_s': cfg['determinism_s'], 'samples': len(a), 'max_diff_m': diff,
                              'end_pose': a[-1],
                              'how': 'two processes, in-process simulator, commands keyed to sim time'}


def part_speed(cfg, out, results):
    results['speed'] = run_scenario('speed', cfg['speed'], out)


def part_realtime(cfg, out, results):
    results['realtime'] = run_scenario('realtime', cfg['realtime'], out)


def part_sensors(cfg, out, results):
    """Every sensor subscribed in real time: the old rendering path (TinyRenderer in the physics
    thread) and the new (render worker, EGL when it loads), one after the other in this run (cfg's sensor_paths:
    the new one only in a quick run)."""
    from bench import plot, report
    from bench import camera_budget
    sens = results['sensors'] = {}
    results['camera_budget'] = camera_budget.run(os.path.join(out, 'tmp', 'camera_budget.json'))
    for path in cfg['sensor_paths']:
        sens[path] = run_scenario('sensors', dict(cfg['sensors'], path=path), out, timeout=600)
    plot.sensor_rates(os.path.join(out, 'sensor_rates.png'), report.sensor_rate_rows(sens),
                      {report.SENSOR_PATH_NAMES[k]: v['loadavg'][0] for k, v in sens.items()})


def part_startup(cfg, out, results):
    runs = [run_scenario('startup', {'run': i}, out, timeout=300)['startup_s'] for i in range(cfg['startup_runs'])]
    results['startup'] = {'cold_runs': runs, 'cold_s': stats.median(runs), 'spread': stats.spread(runs)}


def part_fidelity(cfg, out, results):
    fid = results.setdefault('fidelity', {'skipped': [m for m in ('parallel', 'ackermann') if m not in cfg['modes']]})
    failures = []
    for mode in cfg['modes']:
        params = dict(cfg['fidelity'], mode=mode)
        if mode != 'parallel':  # speeds and full lock are the same in both modes: once is enough
            params.update(speeds=[], lock_angles=[])
        try:
            fid[mode] = run_scenario('fidelity', params, out)
        except common.BenchError as err:
            results['errors']['fidelity_' + mode] = str(err)
            failures.append(mode)
    from bench import plot
    plot.turning_circles(os.path.join(out, 'turning_circles.png'),
                         {m: fid[m]['circles'] for m in ('parallel', 'ackermann') if m in fid})
    if failures:
        raise common.BenchError('fidelity failed in %s steering (see errors)' % ', '.join(failures))


def part_fleet(cfg, out, results):
    """1 to 8 differential-drive robots with laser and IMU beside bare PyBullet (bench/fleet.py)."""
    from bench import plot
    results['fleet'] = run_scenario('fleet', cfg['fleet'], out)
    plot.fleet(os.path.join(out, 'fleet.png'), results['fleet'])


def part_big_world(cfg, out, results):
    """~90 mesh models: roslaunch to /clock and to all models, mesh cache cold and warm (bench/big_world.py)."""
    from bench import big_world
    results['big_world'] = big_world.run(cfg['big_world'], out, run_scenario)


def part_plugins(cfg, out, results):
    """A compiled model plugin's update and an empty C++ event callback beside the same work in Python
    (bench/plugin_cost.py)."""
    from bench import plugin_cost
    with common.quiet_stdout():
        results['plugins'] = plugin_cost.measure(cfg['plugins'], out)


def part_controllers(cfg, out, results):
    """A compiled ros_control controller's update beside racebot's Python controller doing the same
    (bench/controller_cost.py; a scenario: its NodeHandles need a master)."""
    results['controllers'] = run_scenario('controllers', cfg['controllers'], out)


PARTS = (('inprocess', part_inprocess), ('plugins', part_plugins), ('controllers', part_controllers),
         ('determinism', part_determinism),
         ('speed', part_speed), ('realtime', part_realtime), ('sensors', part_sensors), ('startup', part_startup),
         ('fidelity', part_fidelity), ('fleet', part_fleet), ('big_world', part_big_world))


def machine():
    info = {'platform': platform.platform(), 'python': platform.python_version(), 'cpus': os.cpu_count()}
    try:
        with open('/proc/cpuinfo') as f:
            models = [line.split(':', 1)[1].strip() for line in f if line.startswith('model name')]
        info['cpu'] = models[0] if models else None
    except OSError:
        pass
    try:
        import pybullet  # noqa: F401  (its version is pinned in tools/requirements.txt)
        import numpy
        info['numpy'] = numpy.__version__
    except ImportError:
        pass
    return info


def profile_lines(prof, title, self_n, inclusive_n, unavailable):
    """A py-spy profile of the world server's main thread (its self and inclusive time), or why there is none."""
    if prof.get('available'):
        return (['%s (py-spy, %d samples), self time:' % (title, prof['samples'])]
                + ['  %5.1f %%  %s' % (pct, name) for name, pct in prof['self_pct'][:self_n]] + ['  inclusive:']
                + ['  %5.1f %%  %s' % (pct, name) for name, pct in prof['inclusive_pct'][:inclusive_n]])
    return ['%s: %s' % (unavailable, prof.get('why'))] if prof else []


def print_profiles(results):
    """Where the time goes, for the speed targets that were missed."""
    sp = results.get('speed') or {}
    lines = profile_lines(sp.get('profile') or {}, 'world server main thread, as fast as possible', 8, 10,
                          'world server profile')
    for n, entry in sorted((results.get('fleet') or {}).items()):
        lines += profile_lines(entry.get('profile') or {}, 'world server main thread with %s robots' % n, 10, 15,
                               'fleet world server profile')
    ip = results.get('inprocess') or {}
    if ip.get('profile_self_pct'):
        lines.append('Simulator.step in-process, no ROS (cProfile), self time:')
        lines += ['  %5.1f %%  %s' % (pct, name) for name, pct in ip['profile_self_pct'][:8]]
    return lines


def git_commit():
    """The checkout's commit (with '+changes' when the tree differs from it), or None."""
    try:
        sha = subprocess.check_output(['git', 'rev-parse', '--short', 'HEAD'], cwd=common.REPO,
                                      stderr=subprocess.DEVNULL).decode().strip()
        dirty = subprocess.call(['git', 'diff', '--quiet', 'HEAD', '--', '.', ':!tools/bench/last_figures.json'],
                                cwd=common.REPO, stderr=subprocess.DEVNULL) != 0
    except (OSError, subprocess.CalledProcessError):
        return None
    return sha + ('+changes' if dirty else '')


def save_figures(kept, figures, results, loads):
    """--save: this run's key figures become the kept ones (figures not measured now stay)."""
    meta = {'saved': results['started'], 'commit': git_commit(), 'machine': results['machine'],
            'load_max': max(loads, default=None), 'quick': False}
    kept_figures.save(kept_figures.merged(kept, figures, meta))
    print('- saved %d figures to %s: commit it to make them the reference' % (
        len(figures), os.path.relpath(kept_figures.KEPT_FILE)))


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--quick', action='store_true', help='every part, briefly (about 3 minutes)')
    parser.add_argument('--out', default=os.path.join(common.REPO, 'out', 'bench'), help='output folder')
    parser.add_argument('--only', help='comma-separated parts: ' + ', '.join(n for n, _ in PARTS))
    parser.add_argument('--save', action='store_true',
                        help='keep this run\'s figures in %s (the reference the next run is compared with)'
                        % os.path.relpath(kept_figures.KEPT_FILE, common.REPO))
    parser.add_argument('--scenario', help=argparse.SUPPRESS)
    parser.add_argument('--params', help=argparse.SUPPRESS)
    parser.add_argument('--result', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.scenario:
        return args
    if args.save and args.quick:
        parser.error('--save keeps a full run\'s figures as the reference; a --quick run\'s figures mean little. '
                     'Run without --quick to save.')
    if args.only and set(args.only.split(',')) - {n for n, _ in PARTS}:
        parser.error('--only: unknown part(s) %s; the parts are %s' % (
            ', '.join(sorted(set(args.only.split(',')) - {n for n, _ in PARTS})), ', '.join(n for n, _ in PARTS)))
    return args


def run_parts(args, out):
    """Every part asked for, one after the other; the results dictionary (a failed part's error in 'errors')."""
    cfg = QUICK if args.quick else FULL
    only = set(args.only.split(',')) if args.only else None
    results = {'quick': args.quick, 'machine': machine(), 'started': time.strftime('%Y-%m-%d %H:%M:%S'),
               'load': [], 'errors': {}, 'durations_s': {}}
    print('racebot bench%s: %d cores, load average %s (1, 5, 15 min)' % (
        ' --quick' if args.quick else '', os.cpu_count(), ', '.join('%.2f' % x for x in common.loadavg())), flush=True)
    t_all = time.monotonic()
    for name, part in PARTS:
        if only and name not in only:
            continue
        t0 = time.monotonic()
        print('  %s ...' % name, end='', flush=True)
        try:
            part(cfg, out, results)
            status = 'done'
        except Exception as err:  # one failed part must not hide the others' figures
            results['errors'][name] = '%s: %s' % (type(err).__name__, err)
            status = 'FAILED: %s' % str(err).splitlines()[0][:200]
        results['durations_s'][name] = round(time.monotonic() - t0, 1)
        results['load'].append({'after': name, 'loadavg': common.loadavg()})
        print(' %s (%.0f s, load %s)' % (status, time.monotonic() - t0, common.loadavg()[0]), flush=True)
    results['total_s'] = round(time.monotonic() - t_all, 1)
    return results


def print_results(results, rows, loads, quick):
    """The table, the sensors, the machine, the notes and, where a speed target was missed, the profiles."""
    from bench import report
    print()
    print(report.table(rows))
    print()
    if results.get('sensors'):
        print(report.sensor_table(results['sensors']))
        budget = report.camera_budget(results.get('camera_budget'), results['sensors'], results.get('realtime'))
        print('\n'.join(budget))
        print()
    print('machine: %s, %s cores; 1-min load average during the run %s..%s (%s cores are shared with '
          'whatever else runs)' % (results['machine'].get('cpu'), os.cpu_count(), min(loads, default='-'),
                                   max(loads, default='-'), os.cpu_count()))
    missed = [r for r in rows if r[4] == 'NO']
    for line in report.notes(results):
        print('- ' + line)
    if any('ceiling' in r[0] or 'CPU' in r[0] or 'real-time factor' in r[0] for r in missed) or quick or \
            any((e or {}).get('profile') for e in (results.get('fleet') or {}).values()):
        lines = print_profiles(results)
        if lines:
            print('\n'.join(lines))


def print_comparison(results, kept, kept_problem):
    """Each key figure beside the kept one, what the kept ones are, and the regressions."""
    from bench import report
    print()
    print(report.table(results['compared']['rows'], header=kept_figures.HEADER))
    for line in kept_figures.describe(kept, results['machine']) + ([kept_problem] if kept_problem else []):
        print('- ' + line)
    regressed = results['compared']['regressions']
    if regressed:
        print('- REGRESSION against the kept figures: %s' % '; '.join(regressed))


def main():
    args = parse_args()
    if args.scenario:
        return child(args)
    if 'ROS_PACKAGE_PATH' not in os.environ:
        sys.exit('racebot bench: source devel/setup.bash first (or use `make bench`)')
    out = os.path.abspath(args.out)
    common.clean_dir(out)
    common.ensure_dir(os.path.join(out, 'logs'))
    common.ensure_dir(os.path.join(out, 'tmp'))
    os.environ.setdefault('ROS_LOG_DIR', os.path.join(common.REPO, 'out', 'ros_log'))
    results = run_parts(args, out)
    from bench import report
    rows = report.rows(results)
    results['table'] = rows
    kept, kept_problem = kept_figures.load()
    figures = kept_figures.key_figures(results)
    compared = kept_figures.compare(figures, kept, quick=args.quick)
    results['compared'] = {'kept_file': kept_figures.KEPT_FILE, 'kept_problem': kept_problem, 'rows': compared,
                           'regressions': kept_figures.regressions(compared)}
    with open(os.path.join(out, 'bench.json'), 'w') as f:
        json.dump(results, f, indent=1)
    loads = [x['loadavg'][0] for x in results['load']]
    print_results(results, rows, loads, args.quick)
    print_comparison(results, kept, kept_problem)
    if args.save:
        save_figures(kept, figures, results, loads)
    for name, err in results['errors'].items():
        print('\n%s failed:\n%s' % (name, err))
    print('\nraw figures: %s; plots: %s' % (os.path.relpath(os.path.join(out, 'bench.json')), ', '.join(
        os.path.relpath(os.path.join(out, p))
        for p in ('turning_circles.png', 'hinge_step.png', 'sensor_rates.png', 'fleet.png')
        if os.path.exists(os.path.join(out, p)))))
    print('total %.0f s' % results['total_s'])
    return 1 if results['errors'] else 0


if __name__ == '__main__':
    sys.exit(main())
