#!/usr/bin/env python3
"""make corpus: public ROS 1 robot and world packages, unchanged, run on racebot; prints and writes the table.

    tools/corpus/run.py [--only NAME[,NAME]] [--out DIR] [--list] [--keep-going-after S]
    (devel/setup.bash sourced; `make corpus ARGS='--only husky'`)

For each row of tools/corpus/manifest.yaml: its repositories at their pinned commits (sources.py says
from where: a clone it makes in ~/.cache/racebot/corpus, RACEBOT_CORPUS_DIR's existing clones or
RACEBOT_CORPUS_MIRRORS), a catkin workspace of the row's packages on top of racebot's devel space
(`catkin_make`, the row's blacklist left out), its commands as its users type them, headless (no
DISPLAY), with a ROS master of its own, then checks.py's checks, then everything stopped. Writes
out/corpus/corpus.md and corpus.json, logs in out/corpus/logs/<row>/. Exit status 0 only when every
row passes. Nothing of theirs is copied into this repository.
"""
import argparse
import datetime
import json
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import time
import traceback

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from corpus import manifest, sources, table  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHECKS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'checks.py')
BUILD_TIMEOUT_S = 1800
CHECKS_TIMEOUT_S = 600
UNDERLAY_LINE = 'racebot deps: underlay: source '


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def python():
    venv = os.path.join(ROOT, '.venv', 'bin', 'python3')
    return venv if os.path.exists(venv) else sys.executable


COMPILE_ERROR = re.compile(r'/src/([^/\s]+)/\S*:\d+:\d+: ((?:fatal )?error: .*)')
BUILD_ERROR_PATTERNS = [
    re.compile(r'Could not find a package configuration file provided by "([^"]+)"'),
    re.compile(r'Could not find a configuration file for package "([^"]+)"'),
    re.compile(r'(fatal error: .*)'),
    re.compile(r'(error: .*)'),
    re.compile(r'(CMake Error at [^:]+:\d+ \(\w+\):.*)'),
    re.compile(r'(Could NOT find .*)'),
]


def build_error(log_text):
    """The first cause in a catkin_make log, one line: which package, what it could not find or compile."""
    project = None
    for line in log_text.splitlines():
        started = re.search(r"~~\s+- (\S+)$|^-- ==> add_subdirectory\((.+)\)$|Processing catkin package: '(.+)'",
                            line)
        if started:
            project = next(g for g in started.groups() if g)
            continue
        for pattern in BUILD_ERROR_PATTERNS[:2]:
            found = pattern.search(line)
            if found:
                return '%s: find_package(%s) found nothing' % (project or '?', found.group(1))
    lines = log_text.splitlines()
    for line in lines:  # a compiler's error names its source file, hence its package
        found = COMPILE_ERROR.search(line)
        if found:
            return '%s: %s' % found.groups()
    for i, line in enumerate(lines):
        for pattern in BUILD_ERROR_PATTERNS[2:]:
            found = pattern.search(line)
            if found:
                detail = found.group(1).strip()
                if detail.startswith('CMake Error') and i + 1 < len(lines):
                    detail += ' ' + ' '.join(x.strip() for x in lines[i + 1:i + 4] if x.strip())
                return '%s: %s' % (project or '?', detail)
    tail = [x for x in lines if x.strip()][-1:] or ['(empty log)']
    return tail[0].strip()


ANSI = re.compile(r'\x1b\[[0-9;]*m|\x1b\]2;[^\x07]*\x07')
LAUNCH_PATTERNS = {
    'fatal': re.compile(r'\[FATAL\] \[[\d.]+(?:, [\d.]+)?\]: (.*)'),
    'died': re.compile(r'\[([^\]]+)\] process has died \[pid \d+, exit code (-?\d+)'),
    'missing': re.compile(r'ERROR: cannot launch node of type \[([^\]]+)\]: (.*)'),
    'error': re.compile(r'^(RLException: .*|ResourceNotFound: .*|Invalid roslaunch XML syntax.*|'
                        r'.*error loading <rosparam> tag.*|Resource not found: .*)$'),
}


