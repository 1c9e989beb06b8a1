"""The corpus manifest (tools/corpus/manifest.yaml): loading and validation. Pure: no ROS, no git.

A row is one public robot or world package as its users run it: the repositories it needs (each pinned
to a commit, with the package folders it takes from each), the packages left out of the build and why,
the environment and commands its README gives, and checks whose numbers come from the robot's own
files (each check says where in `from`).
"""
import os
import re

import yaml

from corpus import navigation

HERE = os.path.dirname(os.path.abspath(__file__))
MANIFEST = os.path.join(HERE, 'manifest.yaml')
COMMIT = re.compile(r'^[0-9a-f]{40}$')
REPO = re.compile(r'^[A-Za-z0-9][A-Za-z0-9_.-]*/[A-Za-z0-9][A-Za-z0-9_.-]*$')
NAME = re.compile(r'^[a-z0-9_]+$')

# check kind -> the keys it needs; every kind also needs `from` (where its numbers come from)
CHECK_KEYS = {
    'controllers': ('manager', 'running'),
    'drive': ('cmd_topic', 'seconds', 'expect_speed', 'tolerance'),
    'joint_position': ('command_topic', 'joint_states', 'joint', 'target', 'tolerance'),
    'trajectory': ('action', 'joint_states', 'target', 'duration', 'tolerance'),
    'gripper': ('action', 'joint_states', 'joint', 'position', 'tolerance'),
    'sensors': ('description', 'count'),
    'world': ('world', 'min_models'),
    'floor': ('world', 'tolerance'),
    'map': ('world', 'cmd_topic', 'route', 'map_topic', 'base_frame', 'height', 'tolerance', 'on_walls', 'explored'),
    'navigation': navigation.KEYS,
    'plugin_output': ('text', 'count'),
    'flight': ('cmd_topic', 'climb', 'climb_seconds', 'hold_seconds', 'hold_drift', 'command_timeout',
               'estop_seconds', 'estop_deceleration', 'tolerance'),
    'topics_agree': ('topics', 'type', 'messages', 'tolerance'),
}
# the numbers a kind is judged by: at least one must be in a row
NUMERIC = {'drive': ('expect_speed', 'tolerance'), 'joint_position': ('target', 'tolerance'),
           'trajectory': ('tolerance',), 'gripper': ('position', 'tolerance'), 'sensors': ('count',),
           'controllers': (), 'world': ('min_models',), 'floor': ('tolerance',),
           'map': ('on_walls', 'explored'), 'navigation': ('localisation_tolerance', 'xy_goal_tolerance'),
           'plugin_output': ('count',), 'flight': ('climb', 'tolerance'), 'topics_agree': ('messages', 'tolerance')}
FILE_NAME = re.compile(r'^[A-Za-z0-9_][A-Za-z0-9_.-]*$')


def load(path=MANIFEST):
    with open(path) as f:
        data = yaml.safe_load(f)
    return data['rows'] if isinstance(data, dict) else data


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def validate(rows):
    """Every problem of the manifest, one line each (empty: valid)."""
    errors = []
    if not isinstance(rows, list) or not rows:
        return ['the manifest has no rows']
    seen = set()
    for i, row in enumerate(rows):
        where = 'row %d (%s)' % (i + 1, row.get('name', '?') if isinstance(row, dict) else '?')
        if not isinstance(row, dict):
            errors.append('%s: not a mapping' % where)
            continue
        name = row.get('name')
        if not isinstance(name, str) or not NAME.match(name):
            errors.append('%s: name must be lower_case_with_underscores' % where)
        elif name in seen:
            errors.append('%s: name used twice' % where)
        seen.add(name)
        for key in ('covers', 'repos', 'commands', 'checks'):
            if not row.get(key):
                errors.append('%s: no %s' % (where, key))
        for repo in row.get('repos') or []:
            errors += ['%s: %s' % (where, e) for e in _repo_errors(repo)]
        commands = row.get('commands') or []
        if not isinstance(commands, list) or not all(isinstance(c, str) and c.strip() for c in commands):
            errors.append('%s: commands must be a list of command lines' % where)
        files = row.get('files') or {}
        if not isinstance(files, dict):
            errors.append('%s: files must map a file name to its text' % where)
            files = {}
        for file_name, text in files.items():
            if not isinstance(file_name, str) or not FILE_NAME.match(file_name):
                errors.append('%s: file name %r is not a plain name in the row\'s folder' % (where, file_name))
            if not isinstance(text, str) or not text.strip():
                errors.append('%s: file %s has no text' % (where, file_name))
        errors += ['%s: %s' % (where, e) for e in _user_package_errors(row.get('user_packages') or {})]
        for package, why in (row.get('blacklist') or {}).items():
            if not why:
                errors.append('%s: blacklisted %s without a reason' % (where, package))
        numeric = 0
        for check in row.get('checks') or []:
            problems, has_number = _check_errors(check)
            errors += ['%s: %s' % (where, e) for e in problems]
            numeric += has_number
        if row.get('checks') and not numeric:
            errors.append('%s: no check with a number' % where)
    return errors


