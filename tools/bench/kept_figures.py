"""The bench's kept figures: the key figures of the last saved run, committed in the repository
(last_figures.json next to this file), and each new figure printed beside its kept one with the
change, so that a regression shows in the next run. Pure (no ROS); tools/run_bench.py does the I/O.

The file is written only when asked (`tools/run_bench.py --save`), never by every run: it is a
reference chosen on purpose (a full run on a quiet machine, committed with the change that moved
it). Written by every run, a loaded laptop's or a --quick run's figures would become the reference,
the tree would be dirty after each bench, and a slow drift would only ever be compared with its
previous step.

A figure is {'label', 'unit', 'fmt', 'better' ('higher', 'lower' or None), 'tolerance' (relative),
'resolution' (absolute, in its unit; 0 if absent), 'median', 'min', 'max', 'n'}: min-max is the spread over its
n repeats (n 1: one measurement).
"""
import json
import math
import os

from . import report, stats

KEPT_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'last_figures.json')
FORMAT = 1
TOLERANCE = 0.05  # a change smaller than this (relative to the kept figure) is "same"
HEADER = ('figure', 'now', 'kept', 'change', 'verdict')
REGRESSION = 'REGRESSION'


def key_figures(r):
    """The figures worth keeping, from the results dictionary of tools/run_bench.py: {key: figure}."""
    out = {}

    def add(key, label, value, unit='', better=None, fmt='%.2f', tolerance=TOLERANCE, resolution=0.0):
        s = stats.spread([value]) if value is None or isinstance(value, (int, float)) else value
        if s is not None:
            out[key] = dict(s, label=label, unit=unit, fmt=fmt, better=better, tolerance=tolerance,
                            resolution=resolution)

    sp = r.get('speed')
    if sp:
        plain = sp['plain']
        spread = plain.get('spread', {})
        add('speed.ratio', 'bridge / ceiling, as fast as possible', spread.get('ratio'), better='higher',
            tolerance=0.03)
        add('speed.bridge_rtf', 'bridge as fast as possible: real-time factor', spread.get('bridge_rtf'),
            better='higher')
        # The ceiling is the machine, not our code: shown for reading the ratio, not judged.
        add('speed.ceiling_rtf', 'ceiling: bare PyBullet real-time factor', spread.get('ceiling_rtf'), fmt='%.1f')
        sens = sp.get('sensors') or {}
        if sens.get('available'):
            add('speed.sensors.ratio', 'bridge / ceiling, all sensors subscribed', sens['spread'].get('ratio'),
                better='higher', tolerance=0.03)
        if sp.get('rss_end_bytes'):
            add('speed.rss_end_mb', 'simulator RSS at %.0f s of sim time' % sp['memory_sim_s'],
                sp['rss_end_bytes'] / 1048576.0, ' MB', 'lower', '%.0f', 0.10)
    for f in (r.get('fleet') or {}).values():
        add('fleet.%d.ratio' % f['robots'], 'fleet of %d: racebot / bare PyBullet' % f['robots'], f['spread']['ratio'],
            better='higher', tolerance=0.03)
        add('fleet.%d.rtf' % f['robots'], 'fleet of %d: real-time factor' % f['robots'], f['spread']['rtf'],
            better='higher')
    rt = r.get('realtime')
    if rt:
        w = rt['window']
        add('realtime.cpu', 'real time: simulator CPU, sensors off (one core = 1)',
            stats.spread(w['parts_cpu']) if w.get('parts_cpu') else w['cpu'], better='lower', fmt='%.3f',
            tolerance=0.10)
        add('realtime.rtf', 'real time: real-time factor', stats.spread(w['parts_rtf']), fmt='%.3f')
        lat = rt['latency']['applied_ms']
        add('realtime.command_p50_ms', 'command path p50: publish -> applied', lat['p50'], ' ms', 'lower', '%.2f', 0.20)
        add('realtime.command_p99_ms', 'command path p99: publish -> applied', lat['p99'], ' ms', 'lower', '%.2f', 0.20)
    _sensor_figures((r.get('sensors') or {}).get('new'), add)
    su = r.get('startup')
    if su and su.get('cold_runs'):
        add('startup.cold_s', 'start-up, cold, to 7 controllers running', stats.spread(su['cold_runs']), ' s',
            'lower', tolerance=0.10)
    bw = r.get('big_world')
    if bw:  # keyed by the world: the house and the generated world are different figures
        key, name = 'big_world.%s.' % bw['world_kind'], 'big world (%s)' % bw['world_kind']
        for cache in ('warm', 'cold'):
            add(key + cache + '_models_s', '%s: roslaunch -> all models, %s' % (name, cache),
                bw[cache]['models_s'], ' s', 'lower', tolerance=0.10, resolution=0.1)
        add(key + 'warm_clock_s', '%s: roslaunch -> first /clock, warm' % name, bw['warm']['clock_s'], ' s', 'lower',
            tolerance=0.10, resolution=0.1)
        add(key + 'rss_mb', '%s: world server RSS, all models in, warm' % name, bw['warm']['rss_mb'], ' MB', 'lower',
            '%.0f', 0.10)
    ip = r.get('inprocess')
    if ip:
        add('inprocess.sim_rtf', 'simulator in-process, no ROS: real-time factor',
            stats.spread(ip['sim_rtf_runs']) if ip.get('sim_rtf_runs') else ip['sim_rtf'], better='higher', fmt='%.1f')
    de = r.get('determinism')
    if de:
        add('determinism.max_diff_m', 'determinism: two runs, max difference', de['max_diff_m'], ' m', 'lower',
            '%.1e', 0.0)
    for mode in ('parallel', 'ackermann'):
        for c in ((r.get('fidelity') or {}).get(mode) or {}).get('circles', []):
            add('fidelity.%s.radius_error_%.1f' % (mode, c['steering_rad']),
                'turning radius error, %s, %.1f rad' % (mode, c['steering_rad']), c['error_pct'], ' %', 'lower',
                '%.1f', 0.10, resolution=0.5)  # 0.07 -> 0.1 % is +40 % of a figure that is nil
    return out