def launch_notes(log_text):
    """What a roslaunch log says went wrong: nodes that died (with exit codes), node types that could not
    be started (a package missing), roslaunch's own fatal error and nodes' FATAL log lines."""
    died, missing, errors, fatal = [], [], [], []
    for line in ANSI.sub('', log_text).splitlines():
        found = LAUNCH_PATTERNS['fatal'].search(line)
        if found:
            fatal.append(found.group(1).strip())
        found = LAUNCH_PATTERNS['died'].search(line)
        if found and found.group(2) != '0':
            died.append('%s (exit %s)' % (re.sub(r'-\d+$', '', found.group(1)), found.group(2)))
        found = LAUNCH_PATTERNS['missing'].search(line)
        if found:
            missing.append('%s (%s)' % (found.group(1), found.group(2).strip()))
        found = LAUNCH_PATTERNS['error'].search(line.strip())
        if found:
            errors.append(found.group(1))
    return {'died': sorted(set(died)), 'missing': sorted(set(missing)), 'errors': errors[:3], 'fatal': fatal[:3]}


def shell_env(script, base):
    """The environment after `source script` in bash, starting from `base`."""
    done = subprocess.run(['bash', '-c', 'source %s >/dev/null 2>&1 && env -0' % shlex.quote(script)],
                          env=base, stdout=subprocess.PIPE, check=True)
    return dict(item.split('=', 1) for item in done.stdout.decode().split('\0') if '=' in item)


def make_workspace(row, trees, ws):
    """ws/src holding a link to each package folder the row takes and the row's own packages (`user_packages`);
    returns the package folder names."""
    src = os.path.join(ws, 'src')
    os.makedirs(src, exist_ok=True)
    for entry in os.listdir(src):
        path = os.path.join(src, entry)
        if os.path.islink(path):
            os.unlink(path)
    names = []
    for repo in row['repos']:
        tree = trees[repo['repo']]
        for package in repo['packages']:
            target = tree if package == '.' else os.path.join(tree, package)
            name = repo['repo'].split('/')[1] if package == '.' else os.path.basename(package.rstrip('/'))
            os.symlink(target, os.path.join(src, name))
            names.append(name)
    for name, files in sorted((row.get('user_packages') or {}).items()):  # the user's own, written afresh
        shutil.rmtree(os.path.join(src, name), ignore_errors=True)
        for path, text in sorted(files.items()):
            path = os.path.join(src, name, path)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, 'w') as f:
                f.write(text)
        names.append(name)
    return names


def build(row, ws, env, log_path):
    blacklist = ';'.join(sorted(row.get('blacklist') or {}))
    # A configure from scratch (the objects are kept): the workspace's build folder is kept between runs, and
    # CMake's cache keeps where find_package found each package then (pluginlib_DIR), even with --force-cmake;
    # racebot's devel space changes under it (its pluginlib overlay came after racecar's first build, which went on
    # compiling against Debian's pluginlib). --force-cmake: with a Makefile there, catkin_make would otherwise only
    # run `make cmake_check_build_system`, which configures without its devel and install spaces.
    cache = os.path.join(ws, 'build', 'CMakeCache.txt')
    if os.path.exists(cache):
        os.remove(cache)
    cmd = ['catkin_make', '--force-cmake', '-C', ws, '-DPYTHON_EXECUTABLE=%s' % python(),
           '-DCATKIN_BLACKLIST_PACKAGES=%s' % blacklist, '-DCATKIN_WHITELIST_PACKAGES=']
    with open(log_path, 'w') as log:
        log.write('$ %s\n' % ' '.join(shlex.quote(c) for c in cmd))
        log.flush()
        try:
            code = subprocess.call(cmd, env=env, stdout=log, stderr=subprocess.STDOUT, timeout=BUILD_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            code = 'timeout'
    if code == 0:
        return 'ok'
    with open(log_path, errors='replace') as f:
        return 'failed: ' + build_error(f.read())


def wait_for_service(env, name, timeout):
    """Until the master at env's ROS_MASTER_URI lists `name` (the world server is up)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        done = subprocess.run(['rosservice', 'list'], env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              text=True, timeout=30)
        if name in done.stdout.split():
            return True
        time.sleep(2.0)
    return False


def wait_for_master(port, first, timeout):
    """True once the master's port answers; False when the first command exited before (roslaunch refused
    its launch file: no master will come) or after `timeout` s. rospy.init_node would wait forever."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            with socket.create_connection(('localhost', port), timeout=2.0):
                return True
        except OSError:
            if first.poll() is not None:
                return False
            time.sleep(1.0)
    return False


