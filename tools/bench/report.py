"""The bench's table: figure, ours, reference, target, met? Figures measured more than once are
printed as median (min-max over n)."""
from . import stats

MB = 1024.0 * 1024.0

# Sensors in real time, every topic subscribed: (label, topic, declared Hz, target wall Hz for the new path).
# Issue 30's targets: every sensor near its declared rate with all of them subscribed, in real time
SENSOR_ROWS = (('/scan', '/scan', 40.0, 39.0), ('/imu', '/imu', 100.0, 99.0),
               ('camera 800x800', '/rrbot/camera1/image_raw', 30.0, 28.5),
               ('depth camera 640x480', '/real_sense/depth/image_raw', 20.0, 19.0))
SENSOR_RTF_TARGET = 0.98
SENSOR_PATH_NAMES = {'old': 'old: TinyRenderer in the physics thread', 'new': 'new: render worker'}
# Issue 18's targets: one car as fast as possible through ROS, median bridge/ceiling ratio; the world
# server in real time with no sensor subscribed, its CPU share of one core.
RATIO_TARGET = 0.85
REALTIME_CPU_TARGET = 0.20
# Issue 30: a world of ~90 mesh models, roslaunch to all of them in, mesh cache warm (bench/big_world.py)
BIG_WORLD_TARGET_S = 5.0


def _fmt(value, spec='%.2f', missing='-'):
    return missing if value is None else spec % value


def _met(ok):
    if ok is None:
        return '-'
    return 'yes' if ok else 'NO'


