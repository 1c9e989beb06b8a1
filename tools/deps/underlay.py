"""The underlay: a catkin workspace in the cache (CACHE/ws) holding the fetched repositories in src/, built with
`catkin_make_isolated --merge` on top of whatever workspace is sourced (racebot's devel space), so that its
devel_isolated/setup.bash gives racebot plus the underlay. A package that fails is left out and the build goes on
without it (and without what needs it); each gets one line saying why. What was built is recorded with its key
(the repositories and versions, the packages, the workspace below): the same key again builds nothing.
"""
import hashlib
import json
import os
import re
import subprocess
import time


FAILED = re.compile(r"<== Failed to process package '([^']+)'")
STARTED = re.compile(r"==> Processing (?:catkin|plain cmake) package: '([^']+)'")
NOT_FOUND = re.compile(r'Could not find a (?:package )?configuration file (?:provided by|for package) "([^"]+)"')
COMPILER = re.compile(r'(?:^|\s)(\S+?):(\d+):(?:\d+:)? ((?:fatal )?error: .*)')
REASONS = [re.compile(r'(CMake Error at [^:]+:\d+ \(\w+\):.*)'), re.compile(r'(Could NOT find .*)'),
           re.compile(r'(No module named .*)'), re.compile(r'((?:\w+ )?[Ee]rror: .*)')]
BUILD_TIMEOUT_S = 3600


class Workspace:
    """The underlay's folders under `root` and the record of its last build."""

    def __init__(self, root):
        self.root = root
        self.src = os.path.join(root, 'src')
        self.devel = os.path.join(root, 'devel_isolated')
        self.build_space = os.path.join(root, 'build_isolated')
        self.setup = os.path.join(self.devel, 'setup.bash')
        self.logs = os.path.join(root, 'logs')
        self.record_path = os.path.join(root, 'racebot-deps.json')

    def record(self):
        try:
            with open(self.record_path) as f:
                return json.load(f)
        except (OSError, ValueError):
            return {}

    def save(self, record):
        os.makedirs(self.root, exist_ok=True)
        with open(self.record_path + '.tmp', 'w') as f:
            json.dump(record, f, indent=1, sort_keys=True)
        os.replace(self.record_path + '.tmp', self.record_path)


