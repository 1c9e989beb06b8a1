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


CEILING_REFERENCE = '11-15 (bare PyBullet, 1 core)'  # steps per ms of sim time: 11,000-15,000 steps/s measured


def _one(condition):
    """A row spec's `each` that gives its section's data once when condition(data) holds, else nothing."""
    return lambda x: [x] if condition(x) else []


def _speed_ceiling(sp):
    plain = sp['plain']
    return '%s, %.0f steps/s' % (stats.with_spread(_spreads(plain)['ceiling_rtf'], '%.1f'),
                                 plain['ceiling_steps_per_s'])


def _realtime_cpu(w):
    cpu = '%.1f %%' % (100 * w['cpu'])
    if len(w.get('parts_cpu') or []) > 1:
        cpu += ' (%.1f-%.1f over %d parts of %.0f s)' % (100 * min(w['parts_cpu']), 100 * max(w['parts_cpu']),
                                                      len(w['parts_cpu']), w['wall_s'] / len(w['parts_cpu']))
    return cpu


def _cold_startup(r):
    su = r.get('startup')
    return bool(su and su.get('cold_s'))


def _hz(sensor_path, topic):
    return sensor_path['topics'].get(topic, {}).get('wall_hz') if sensor_path else None


def _circles(fidelity, mode):
    """A steering mode's turning circles; [None] (one 'skipped' row) for a mode a quick run skipped."""
    if fidelity.get(mode):
        return fidelity[mode]['circles']
    return [None] if mode in fidelity.get('skipped', []) else []


def _spread_pair(a, b, spec='%.2f', unit=' s'):
    return '%s / %s' % (stats.with_spread(a, spec, unit), stats.with_spread(b, spec, unit))