# -- the kept file -----------------------------------------------------------------------------------

def _sensor_figures(new, add):
    """The sensor part's figures (the render worker's run `new`, None when not run), through key_figures' `add`."""
    if not new:
        return
    add('sensors.rtf', 'sensors in real time, render worker: real-time factor', new['rtf'], better='higher',
        fmt='%.3f', tolerance=0.02)
    add('sensors.cpu', 'sensors in real time: world server CPU (one core = 1)', new['cpu_world_server'],
        better='lower', fmt='%.3f', tolerance=0.10)
    for label, topic, _, _ in report.SENSOR_ROWS:
        add('sensors.hz.' + topic, 'sensors in real time: %s, wall Hz' % label,
            new['topics'].get(topic, {}).get('wall_hz'), ' Hz', 'higher', '%.1f', 0.05)
        plain = (new.get('plain') or {}).get('topics', {}).get(topic, {}).get('wall_hz')
        if plain is not None:  # runs before the plain subscriber was measured have none
            add('sensors.plain_hz.' + topic, 'sensors in real time: %s, plain subscriber, wall Hz' % label,
                plain, ' Hz', 'higher', '%.1f', 0.05)


def load(path=KEPT_FILE):
    """-> (kept dictionary, problem): ({}, why) when there is nothing usable to compare with."""
    try:
        with open(path) as f:
            kept = json.load(f)
    except FileNotFoundError:
        return {}, 'no kept figures yet (%s): `tools/run_bench.py --save` writes them' % os.path.relpath(path)
    except (OSError, ValueError) as err:
        return {}, 'kept figures unreadable (%s: %s): compared with nothing; `tools/run_bench.py --save` rewrites ' \
                   'the file' % (os.path.relpath(path), err)
    if not isinstance(kept, dict) or kept.get('format') != FORMAT or not isinstance(kept.get('figures'), dict):
        return {}, 'kept figures in %s are not in format %d: compared with nothing; `tools/run_bench.py --save` ' \
                   'rewrites the file' % (os.path.relpath(path), FORMAT)
    kept['figures'] = {k: f for k, f in kept['figures'].items() if _valid(f)}
    return kept, None