def build_key(repos, packages, below):
    """What a build depends on: each repository's URL and version, the packages built, the workspace below."""
    text = json.dumps({'repos': {name: [entry.get('url'), str(entry.get('version'))] for name, entry in repos.items()},
                       'packages': sorted(packages), 'below': below}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()


ANSI = re.compile(r'\x1b\[[0-9;?]*[A-Za-z]|\x1b\][^\x07]*\x07')  # colours and window titles (catkin, gcc on a tty)


def _package_reason(block):
    """The reason a package configuration gave when it set <name>_FOUND to FALSE (CMake prints it after "Reason
    given by package:", up to a blank line): the one part of that error saying what to do."""
    for i, line in enumerate(block):
        if 'Reason given by package:' in line:
            reason = []
            for rest in block[i + 1:]:
                if not rest.strip() and reason:
                    break
                reason.append(rest.strip())
            return ' '.join(x for x in reason if x)
    return ''


def first_error(text, package_folder=None):
    """The first cause in a package's build output, one line."""
    lines = ANSI.sub('', text).splitlines()
    for line in lines:
        found = NOT_FOUND.search(line)
        if found:
            return 'find_package(%s) found nothing' % found.group(1)
    for line in lines:
        found = COMPILER.search(line)
        if found and not found.group(1).endswith(('.txt', '.cmake')):
            path = found.group(1)
            if package_folder and path.startswith(package_folder + os.sep):
                path = os.path.relpath(path, package_folder)
            return '%s:%s: %s' % (path, found.group(2), found.group(3).strip())
    for pattern in REASONS:
        for i, line in enumerate(lines):
            found = pattern.search(line)
            if found:
                detail = found.group(1).strip()
                if detail.startswith('CMake Error'):
                    detail += ' ' + (_package_reason(lines[i + 1:i + 12]) or
                                     ' '.join(x.strip() for x in lines[i + 1:i + 4] if x.strip()))
                return detail[:300]
    tail = [x.strip() for x in lines if x.strip()][-1:] or ['(no output)']
    return tail[0][:300]


def section(log_text, package):
    """The part of a catkin_make_isolated log that processed `package`."""
    start = None
    lines = ANSI.sub('', log_text).splitlines()
    for i, line in enumerate(lines):
        found = STARTED.search(line)
        if found and found.group(1) == package:
            start = i
    return '\n'.join(lines[start:] if start is not None else lines)


def build_needs(package):
    """What a package needs to build: its build and buildtool dependencies (`<depend>` is one too), not its exec
    ones, which catkin does not look for."""
    groups = [package.build_depends, package.buildtool_depends]
    return {dep.name for group in groups for dep in group if dep.evaluated_condition is not False}


def dependents(failed, packages):
    """The packages of `packages` ({name: (folder, Package)}) that need `failed` to build, directly or not (an exec
    dependency that failed leaves a package buildable: hector_sensors_description's hector_gazebo_thermal_camera,
    a compiled camera plugin, is needed only by the xacro macro of a thermal camera)."""
    found, todo = set(), [failed]
    while todo:
        name = todo.pop()
        for other, (_, package) in packages.items():
            if other not in found and name in build_needs(package):
                found.add(other)
                todo.append(other)
    return found


def python():
    """The interpreter node scripts get in their shebang: racebot's venv when there, else Debian's."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    venv = os.path.join(root, '.venv', 'bin', 'python3')
    return venv if os.path.exists(venv) else '/usr/bin/python3'


def cmi_command(ws, selection, others):
    """catkin_make_isolated of `selection` and what it needs of ws.src; `others` (the rest of ws.src's packages: a
    fetched repository's packages that racebot, Debian or another underlay provide) are ignored, or
    --only-pkg-with-deps would build the source copy of one that a selected package depends on over the provider
    the resolution chose (hector_gazebo's own hector_gazebo_plugins, which needs Gazebo's removed gazebo/math)."""
    cmd = ['catkin_make_isolated', '-C', ws.root, '--source', ws.src, '--build', ws.build_space,
           '--devel', ws.devel, '--merge', '--force-cmake', '--only-pkg-with-deps'] + sorted(selection)
    ignored = sorted(set(others) - set(selection))
    if ignored:
        cmd += ['--ignore-pkg'] + ignored
    return cmd + ['--cmake-args', '-DPYTHON_EXECUTABLE=%s' % python(), '-DCATKIN_ENABLE_TESTING=OFF',
                  '-DCMAKE_BUILD_TYPE=Release']


def _run_cmi(ws, selection, others, env, log_path, jobs):
    # configured from scratch: what the packages find below them has changed when they are built again (a build
    # folder's CMake cache keeps rosbag_storage_DIR at Debian's after racebot's overlay of it lands), and
    # --force-cmake, since with a Makefile there catkin_make_isolated would only re-check, without its arguments
    for name in selection:
        cache = os.path.join(ws.build_space, name, 'CMakeCache.txt')
        if os.path.exists(cache):
            os.remove(cache)
    cmd = cmi_command(ws, selection, others)
    env = dict(env, ROS_PARALLEL_JOBS='-j%d -l%d' % (jobs, jobs))
    with open(log_path, 'w') as log:
        log.write('$ %s\n' % ' '.join(cmd))
        log.flush()
        try:
            code = subprocess.call(cmd, env=env, stdout=log, stderr=subprocess.STDOUT, timeout=BUILD_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            code = 'timeout after %d s' % BUILD_TIMEOUT_S
    with open(log_path, errors='replace') as f:
        return code, f.read()


def build(ws, selection, packages, env, jobs=2, say=print):
    """Builds `selection` (package names in ws.src; `packages` is {name: (folder, Package)} of ws.src) and returns
    {name: 'built' | 'failed: why' | 'skipped: needs X, which failed to build'}."""
    os.makedirs(ws.logs, exist_ok=True)
    results, remaining, attempt = {}, set(selection), 0
    while remaining:
        attempt += 1
        log_path = os.path.join(ws.logs, 'build-%d.log' % attempt)
        started = time.time()
        say('racebot deps: catkin_make_isolated of %d package(s), log %s' % (len(remaining), log_path))
        code, text = _run_cmi(ws, remaining, packages, env, log_path, jobs)
        if code == 0:
            results.update({name: 'built' for name in remaining})
            say('racebot deps: built in %.0f s' % (time.time() - started))
            break
        failed = FAILED.findall(text)
        culprit = failed[-1] if failed and failed[-1] in remaining else None
        if culprit is None:
            why = first_error(text)
            results.update({name: 'failed: catkin_make_isolated: %s' % why for name in remaining})
            break
        folder = packages[culprit][0] if culprit in packages else None
        why = first_error(section(text, culprit), folder)
        if why.startswith('Command failed') and folder:  # the section's cause not found: its own files' first error
            own = [line for line in ANSI.sub('', text).splitlines() if folder + os.sep in line]
            why = first_error('\n'.join(own), folder) if own else why
        results[culprit] = 'failed: %s' % why
        say('racebot deps: %s %s' % (culprit, results[culprit]))
        remaining.discard(culprit)
        for other in dependents(culprit, {n: packages[n] for n in remaining if n in packages}):
            results[other] = 'skipped: needs %s, which failed to build' % culprit
            remaining.discard(other)
    return results