def rows(r):
    """[(figure, ours, reference, target, met)] from the results dictionary of tools/bench.py."""
    out = []
    add = lambda *row: out.append(tuple(str(x) for x in row))
    errors = r.get('errors', {})

    sp = r.get('speed')
    if sp:
        plain = sp['plain']
        spread = _spreads(plain)
        add('ceiling: bare PyBullet, our URDF, 1 ms step (real-time factor)', '%s, %.0f steps/s' % (
            stats.with_spread(spread['ceiling_rtf'], '%.1f'), plain['ceiling_steps_per_s']),
            '11-15 (ENVIRONMENT.md)', '-', '-')
        add('bridge as fast as possible: real-time factor', stats.with_spread(spread['bridge_rtf']),
            'Gazebo: 0.5-0.9', '-', '-')
        add('bridge / ceiling: median of %d side-by-side pairs (min-max)' % len(plain['rounds']),
            stats.with_spread(spread['ratio']), '-', '>= %.2f' % RATIO_TARGET, _met(plain['ratio'] >= RATIO_TARGET))
        sens = sp.get('sensors', {})
        if sens.get('available'):
            s_spread = _spreads(sens)
            add('bridge / ceiling, all sensors subscribed (min-max)', '%s, RTF %s' % (
                stats.with_spread(s_spread['ratio']), stats.with_spread(s_spread['bridge_rtf'])), '-', 'reported', '-')
        else:
            add('bridge / ceiling, all sensors subscribed', 'not available', '-', 'reported', '-')
        add('simulator RSS after start / after the sensor rounds / at %.0f s of sim time' % sp['memory_sim_s'],
            '%.0f / %.0f / %.0f MB' % (sp['rss_start_bytes'] / MB, sp['rss_after_sensors_bytes'] / MB,
                                       sp['rss_end_bytes'] / MB), '-', 'reported', '-')
    elif 'speed' in errors:
        add('speed (ceiling, bridge)', 'ERROR', '-', '-', 'NO')

    fleet = r.get('fleet')
    if fleet:
        for f in sorted(fleet.values(), key=lambda f: f['robots']):
            sp_ = f['spread']
            add('fleet: %d diff-drive robot%s with laser and IMU, as fast as possible: RTF racebot / bare PyBullet '
                '(ratio)' % (f['robots'], '' if f['robots'] == 1 else 's'),
                '%s / %s (%s)' % (stats.with_spread(sp_['rtf']), stats.with_spread(sp_['ceiling_rtf']),
                                  stats.with_spread(sp_['ratio'])), '-', 'reported', '-')
    elif 'fleet' in errors:
        add('fleet (1 to 8 robots)', 'ERROR', '-', '-', 'NO')

    rt = r.get('realtime')
    if rt:
        w = rt['window']
        add('real time (world settings): real-time factor over %.0f s wall' % w['wall_s'], '%.3f' % w['rtf'],
            'Gazebo: 1.00', '1.00 +- 0.02', _met(abs(w['rtf'] - 1.0) <= 0.02))
        cpu = '%.1f %%' % (100 * w['cpu'])
        if len(w.get('parts_cpu') or []) > 1:
            cpu += ' (%.1f-%.1f over %d parts of %.0f s)' % (100 * min(w['parts_cpu']), 100 * max(w['parts_cpu']),
                                                          len(w['parts_cpu']), w['wall_s'] / len(w['parts_cpu']))
        add('real time: simulator CPU (one core = 100 %), sensors off', cpu, '-', '<= %.0f %%' % (
            100 * REALTIME_CPU_TARGET), _met(w['cpu'] <= REALTIME_CPU_TARGET))
        lat = rt['latency']
        a, c = lat['applied_ms'], lat['callback_ms']
        add('command path: publish -> wheel commands applied, p50 / p99', '%s / %s ms' % (
            _fmt(a['p50']), _fmt(a['p99'])), '-', 'p99 <= 5 ms', _met(a['p99'] is not None and a['p99'] <= 5.0))
        add('command path: publish -> controller callback, p50 / p99', '%s / %s ms' % (
            _fmt(c['p50']), _fmt(c['p99'])), '-', '-', '-')
        add('delivery: %d distinct commands at 100 Hz' % lat['sent'], '%d arrived, %d applied' % (
            lat['delivered'], lat['applied']), '-', 'all %d' % lat['sent'], _met(lat['delivered'] == lat['sent']))
    elif 'realtime' in errors:
        add('real time, command path', 'ERROR', '-', '-', 'NO')

    sens = r.get('sensors')
    if sens and sens.get('new'):
        new, old = sens['new'], sens.get('old')
        add('sensors in real time, all subscribed, render worker: real-time factor',
            '%.3f' % new['rtf'], 'old path: %s' % (_fmt(old['rtf'], '%.3f') if old else '-'),
            '>= %.2f' % SENSOR_RTF_TARGET, _met(new['rtf'] >= SENSOR_RTF_TARGET))
        for label, topic, declared, target in SENSOR_ROWS:
            hz = new['topics'].get(topic, {}).get('wall_hz')
            was = old['topics'].get(topic, {}).get('wall_hz') if old else None
            add('sensors in real time: %s, messages per wall second (declared %g Hz)' % (label, declared),
                _fmt(hz, '%.1f Hz'), 'old path: %s' % _fmt(was, '%.1f Hz'), '>= %g Hz' % target,
                _met(hz is not None and hz >= target))
    elif 'sensors' in errors:
        add('sensors in real time', 'ERROR', '-', '-', 'NO')

    su = r.get('startup')
    if su and su.get('cold_s'):
        add('start-up: racebot.launch to 7 controllers running (median of %d, cold; min-max)' % len(su['cold_runs']),
            stats.with_spread(stats.spread(su['cold_runs']), unit=' s'), '-', '<= 5 s', _met(su['cold_s'] <= 5.0))
    if rt:
        add('start-up with the master already running', '%.2f s' % rt['startup_warm_s'], '-',
            '<= 5 s' if not (su and su.get('cold_s')) else '-',
            _met(rt['startup_warm_s'] <= 5.0) if not (su and su.get('cold_s')) else '-')

    bw = r.get('big_world')
    if bw:
        w, c, conv = bw['warm'], bw['cold'], bw['conversion']
        add('big world, %s, %d models: roslaunch -> all models listed, warm mesh cache' % (
            bw['world_kind'], bw['models']), stats.with_spread(w['models_s'], unit=' s'),
            'Gazebo: minutes (gazebo_ros_pkgs#680)', '<= %g s' % BIG_WORLD_TARGET_S,
            _met(w['models_s']['median'] <= BIG_WORLD_TARGET_S))
        add('big world: roslaunch -> first /clock, warm', stats.with_spread(w['clock_s'], unit=' s'), '-',
            '<= %g s' % BIG_WORLD_TARGET_S, _met(w['clock_s']['median'] <= BIG_WORLD_TARGET_S))
        add('big world, empty mesh cache: roslaunch -> all models / first /clock', '%s / %s' % (
            stats.with_spread(c['models_s'], unit=' s'), stats.with_spread(c['clock_s'], unit=' s')), '-',
            'reported', '-')
        add('big world, warm: of it, roslaunch -> master up / world server CPU time to all models in', '%s / %s' % (
            stats.with_spread(w['master_s'], unit=' s'), stats.with_spread(w['cpu_s'], unit=' s')), '-', 'reported',
            '-')
        add('big world: mesh conversion in a cold start, world server CPU cold - warm; %d meshes alone' % conv['files'],
            '%.2f of %.2f s; alone %.2f s CPU (%.2f s wall)' % (
                bw['cold_minus_warm_cpu_s'], c['cpu_s']['median'], conv['cpu_s'], conv['wall_s']),
            '-', 'reported', '-')
        add('big world: world server RSS, all models in, warm / cold', '%s / %s' % (
            stats.with_spread(w['rss_mb'], '%.0f', ' MB'), stats.with_spread(c['rss_mb'], '%.0f', ' MB')), '-',
            'reported', '-')
    elif 'big_world' in errors:
        add('big world (roslaunch -> all models)', 'ERROR', '-', '-', 'NO')

    fi = r.get('fidelity', {})
    par = fi.get('parallel')
    if par:
        for s in par['speeds']:
            add('steady speed at %.1f m/s (model_states)' % s['commanded'], '%.3f m/s (%.1f %%)' % (
                s['measured'], s['error_pct']), '%.1f' % s['commanded'], '<= 5 %', _met(s['error_pct'] <= 5.0))
    for mode in ('parallel', 'ackermann'):
        f = fi.get(mode)
        if not f:
            if mode in fi.get('skipped', []):
                add('turning circles, %s steering' % mode, 'skipped (quick)', '-', '-', '-')
            continue
        for c in f['circles']:
            add('turning radius, %s, steering %.1f rad, 0.5 m/s' % (mode, c['steering_rad']), '%.3f m (%.1f %%)' % (
                c['measured_m'], c['error_pct']), '%.3f (L/tan d)' % c['reference_m'], '<= 10 %',
                _met(c['error_pct'] <= 10.0))
    if par:
        for lock in par['full_lock']:
            add('full lock %+.1f rad at %.0f m/s for %.0f s' % (lock['steering_rad'], lock['speed'], lock['sim_s']),
                'max tilt %s deg, %s' % (_fmt(lock['max_tilt_deg'], '%.1f'),
                                         'finite' if lock['finite'] else 'NOT finite'),
                '-', 'no flip, finite', _met(lock['ok']))
    for mode in ('parallel', 'ackermann'):
        if 'fidelity_' + mode in errors:
            add('fidelity, %s steering' % mode, 'ERROR', '-', '-', 'NO')

    ip = r.get('inprocess')
    if ip:
        h = ip['hinge']
        add('hinge step 0 -> 0.3 rad (p 10, d 0.5): rise 10-90 %', _fmt(h['rise_time_s'], '%.3f s'), '-', '-', '-')
        add('hinge step: overshoot / final value', '%.1f %% / %.4f rad' % (h['overshoot_pct'], h['final_rad']),
            '-', '-', '-')
        add('hinge step: settling into 2 %', _fmt(h['settling_time_s'], '%.3f s', 'not within 2 %% in %.0f s'
                                                  % h['duration_s']), '-', '-', '-')
        add('simulator in-process, no ROS (real-time factor; min-max)', stats.with_spread(
            stats.spread(ip.get('sim_rtf_runs') or [ip['sim_rtf']]), '%.1f'), '-', '-', '-')
    elif 'inprocess' in errors:
        add('hinge step', 'ERROR', '-', '-', 'NO')

    de = r.get('determinism')
    if de:
        add('determinism: two runs, %.0f s scripted, max difference' % de['sim_s'], '%.1e m' % de['max_diff_m'],
            'Gazebo: not deterministic', '<= 1e-9 m', _met(de['max_diff_m'] <= 1e-9))
    elif 'determinism' in errors:
        add('determinism', 'ERROR', '-', '-', 'NO')
    return out