def _valid(f):
    return isinstance(f, dict) and all(isinstance(f.get(k), (int, float)) and math.isfinite(f[k])
                                       for k in ('median', 'min', 'max', 'n'))


def merged(kept, new, meta):
    """The file's new content: this run's figures replace the kept ones; figures this run did not
    measure (a failed part, --only) stay as they were, with the date they were saved."""
    figures = dict(kept.get('figures') or {})
    for key, f in new.items():
        figures[key] = dict(f, saved=meta.get('saved'))
    return dict(meta, format=FORMAT, figures=figures)


def save(content, path=KEPT_FILE):
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump(content, f, indent=1, sort_keys=True)
        f.write('\n')
    os.replace(tmp, path)


# -- the comparison ---------------------------------------------------------------------------------
def text(f):
    return stats.with_spread(f, f.get('fmt', '%.2f'), f.get('unit', ''))


def change(new, old):
    d = new['median'] - old['median']
    if old['median'] != 0:
        return '%+.1f %%' % (100.0 * d / abs(old['median']))
    return ('%+' + old.get('fmt', '%.2f').lstrip('%')) % d


def verdict(new, old):
    """'same', 'better', 'worse, within spread', REGRESSION, ... for one figure against its kept one.
    A change counts beyond the figure's tolerance (relative) and its resolution (absolute); a worse median is a
    REGRESSION when, in addition, the two spreads do not overlap (a noisy figure moving inside its own spread is
    reported, not flagged)."""
    better = new.get('better')
    now, was = new['median'], old['median']
    if abs(now - was) <= max(new.get('tolerance', TOLERANCE) * abs(was), new.get('resolution', 0.0)):
        return 'same'
    if better is None:
        return 'changed (not judged)'
    worse = now < was if better == 'higher' else now > was
    overlap = new['n'] > 1 and old['n'] > 1 and new['min'] <= old['max'] and old['min'] <= new['max']
    if worse:
        return 'worse, within spread' if overlap else REGRESSION
    return 'better, within spread' if overlap else 'better'


def compare(new, kept, quick=False):
    """[(figure, now, kept, change, verdict)]: every new figure, then kept figures not measured now.
    A --quick run (or a kept quick run) is shown beside the kept figures but not judged."""
    old = kept.get('figures') or {}
    judged = not quick and not kept.get('quick')
    rows = []
    for key, f in new.items():
        k = old.get(key)
        if k is None:
            rows.append((f['label'], text(f), 'none kept', '-', 'new figure'))
        else:
            rows.append((f['label'], text(f), text(k), change(f, k), verdict(f, k) if judged else 'not judged (quick)'))
    for key, k in old.items():
        if key not in new:
            rows.append((k.get('label', key), '-', text(k), '-', 'not measured this run'))
    return rows


def regressions(rows):
    return [r[0] for r in rows if r[4] == REGRESSION]


def describe(kept, machine=None):
    """Lines that say where the kept figures come from (and whether another machine made them)."""
    if not kept.get('figures'):
        return []
    m = kept.get('machine') or {}
    lines = ['kept figures: saved %s at commit %s on %s (%s cores), 1-min load up to %s' % (
        kept.get('saved', '?'), kept.get('commit') or '?', m.get('cpu', '?'), m.get('cpus', '?'),
        kept.get('load_max', '?'))]
    if machine and (m.get('cpu'), m.get('cpus')) != (machine.get('cpu'), machine.get('cpus')):
        lines.append('the kept figures come from another machine: a change may be the machine, not the code')
    return lines