# The table, section by section: (section's data from the results, the error that stands in for a missing section
# (key in results['errors'], figure) or None, its rows). A row: (each, figure, ours, reference, target, met), each
# None (one row of the section's data) or a function of the data giving the items of one row each; the other
# fields are text, or functions of the data (or item) giving text.
SECTIONS = (
    (lambda r: r.get('speed'), ('speed', 'speed (ceiling, bridge)'), (
        (None, 'ceiling: bare PyBullet, our URDF, 1 ms step (real-time factor)', _speed_ceiling, CEILING_REFERENCE,
         '-', '-'),
        (None, 'bridge as fast as possible: real-time factor',
         lambda sp: stats.with_spread(_spreads(sp['plain'])['bridge_rtf']), 'Gazebo: 0.5-0.9', '-', '-'),
        (None, lambda sp: 'bridge / ceiling: median of %d side-by-side pairs (min-max)' % len(sp['plain']['rounds']),
         lambda sp: stats.with_spread(_spreads(sp['plain'])['ratio']), '-', '>= %.2f' % RATIO_TARGET,
         lambda sp: _met(sp['plain']['ratio'] >= RATIO_TARGET)),
        (lambda sp: [sp['sensors']] if sp.get('sensors', {}).get('available') else [],
         'bridge / ceiling, all sensors subscribed (min-max)', lambda sens: '%s, RTF %s' % (
             stats.with_spread(_spreads(sens)['ratio']), stats.with_spread(_spreads(sens)['bridge_rtf'])),
         '-', 'reported', '-'),
        (_one(lambda sp: not sp.get('sensors', {}).get('available')), 'bridge / ceiling, all sensors subscribed',
         'not available', '-', 'reported', '-'),
        (None, lambda sp: 'simulator RSS after start / after the sensor rounds / at %.0f s of sim time'
         % sp['memory_sim_s'], lambda sp: '%.0f / %.0f / %.0f MB' % (
             sp['rss_start_bytes'] / MB, sp['rss_after_sensors_bytes'] / MB, sp['rss_end_bytes'] / MB),
         '-', 'reported', '-'))),
    (lambda r: r.get('fleet'), ('fleet', 'fleet (1 to 8 robots)'), (
        (lambda fleet: sorted(fleet.values(), key=lambda f: f['robots']),
         lambda f: 'fleet: %d diff-drive robot%s with laser and IMU, as fast as possible: RTF racebot / bare '
         'PyBullet (ratio)' % (f['robots'], '' if f['robots'] == 1 else 's'),
         lambda f: '%s / %s (%s)' % (stats.with_spread(f['spread']['rtf']), stats.with_spread(
             f['spread']['ceiling_rtf']), stats.with_spread(f['spread']['ratio'])), '-', 'reported', '-'),)),
    (lambda r: r.get('realtime'), ('realtime', 'real time, command path'), (
        (None, lambda rt: 'real time (world settings): real-time factor over %.0f s wall' % rt['window']['wall_s'],
         lambda rt: '%.3f' % rt['window']['rtf'], 'Gazebo: 1.00', '1.00 +- 0.02',
         lambda rt: _met(abs(rt['window']['rtf'] - 1.0) <= 0.02)),
        (None, 'real time: simulator CPU (one core = 100 %), sensors off', lambda rt: _realtime_cpu(rt['window']), '-',
         '<= %.0f %%' % (100 * REALTIME_CPU_TARGET), lambda rt: _met(rt['window']['cpu'] <= REALTIME_CPU_TARGET)),
        (None, 'command path: publish -> wheel commands applied, p50 / p99', lambda rt: '%s / %s ms' % (
            _fmt(rt['latency']['applied_ms']['p50']), _fmt(rt['latency']['applied_ms']['p99'])), '-', 'p99 <= 5 ms',
         lambda rt: _met(rt['latency']['applied_ms']['p99'] is not None and rt['latency']['applied_ms']['p99'] <= 5.0)),
        (None, 'command path: publish -> controller callback, p50 / p99', lambda rt: '%s / %s ms' % (
            _fmt(rt['latency']['callback_ms']['p50']), _fmt(rt['latency']['callback_ms']['p99'])), '-', '-', '-'),
        (lambda rt: [rt['latency']], lambda lat: 'delivery: %d distinct commands at 100 Hz' % lat['sent'],
         lambda lat: '%d arrived, %d applied' % (lat['delivered'], lat['applied']), '-',
         lambda lat: 'all %d' % lat['sent'], lambda lat: _met(lat['delivered'] == lat['sent'])))),
    (lambda r: r.get('sensors') if r.get('sensors') and r['sensors'].get('new') else None,
     ('sensors', 'sensors in real time'), (
        (None, 'sensors in real time, all subscribed, render worker: real-time factor',
         lambda sens: '%.3f' % sens['new']['rtf'],
         lambda sens: 'old path: %s' % (_fmt(sens['old']['rtf'], '%.3f') if sens.get('old') else '-'),
         '>= %.2f' % SENSOR_RTF_TARGET, lambda sens: _met(sens['new']['rtf'] >= SENSOR_RTF_TARGET)),
        (lambda sens: [(sens, row) for row in SENSOR_ROWS],
         lambda x: 'sensors in real time: %s, messages per wall second (declared %g Hz)' % (x[1][0], x[1][2]),
         lambda x: _fmt(_hz(x[0]['new'], x[1][1]), '%.1f Hz'),
         lambda x: 'old path: %s' % _fmt(_hz(x[0].get('old'), x[1][1]), '%.1f Hz'), lambda x: '>= %g Hz' % x[1][3],
         lambda x: _met(_hz(x[0]['new'], x[1][1]) is not None and _hz(x[0]['new'], x[1][1]) >= x[1][3])))),
    (lambda r: r, None, (
        (_one(_cold_startup), lambda r: 'start-up: racebot.launch to 7 controllers running (median of %d, cold; '
         'min-max)' % len(r['startup']['cold_runs']),
         lambda r: stats.with_spread(stats.spread(r['startup']['cold_runs']), unit=' s'), '-', '<= 5 s',
         lambda r: _met(r['startup']['cold_s'] <= 5.0)),
        (_one(lambda r: r.get('realtime')), 'start-up with the master already running',
         lambda r: '%.2f s' % r['realtime']['startup_warm_s'], '-',
         lambda r: '<= 5 s' if not _cold_startup(r) else '-',
         lambda r: _met(r['realtime']['startup_warm_s'] <= 5.0) if not _cold_startup(r) else '-'))),
    (lambda r: r.get('big_world'), ('big_world', 'big world (roslaunch -> all models)'), (
        (None, lambda bw: 'big world, %s, %d models: roslaunch -> all models listed, warm mesh cache' % (
            bw['world_kind'], bw['models']), lambda bw: stats.with_spread(bw['warm']['models_s'], unit=' s'),
         'Gazebo: minutes (gazebo_ros_pkgs#680)', '<= %g s' % BIG_WORLD_TARGET_S,
         lambda bw: _met(bw['warm']['models_s']['median'] <= BIG_WORLD_TARGET_S)),
        (None, 'big world: roslaunch -> first /clock, warm', lambda bw: stats.with_spread(bw['warm']['clock_s'],
                                                                                          unit=' s'),
         '-', '<= %g s' % BIG_WORLD_TARGET_S, lambda bw: _met(bw['warm']['clock_s']['median'] <= BIG_WORLD_TARGET_S)),
        (None, 'big world, empty mesh cache: roslaunch -> all models / first /clock',
         lambda bw: _spread_pair(bw['cold']['models_s'], bw['cold']['clock_s']), '-', 'reported', '-'),
        (None, 'big world, warm: of it, roslaunch -> master up / world server CPU time to all models in',
         lambda bw: _spread_pair(bw['warm']['master_s'], bw['warm']['cpu_s']), '-', 'reported', '-'),
        (None, lambda bw: 'big world: mesh conversion in a cold start, world server CPU cold - warm; %d meshes alone'
         % bw['conversion']['files'], lambda bw: '%.2f of %.2f s; alone %.2f s CPU (%.2f s wall)' % (
             bw['cold_minus_warm_cpu_s'], bw['cold']['cpu_s']['median'], bw['conversion']['cpu_s'],
             bw['conversion']['wall_s']), '-', 'reported', '-'),
        (None, 'big world: world server RSS, all models in, warm / cold',
         lambda bw: _spread_pair(bw['warm']['rss_mb'], bw['cold']['rss_mb'], '%.0f', ' MB'), '-', 'reported', '-'))),
    (lambda r: r.get('fidelity', {}).get('parallel'), None, (
        (lambda par: par['speeds'], lambda s: 'steady speed at %.1f m/s (model_states)' % s['commanded'],
         lambda s: '%.3f m/s (%.1f %%)' % (s['measured'], s['error_pct']), lambda s: '%.1f' % s['commanded'],
         '<= 5 %', lambda s: _met(s['error_pct'] <= 5.0)),)),
    (lambda r: r.get('fidelity', {}), None, (
        (lambda fi: [(mode, c) for mode in ('parallel', 'ackermann') for c in _circles(fi, mode)],
         lambda x: 'turning circles, %s steering' % x[0] if x[1] is None else
         'turning radius, %s, steering %.1f rad, 0.5 m/s' % (x[0], x[1]['steering_rad']),
         lambda x: 'skipped (quick)' if x[1] is None else '%.3f m (%.1f %%)' % (x[1]['measured_m'], x[1]['error_pct']),
         lambda x: '-' if x[1] is None else '%.3f (L/tan d)' % x[1]['reference_m'],
         lambda x: '-' if x[1] is None else '<= 10 %',
         lambda x: '-' if x[1] is None else _met(x[1]['error_pct'] <= 10.0)),)),
    (lambda r: r.get('fidelity', {}).get('parallel'), None, (
        (lambda par: par['full_lock'], lambda lock: 'full lock %+.1f rad at %.0f m/s for %.0f s' % (
            lock['steering_rad'], lock['speed'], lock['sim_s']), lambda lock: 'max tilt %s deg, %s' % (
            _fmt(lock['max_tilt_deg'], '%.1f'), 'finite' if lock['finite'] else 'NOT finite'),
         '-', 'no flip, finite', lambda lock: _met(lock['ok'])),)),
    (lambda r: r.get('errors'), None, (
        (lambda errors: [mode for mode in ('parallel', 'ackermann') if 'fidelity_' + mode in errors],
         lambda mode: 'fidelity, %s steering' % mode, 'ERROR', '-', '-', 'NO'),)),
    (lambda r: r.get('inprocess'), ('inprocess', 'hinge step'), (
        (None, 'hinge step 0 -> 0.3 rad (p 10, d 0.5): rise 10-90 %',
         lambda ip: _fmt(ip['hinge']['rise_time_s'], '%.3f s'), '-', '-', '-'),
        (None, 'hinge step: overshoot / final value',
         lambda ip: '%.1f %% / %.4f rad' % (ip['hinge']['overshoot_pct'], ip['hinge']['final_rad']), '-', '-', '-'),
        (None, 'hinge step: settling into 2 %', lambda ip: _fmt(ip['hinge']['settling_time_s'], '%.3f s',
                                                               'not within 2 %% in %.0f s' % ip['hinge']['duration_s']),
         '-', '-', '-'),
        (None, 'simulator in-process, no ROS (real-time factor; min-max)', lambda ip: stats.with_spread(
            stats.spread(ip.get('sim_rtf_runs') or [ip['sim_rtf']]), '%.1f'), '-', '-', '-'))),
    (lambda r: r.get('plugins'), ('plugins', 'compiled plugins'), (
        (None, 'compiled model plugin: an empty worldUpdateBegin callback, per update above none (us; min-max)',
         lambda pl: stats.with_spread(pl['overhead_spread_us']['cpp_empty'], '%.2f'), '-', '<= 5 us',
         lambda pl: _met(pl['overhead_us']['cpp_empty'] <= 5.0)),
        (None, 'compiled model plugin: Joint::SetVelocity every update, above none (us; min-max)',
         lambda pl: stats.with_spread(pl['overhead_spread_us']['cpp_velocity'], '%.2f'),
         lambda pl: 'Python plugin, same work: %s' % stats.with_spread(pl['overhead_spread_us']['python_velocity'],
                                                                       '%.2f'), '-', '-'))),
    (lambda r: r.get('controllers'), ('controllers', 'compiled controllers'), (
        (None, 'compiled ros_control controller: a velocity command to a joint every update, above none (us; min-max)',
         lambda co: stats.with_spread(co['overhead_spread_us']['cpp'], '%.2f'),
         lambda co: 'Python controller, same work: %s' % stats.with_spread(co['overhead_spread_us']['python'],
                                                                          '%.2f'), '-', '-'),)),
    (lambda r: r.get('determinism'), ('determinism', 'determinism'), (
        (None, lambda de: 'determinism: two runs, %.0f s scripted, max difference' % de['sim_s'],
         lambda de: '%.1e m' % de['max_diff_m'], 'Gazebo: not deterministic', '<= 1e-9 m',
         lambda de: _met(de['max_diff_m'] <= 1e-9)),)),
)