def _spreads(rounds_result):
    """The min-max of each figure over the side-by-side pairs (older results without 'spread': from the rounds)."""
    if rounds_result.get('spread'):
        return rounds_result['spread']
    pairs = rounds_result['rounds']
    spread = stats.of_pairs(pairs, ('ceiling_rtf', 'rtf', 'ratio'))
    spread['bridge_rtf'] = spread.pop('rtf')
    return spread


def sensor_rate_rows(sens):
    """The rows plot.sensor_rates draws: each topic's wall Hz per path (None when not measured)."""
    return [{'label': label, 'declared_hz': declared, 'target_hz': target,
             'paths': {SENSOR_PATH_NAMES[k]: sens[k]['topics'].get(topic, {}).get('wall_hz')
                       for k in ('old', 'new') if k in sens}}
            for label, topic, declared, target in SENSOR_ROWS]


def sensor_table(sens):
    """Old path and new path side by side: RTF, each sensor's wall Hz, CPU, load average."""
    paths = [k for k in ('old', 'new') if k in sens]
    header = ('sensors in real time, all subscribed',) + tuple(SENSOR_PATH_NAMES[k] for k in paths)
    rows_ = [('real-time factor',) + tuple('%.3f' % sens[k]['rtf'] for k in paths)]
    for label, topic, declared, _ in SENSOR_ROWS:
        rows_.append(('%s (declared %g Hz), wall Hz' % (label, declared),) + tuple(
            _fmt(sens[k]['topics'].get(topic, {}).get('wall_hz'), '%.1f') for k in paths))
    rows_.append(('CPU: world server / render worker (one core = 100 %)',) + tuple(
        '%.0f %% / %.0f %%' % (100 * sens[k]['cpu_world_server'], 100 * sens[k]['cpu_children']) for k in paths))
    rows_.append(('renderer',) + tuple(str(sens[k].get('renderer') or '-') for k in paths))
    rows_.append(('1-min load average after',) + tuple('%.2f' % sens[k]['loadavg'][0] for k in paths))
    n = len(header)
    widths = [max(len(r[i]) for r in rows_ + [header]) for i in range(n)]
    line = lambda r: '| ' + ' | '.join(r[i].ljust(widths[i]) for i in range(n)) + ' |'
    return '\n'.join([line(header), '|' + '|'.join('-' * (w + 2) for w in widths) + '|'] + [line(r) for r in rows_])