def _user_package_errors(packages):
    """The row's own catkin packages (`user_packages`: package name -> {path in it: text}), as a user keeps one in
    the workspace beside the packages they took."""
    if not isinstance(packages, dict):
        return ['user_packages must map a package name to its files']
    errors = []
    for package, files in packages.items():
        if not isinstance(package, str) or not NAME.match(package):
            errors.append('user package %r: its name must be lower_case_with_underscores' % (package,))
        if not isinstance(files, dict) or 'package.xml' not in files or 'CMakeLists.txt' not in files:
            errors.append('user package %s: needs at least package.xml and CMakeLists.txt' % package)
            continue
        for path, text in files.items():
            parts = str(path).split('/')
            if not all(FILE_NAME.match(part) for part in parts):
                errors.append('user package %s: %r is not a path inside the package' % (package, path))
            if not isinstance(text, str) or not text.strip():
                errors.append('user package %s: %s has no text' % (package, path))
    return errors


def _repo_errors(repo):
    if not isinstance(repo, dict):
        return ['a repos entry is not a mapping']
    errors = []
    if not isinstance(repo.get('repo'), str) or not REPO.match(repo['repo']):
        errors.append('repo %r is not owner/name' % repo.get('repo'))
    if not isinstance(repo.get('commit'), str) or not COMMIT.match(repo['commit']):
        errors.append('%s: commit %r is not 40 hex digits' % (repo.get('repo'), repo.get('commit')))
    if not repo.get('branch'):
        errors.append('%s: no branch (the one its users build)' % repo.get('repo'))
    packages = repo.get('packages')
    if not isinstance(packages, list) or not packages:
        errors.append('%s: no packages (the folders the row builds, "." for the root)' % repo.get('repo'))
    return errors


def _check_errors(check):
    """(problems, 1 if the check carries a number it is judged by)."""
    if not isinstance(check, dict) or check.get('kind') not in CHECK_KEYS:
        return ['check %r has no known kind (%s)' % (check, ', '.join(sorted(CHECK_KEYS)))], 0
    kind = check['kind']
    problems = ['%s check without %s' % (kind, key) for key in CHECK_KEYS[kind] + ('from',) if key not in check]
    if kind == 'navigation':  # its fields' shapes: the check refuses the same
        problems += [p for p in navigation.input_problems(check) if ' without ' not in p]
    numbers = [check.get(key) for key in NUMERIC.get(kind, ())]
    if kind == 'trajectory' and isinstance(check.get('target'), dict):
        numbers += list(check['target'].values())
    if kind == 'controllers':
        numbers = [len(check.get('running') or [])]
    for key in ('tolerance', 'seconds', 'duration'):
        if key in check and not (_is_number(check[key]) and check[key] > 0):
            problems.append('%s check: %s must be a positive number' % (kind, key))
    if 'settle_s' in check and not (_is_number(check['settle_s']) and check['settle_s'] >= 0):
        problems.append('%s check: settle_s must be a number of sim seconds, 0 or more' % kind)
    has_number = any(_is_number(n) for n in numbers)
    if not has_number:
        problems.append('%s check: no number to judge by (%s)' % (kind, ', '.join(NUMERIC[kind]) or 'running'))
    return problems, int(has_number)


def repo_entries(rows):
    """{owner/name: {commit, ...}} over all rows: what `make corpus` must have at hand."""
    out = {}
    for row in rows:
        for repo in row['repos']:
            out.setdefault(repo['repo'], set()).add(repo['commit'])
    return out