def rows(r):
    """[(figure, ours, reference, target, met)] from the results dictionary of tools/run_bench.py (SECTIONS)."""
    out = []
    for section, error, specs in SECTIONS:
        data = section(r)
        if data:
            for each, *fields in specs:
                for x in (each(data) if each else (data,)):
                    out.append(tuple(str(f(x) if callable(f) else f) for f in fields))
        elif error and error[0] in r.get('errors', {}):
            out.append((error[1], 'ERROR', '-', '-', 'NO'))
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
    rows_.append(('first message on every topic after subscribing (plain, first), wall s',) + tuple(
        '%s / %s' % (_fmt((sens[k].get('plain') or {}).get('first_message_s'), '%.1f'),
                     _fmt(sens[k].get('first_message_s'), '%.1f')) for k in paths))
    rows_.append(('the same through a plain subscriber (as rostopic hz), RTF',) + tuple(
        _fmt((sens[k].get('plain') or {}).get('rtf'), '%.3f') for k in paths))
    hz = lambda window, topic: _fmt(((window or {}).get('topics') or {}).get(topic, {}).get('wall_hz'), '%.1f')
    for label, topic, declared, _ in SENSOR_ROWS:
        rows_.append(('%s, plain subscriber before / after the above, wall Hz' % label,) + tuple(
            '%s / %s' % (hz(sens[k].get('plain'), topic), hz(sens[k].get('plain_after'), topic)) for k in paths))
    for label, topic, declared, _ in SENSOR_ROWS[2:]:  # the cameras: did the frames go unmade, or unreceived?
        rows_.append(('%s, published by the world server (plain / above / plain after), wall Hz' % label,) + tuple(
            ' / '.join(hz({'topics': (w or {}).get('published')}, topic)
                       for w in (sens[k].get('plain'), sens[k], sens[k].get('plain_after'))) for k in paths))
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