def stop(procs):
    """SIGINT to each started process group (roslaunch shuts its nodes down), then TERM, then KILL."""
    for sig, grace in ((signal.SIGINT, 30.0), (signal.SIGTERM, 10.0), (signal.SIGKILL, 5.0)):
        alive = [p for p in procs if p.poll() is None]
        if not alive:
            return
        for p in alive:
            try:
                os.killpg(p.pid, sig)
            except ProcessLookupError:
                pass
        deadline = time.time() + grace
        while time.time() < deadline and any(p.poll() is None for p in alive):
            time.sleep(0.5)


def checkout_row(row, logs, env_base, result):
    """Every repository of the row at its commit: {repo: tree}, or None (the result says why) when one fails."""
    trees = {}
    for repo in row['repos']:
        git_log = []
        try:
            tree, note = sources.checkout(repo['repo'], repo['commit'], env_base, git_log, repo['packages'])
        except sources.SourceError as err:
            result.update(status='not run', reason='source: %s' % err)
            return None
        finally:
            with open(os.path.join(logs, 'git.log'), 'a') as f:
                f.write('\n'.join(git_log))
        trees[repo['repo']] = tree
        result['repos'].append({'repo': repo['repo'], 'commit': repo['commit'], 'branch': repo['branch'],
                                'packages': repo['packages'], 'note': note})
    return trees


def with_deps(ws, env_base, log_path, result):
    """`make deps` for the row's workspace (a row with `deps: true`: what its packages need that neither Debian
    nor racebot provides, built from source in the deps underlay, docs/DEPS.md), as its users run it before their
    build; the environment with the underlay sourced. What it could not provide goes in the row's notes."""
    print('  make deps %s' % ws, flush=True)
    with open(log_path, 'w') as log:
        code = subprocess.call([python(), os.path.join(ROOT, 'tools', 'deps', 'run.py'), os.path.join(ws, 'src')],
                               env=env_base, stdout=log, stderr=subprocess.STDOUT, timeout=BUILD_TIMEOUT_S * 4)
    with open(log_path, errors='replace') as f:
        text = f.read().splitlines()
    lines = [line.strip() for line in text if line.strip().split(' ', 1)[0] in ('failed', 'skipped', 'unknown')]
    if code != 0:
        result['notes'].append('make deps: %d not provided (%s)' % (len(lines), '; '.join(lines[:4])[:400]))
    setup = underlay_of(text)
    return shell_env(setup, env_base) if setup and os.path.exists(setup) else env_base


def underlay_of(report_lines):
    """The setup.bash make deps's report names last ('racebot deps: underlay: source PATH'), or None."""
    return next((line.split(UNDERLAY_LINE, 1)[1].strip() for line in reversed(report_lines) if UNDERLAY_LINE in line),
                None)


def row_env(row, ws, env_base, logs, result):
    """(environment, master port) the row's commands run in: its devel space's, or its sources' after a failed
    build, with the row's own variables, a private master and no display."""
    if result['build'] == 'ok':
        env = shell_env(os.path.join(ws, 'devel', 'setup.bash'), env_base)
    else:  # run from the sources anyway: the worklist wants what fails after the build too
        env = dict(env_base)
        env['ROS_PACKAGE_PATH'] = os.path.join(ws, 'src') + ':' + env_base.get('ROS_PACKAGE_PATH', '')
        result['notes'].append('the build failed; ran with the sources on ROS_PACKAGE_PATH (no devel space)')
    port = free_port()
    env.update({k: str(v) for k, v in (row.get('env') or {}).items()})
    env.update(ROS_MASTER_URI='http://localhost:%d' % port, ROS_HOSTNAME='localhost',
               ROS_LOG_DIR=os.path.join(logs, 'ros'), ROS_HOME=os.path.join(logs, 'ros_home'))
    for name in ('DISPLAY', 'ROS_IP', 'ROS_IPV6', 'WAYLAND_DISPLAY'):
        env.pop(name, None)
    return env, port


def write_files(row, folder):
    """The row's own files (`files`: name -> text; a user's small launch file, say) into the folder its commands
    run in, as a user keeps them in the folder they type the command in; their paths."""
    paths = []
    for name, text in sorted((row.get('files') or {}).items()):
        path = os.path.join(folder, name)
        with open(path, 'w') as f:
            f.write(text)
        paths.append(path)
    return paths