BUDGET_STAGES = (('render', 'worker'), ('convert', 'worker'), ('message', 'world server'),
                 ('serialize', 'world server'), ('send', 'world server'), ('receive', 'subscriber'))


def camera_budget(budget, sens=None, realtime=None):
    """What the declared camera rates need of two cores, from bench/camera_budget.py's per-frame CPU times, beside
    what the sensor run measured: lines to print."""
    if not budget:
        return []
    out = ['camera budget: CPU ms per frame by stage (%s, LP_NUM_THREADS %s), and what the declared rate needs:'
           % (budget['renderer'], budget.get('lp_num_threads'))]
    need = {'worker': 0.0, 'world server': 0.0, 'subscriber': 0.0}
    for name, cam in sorted(budget['cameras'].items()):
        ms, rate = cam['ms'], cam['rate_hz']
        parts = ', '.join('%s %.2f' % (k, ms[k]) for k, _ in BUDGET_STAGES)
        out.append('- %s %dx%d (%s) at %g Hz: %s (readback of an empty view %.2f of render); %.1f MB a frame'
                   % (name, cam['width'], cam['height'], cam['type'], rate, parts, ms['readback'], cam['bytes'] / 1e6))
        for stage, where in BUDGET_STAGES:
            need[where] += rate * ms[stage] / 1000.0
    physics = realtime['window']['cpu'] if realtime else None
    total = sum(need.values()) + (physics or 0.0)
    out.append('- at the declared rates: render worker %.2f of a core (one process: at most 1), world server %.2f '
               'for the frames + %s for the physics with nothing subscribed (real-time part), a subscriber at '
               'least %.2f: %.2f of the 2 cores' % (need['worker'], need['world server'],
                                                    '%.2f' % physics if physics is not None else 'n/a',
                                                    need['subscriber'], total))
    new = (sens or {}).get('new')
    if new:
        got = {t: new['topics'].get(t, {}).get('wall_hz') for _, t, _, _ in SENSOR_ROWS}
        out.append('- measured (render worker path): world server %.2f, render worker %.2f, bench subscriber (rospy) '
                   '%.2f of a core; %s' % (new['cpu_world_server'], new['cpu_children'], new.get('cpu_subscriber', 0),
                                           ', '.join('%s %s of %g Hz' % (label, _fmt(got[t], '%.1f'), declared)
                                                     for label, t, declared, _ in SENSOR_ROWS)))
        published = new.get('published') or {}
        skipped = ['%s %.1f/s' % (t, v['skipped_per_s']) for t, v in sorted(published.items()) if v['skipped_per_s']]
        if skipped:
            out.append('- frames the simulator skipped (the worker still held two of that camera): %s'
                       % ', '.join(skipped))
    return out