def start_commands(row, env, logs, procs, result):
    """The row's commands, each once the world server offers its services, in the row's folder (`logs`, holding
    its files); their log paths."""
    write_files(row, logs)
    launch_logs = []
    for i, command in enumerate(row['commands']):
        if i and not wait_for_service(env, '/gazebo/get_world_properties', float(row.get('ready_timeout', 120))):
            result['notes'].append('the world server never offered /gazebo/get_world_properties; '
                                   'started `%s` anyway' % command)
        path = os.path.join(logs, 'command-%d.log' % (i + 1))
        launch_logs.append(path)
        with open(path, 'w') as log:
            log.write('$ %s\n' % command)
            log.flush()
            procs.append(subprocess.Popen(['bash', '-c', command], env=env, stdout=log, stderr=subprocess.STDOUT,
                                          stdin=subprocess.DEVNULL, cwd=logs, start_new_session=True))
        time.sleep(float(row.get('command_gap', 3.0)))
    return launch_logs


def run_checks(row, env, port, master_up, logs, result):
    """The row's checks in a child process (CHECKS) against the running commands, into result['checks']."""
    row_file = os.path.join(logs, 'row.json')
    with open(row_file, 'w') as f:
        json.dump(dict(row, logs_dir=logs), f, indent=2)  # plugin_output reads the commands' logs there
    result_file = os.path.join(logs, 'checks.json')
    if os.path.exists(result_file):
        os.unlink(result_file)
    with open(os.path.join(logs, 'checks.log'), 'w') as log:
        if not master_up:
            log.write('no ROS master came up on port %d: checks not run\n' % port)
        else:
            try:
                subprocess.call([python(), CHECKS, row_file, result_file], env=env, stdout=log,
                                stderr=subprocess.STDOUT, timeout=CHECKS_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                result['notes'].append('the checks took over %d s and were stopped' % CHECKS_TIMEOUT_S)
    try:
        with open(result_file) as f:
            result['checks'] = json.load(f)
    except (OSError, ValueError):
        why = 'no ROS master came up' if not master_up else 'the checker wrote no result (see checks.log)'
        result['checks'] = [{'kind': c['kind'], 'ok': False, 'numbers': '', 'reason': why} for c in row['checks']]


def conclude_row(row, result, launch_logs, exited):
    """The launch logs' notes, the row's status and, when it did not pass, the reason that explains it best."""
    notes = {'died': [], 'missing': [], 'errors': [], 'fatal': []}
    for path in launch_logs:
        with open(path, errors='replace') as f:
            for key, values in launch_notes(f.read()).items():
                notes[key] += values
    if notes['errors']:
        result['notes'].append('roslaunch: ' + ' | '.join(notes['errors']))
    if notes['fatal']:
        result['notes'].append('FATAL: ' + ' | '.join(notes['fatal']))
    if notes['died']:
        result['notes'].append('died: ' + ', '.join(notes['died']))
    if notes['missing']:
        result['notes'].append('could not start: ' + ', '.join(notes['missing']))
    first_launch_exit = next((code for cmd, code in exited if cmd == row['commands'][0]), None)
    result['status'] = table.status(result)
    if result['status'] != 'pass':
        reason = table.first_reason(result)
        if first_launch_exit is not None and notes['errors']:
            reason = '`%s` exited %s: %s' % (row['commands'][0], first_launch_exit, notes['errors'][0])
        elif ': not ready: ' in reason and notes['fatal']:  # the world never came up: say why, not what waited
            reason = 'not ready: FATAL %s' % notes['fatal'][0]
        hints = ['died: ' + ', '.join(notes['died'])] if notes['died'] else []
        result['reason'] = reason + (' [%s]' % '; '.join(hints) if hints else '')


def run_row(row, out, env_base):
    """One row: sources, build, commands, checks, stop. Returns its result for the table."""
    start = time.time()
    logs = os.path.join(out, 'logs', row['name'])
    os.makedirs(logs, exist_ok=True)
    result = {'name': row['name'], 'covers': row['covers'], 'commands': row['commands'], 'env': row.get('env') or {},
              'blacklist': row.get('blacklist') or {}, 'files': sorted(row.get('files') or {}),
              'user_packages': sorted(row.get('user_packages') or {}), 'repos': [],
              'checks': [], 'notes': [], 'build': 'not run'}
    trees = checkout_row(row, logs, env_base, result)
    if trees is None:
        return result
    ws = os.path.join(sources.cache_dir(env_base), 'ws', row['name'])
    make_workspace(row, trees, ws)
    if row.get('deps'):
        env_base = with_deps(ws, env_base, os.path.join(logs, 'deps.log'), result)
    print('  building %s' % ws, flush=True)
    result['build'] = build(row, ws, env_base, os.path.join(logs, 'build.log'))
    env, port = row_env(row, ws, env_base, logs, result)
    procs, launch_logs = [], []
    try:
        launch_logs = start_commands(row, env, logs, procs, result)
        master_up = wait_for_master(port, procs[0], float(row.get('ready_timeout', 120)))
        run_checks(row, env, port, master_up, logs, result)
        exited = [(row['commands'][i], p.returncode) for i, p in enumerate(procs) if p.poll() is not None]
    finally:
        stop(procs)
    conclude_row(row, result, launch_logs, exited)
    result['seconds'] = round(time.time() - start)
    return result


def racebot_commit():
    head = subprocess.run(['git', 'rev-parse', 'HEAD'], cwd=ROOT, stdout=subprocess.PIPE,
                          text=True).stdout.strip()
    dirty = subprocess.run(['git', 'status', '--porcelain', '--untracked-files=no'], cwd=ROOT,
                           stdout=subprocess.PIPE, text=True).stdout.strip()
    return head + (' (with uncommitted changes)' if dirty else '')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--only', help='comma-separated row names')
    parser.add_argument('--out', default=os.path.join(ROOT, 'out', 'corpus'))
    parser.add_argument('--list', action='store_true', help='print the rows and their sources, run nothing')
    args = parser.parse_args()
    rows = manifest.load()
    errors = manifest.validate(rows)
    if errors:
        sys.exit('racebot corpus: the manifest is invalid:\n  ' + '\n  '.join(errors))
    if args.only:
        wanted = args.only.split(',')
        unknown = [w for w in wanted if w not in {r['name'] for r in rows}]
        if unknown:
            sys.exit('racebot corpus: no row named %s' % ', '.join(unknown))
        rows = [r for r in rows if r['name'] in wanted]
    if args.list:
        for row in rows:
            print('%s: %s' % (row['name'], ' ; '.join(row['commands'])))
            for repo in row['repos']:
                print('    %s@%s %s <- %s' % (repo['repo'], repo['commit'][:12], ','.join(repo['packages']),
                                             sources.resolve(repo['repo'])[1]))
        return
    if 'ROS_PACKAGE_PATH' not in os.environ or ROOT not in os.environ['ROS_PACKAGE_PATH']:
        sys.exit('racebot corpus: source devel/setup.bash first (or use `make corpus`)')
    os.makedirs(args.out, exist_ok=True)
    env_base = dict(os.environ)
    started = datetime.datetime.now(datetime.timezone.utc)
    results = []
    for i, row in enumerate(rows):
        print('== [%d/%d] %s: %s' % (i + 1, len(rows), row['name'], ' ; '.join(row['commands'])), flush=True)
        try:
            result = run_row(row, args.out, env_base)
        except Exception as err:  # one row's crash must not take the table with it
            traceback.print_exc()
            result = {'name': row['name'], 'covers': row['covers'], 'commands': row['commands'], 'repos': [],
                      'checks': [], 'build': 'not run', 'status': 'not run', 'reason': 'runner: %r' % err}
        results.append(result)
        print('   %s  %s' % (result['status'], result.get('reason', '')), flush=True)
    meta = {'date': started.strftime('%Y-%m-%d %H:%M UTC'), 'racebot_commit': racebot_commit(),
            'source': 'RACEBOT_CORPUS_DIR' if os.environ.get('RACEBOT_CORPUS_DIR') else
            'RACEBOT_CORPUS_MIRRORS' if os.environ.get('RACEBOT_CORPUS_MIRRORS') else 'clones from the network',
            'minutes': round((time.time() - started.timestamp()) / 60.0, 1)}
    header = ['# racebot corpus: public ROS 1 packages run unchanged',
              '', 'Run %s on racebot %s (%s, %.0f min); `make corpus`.' % (
                  meta['date'], meta['racebot_commit'], meta['source'], meta['minutes'])]
    with open(os.path.join(args.out, 'corpus.md'), 'w') as f:
        f.write(table.markdown(results, header))
    with open(os.path.join(args.out, 'corpus.json'), 'w') as f:
        f.write(table.to_json(results, meta))
    print('\n' + table.console(results))
    print('written: %s, corpus.json (logs in %s)' % (os.path.join(args.out, 'corpus.md'),
                                                   os.path.join(args.out, 'logs')))
    sys.exit(0 if all(r['status'] == 'pass' for r in results) else 1)


if __name__ == '__main__':
    main()