def notes(r):
    """Why each missed target was missed, from the raw figures: lines to print under the table."""
    out = []
    load = max((x['loadavg'][0] for x in r.get('load', [])), default=None)
    sp, rt = r.get('speed'), r.get('realtime')
    if sp and sp['plain']['ratio'] < RATIO_TARGET:
        out.append('bridge / ceiling below %.2f: where the world server spends its time is in the profile below.'
                   % RATIO_TARGET)
    if rt:
        w, lat = rt['window'], rt['latency']
        if abs(w['rtf'] - 1.0) > 0.02:
            out.append('real-time factor off by more than 0.02 (per 10 s: %s): the update loop could not keep its '
                       'schedule; the machine load was up to %s.' % (w['parts_rtf'], load))
        if w['cpu'] > REALTIME_CPU_TARGET:
            out.append('simulator CPU above %.0f %%: see the profile below.' % (100 * REALTIME_CPU_TARGET))
        a = lat['applied_ms']
        if a['p99'] is None or a['p99'] > 5.0:
            seg = lat.get('segments_ms', {})
            out.append('command path p99 above 5 ms. Its parts (p50 / p99 ms): publish -> first controller callback '
                       '%s; first -> fourth wheel controller callback %s; last callback -> update that applies it %s. '
                       'The first two are rospy transport through servo_commands, which publishes the six commands '
                       'one after the other through queued publishers (a writer thread per subscriber); their tail '
                       'is scheduling on a machine with load up to %s on %s cores. The simulator\'s own part is the '
                       'last (at most one 1 ms update period when the loop is on time).' % (
                           _pair(seg.get('publish_to_first_callback')),
                           _pair(seg.get('first_to_fourth_wheel_callback')),
                           _pair(seg.get('last_callback_to_applied')), load, r.get('machine', {}).get('cpus')))
        if lat['delivered'] != lat['sent']:
            out.append('%d of %d commands never reached the controllers.' % (
                lat['sent'] - lat['delivered'], lat['sent']))
    su = r.get('startup')
    if su and su.get('cold_s') and su['cold_s'] > 5.0:
        out.append('start-up above 5 s (runs: %s s): roslaunch, the master and six Python nodes start at once on '
                   '%s cores; with the machine load up to %s they queue for the CPU. With the master running it took '
                   '%s s.' % (', '.join('%.2f' % x for x in su['cold_runs']), r.get('machine', {}).get('cpus'), load,
                              '%.2f' % rt['startup_warm_s'] if rt else '-'))
    bw = r.get('big_world')
    if bw:
        out.append('big world: %s, started by `%s`%s.' % (bw['world'], bw['launch'], (
            ' (not the corpus\'s house: %s)' % bw['why_not_house']) if bw.get('why_not_house') else ''))
        if bw['warm']['models_s']['median'] > BIG_WORLD_TARGET_S:
            out.append('big world above %g s warm (world server CPU to all models in: %.2f s; load up to %s): '
                       'profile the start with py-spy (tools/bench/profiling.py).' % (
                           BIG_WORLD_TARGET_S, bw['warm']['cpu_s']['median'], load))
    par = (r.get('fidelity') or {}).get('parallel')
    if par and any(c['error_pct'] > 10.0 for c in par['circles']):
        ack = (r.get('fidelity') or {}).get('ackermann')
        out.append('parallel steering misses the bicycle model: it is the tutorial\'s mapping (both hinges at the '
                   'bicycle angle), not Ackermann geometry, so the inner front wheel steers too little, the front '
                   'tyres scrub and the car understeers (a larger circle). steering_mode:=ackermann follows the '
                   'model%s.' % (' (errors %s %%)' % ', '.join('%.1f' % c['error_pct'] for c in ack['circles'])
                                 if ack else ''))
    return out


def _pair(stats):
    if not stats or stats.get('p50') is None:
        return '-'
    return '%.2f / %.2f' % (stats['p50'], stats['p99'])


def table(rows_, header=('figure', 'ours', 'reference', 'target', 'met?')):
    widths = [max(len(header[i]), *(len(r[i]) for r in rows_)) if rows_ else len(header[i]) for i in range(5)]
    line = lambda r: '| ' + ' | '.join(r[i].ljust(widths[i]) for i in range(5)) + ' |'
    return '\n'.join([line(header), '|' + '|'.join('-' * (w + 2) for w in widths) + '|'] + [line(r) for r in rows_])
