#!/usr/bin/env python3
"""make deps: the ROS 1 packages a workspace or package needs that neither Debian nor racebot provides, fetched at
their Noetic release and built in an underlay on top of racebot (docs/DEPS.md).

    tools/deps/run.py [options] TARGET [TARGET ...]        (racebot's devel/setup.bash sourced)
    make deps ARGS='~/my_ws/src amcl'

A TARGET is a folder (a workspace, its src/, or one package: every package.xml at or below it, with its launch
files) or a package name. Then, with the ecosystem's tools: rosdep (Debian's rules and the rosdistro's) says what
Debian provides, rospack what racebot and the installed packages provide; rosinstall_generator names the rest's
repositories at their Noetic release, vcstool checks them out into the underlay (CACHE/ws/src), `rosdep install`
installs their Debian dependencies, `catkin_make_isolated --merge` builds them. Then
`source CACHE/ws/devel_isolated/setup.bash` (it sources racebot's devel space too) before building or launching
the target. CACHE is ~/.cache/racebot/deps (--cache, RACEBOT_DEPS_CACHE). Exit status 0 when every needed name is
provided or built.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from deps import index, needs, provide, repos, resolve, underlay  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def parse_args(argv):
    parser = argparse.ArgumentParser(prog='make deps', description=__doc__.split('\n\n')[0])
    parser.add_argument('targets', nargs='+', metavar='TARGET', help='a workspace or package folder, or a package name')
    parser.add_argument('--cache', default=os.environ.get('RACEBOT_DEPS_CACHE') or
                        os.path.expanduser(os.path.join('~', '.cache', 'racebot', 'deps')))
    parser.add_argument('--clones', default=os.environ.get('RACEBOT_CORPUS_DIR'),
                        help='a folder of existing clones: DIR/<name>, DIR/<owner>/<name> or DIR/<owner>+<name>')
    parser.add_argument('--mirrors', default=os.environ.get('RACEBOT_CORPUS_MIRRORS'),
                        help='a folder of mirrors: ROOT/<owner>+<name>/repo (as make corpus takes them)')
    parser.add_argument('--rosdistro', default=os.environ.get('RACEBOT_DEPS_ROSDISTRO'),
                        help='a ros/rosdistro checkout or git directory (default: MIRRORS/ros+rosdistro/repo)')
    parser.add_argument('--no-install', action='store_true', help='list missing Debian packages, do not install')
    parser.add_argument('--rebuild', action='store_true', help='resolve and build again even if nothing changed')
    parser.add_argument('--jobs', type=int, default=2)
    return parser.parse_args(argv)


def below(env):
    """The workspaces the underlay extends, as a fingerprint: each CMAKE_PREFIX_PATH entry and its packages."""
    found = []
    for prefix in filter(None, env.get('CMAKE_PREFIX_PATH', '').split(':')):
        share = os.path.join(prefix, 'share')
        found.append([prefix, sorted(os.listdir(share)) if os.path.isdir(share) else []])
    return found


def resolution_key(local, names, env):
    """What the walk depends on: the targets' package.xml and launch files, the names asked for, the index, the
    workspaces below and the stand-ins that give way."""
    digest = hashlib.sha1()
    for name, (folder, _) in sorted(local.items()):
        for rel in ['package.xml'] + needs.launch_files(folder):
            digest.update(('%s/%s\0' % (name, rel)).encode())
            with open(os.path.join(folder, rel), 'rb') as f:
                digest.update(f.read())
    digest.update(json.dumps([sorted(names), env.get('ROSDISTRO_INDEX_URL'), below(env),
                              needs.GIVE_WAY]).encode())
    return digest.hexdigest()


def cached_resolution(record, key, ws):
    """The recorded resolution for `key` when its checkouts are still at their versions, else None."""
    data = (record.get('resolutions') or {}).get(key)
    if not data:
        return None
    for name, entry in data['repos'].items():
        if name in data['selected'].values() and not repos.at_version(os.path.join(ws.src, name),
                                                                      str(entry['version'])):
            return None
    result = resolve.Resolution()
    result.providers = {name: provide.Provider(p['kind'], p['where'], p['packages'], p['missing'])
                        for name, p in data['providers'].items()}
    result.selected, result.repos, result.unknown = data['selected'], data['repos'], data['unknown']
    result.needed_by = data['needed_by']
    return result


def install_system(result, local, src_packages, env, install, say):
    """`rosdep install` over the targets and the packages taken from source, when rosdep named Debian packages
    that are not installed (or, with install False, the command to run)."""
    missing = sorted({pkg for p in result.providers.values() if p.kind == 'debian' for pkg in p.missing})
    if not missing:
        return
    paths = [folder for folder, _ in local.values()] + \
        [src_packages[n][0] for n in result.selected if n in src_packages]
    cmd = ['rosdep', 'install', '--from-paths'] + sorted(set(paths)) + \
        ['--ignore-src', '-y', '-r', '--os=%s:%s' % provide.DEBIAN]
    if os.geteuid() == 0:
        cmd += ['--as-root', 'apt:false']
    if not install:
        say('racebot deps: Debian packages to install: %s (rosdep install, or apt-get install -y %s)'
            % (' '.join(missing), ' '.join(missing)))
        return
    say('racebot deps: rosdep install of %s' % ' '.join(missing))
    done = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        last = [line for line in done.stdout.splitlines() if line.strip()][-1:] or ['exit %d' % done.returncode]
        say('racebot deps: rosdep install failed: %s' % last[0].strip())


def setup_index(args, env):
    """env for rosinstall_generator and rosdep, with the offline index when a rosdistro copy is at hand."""
    source = None if env.get('ROSDISTRO_INDEX_URL') else index.find_rosdistro(args.rosdistro, args.mirrors)
    folder = index.materialise(source, args.cache) if source else None
    return index.rosdep_env(args.cache, folder, env)


def report(result, results, ws, local, say):
    """The summary, one line per package taken from source and per name nobody provides; True when all is well."""
    kinds = {kind: 0 for kind in ('racebot', 'installed', 'debian', 'source')}
    for provider in result.providers.values():
        kinds[provider.kind] += 1
    say('racebot deps: %d target package(s); %d needed name(s): %d racebot, %d installed, %d Debian via rosdep, '
        '%d from source' % ((len(local), len(result.providers)) + tuple(kinds.values())))
    used = sorted(set(result.selected.values()))
    if used:
        say('racebot deps: from source: %s' % ', '.join('%s %s' % (r, result.repos.get(r, {}).get('version', '?'))
                                                       for r in used))
    ok = True
    for name in sorted(result.selected):
        status = results.get(name, 'not built')
        ok = ok and status == 'built'
        say('  %-8s %s (%s)%s' % (status.split(':')[0], name, result.selected[name],
                                  ': ' + status.split(': ', 1)[1] if ': ' in status else ''))
    for name, why in sorted(result.unknown.items()):
        ok = False
        say('  %-8s %s (needed by %s): %s' % ('unknown', name, ', '.join(result.needed_by.get(name, [])), why))
    say('racebot deps: underlay: source %s' % ws.setup)
    return ok


def _resolve(args, ws, env, local, names, record, say):
    key = resolution_key(local, names, env)
    result = None if args.rebuild else cached_resolution(record, key, ws)
    if result is not None:
        src_packages = resolve.src_packages_of(ws)
        return result, src_packages, True
    providers = provide.Providers(ROOT, env['ROS_HOME'], needs.GIVE_WAY)
    ctx = {'env': env, 'ws': ws, 'clones': args.clones, 'mirrors': args.mirrors, 'say': say}
    result, src_packages = resolve.walk(local, names, providers, ctx)
    for repo in set(result.selected.values()) - set(result.repos):  # taken from src/, checked out by an earlier run
        if repo in record.get('repos', {}):
            result.repos[repo] = record['repos'][repo]
    install_system(result, local, src_packages, env, not args.no_install, say)
    if not any(why.startswith(repos.CHECKOUT_FAILED) for why in result.unknown.values()):
        record.setdefault('resolutions', {})[key] = result.to_json()  # a failed checkout is tried again next time
    return result, src_packages, False


def main(argv=None, say=print):
    args = parse_args(argv)
    started = time.time()
    args.cache = os.path.abspath(os.path.expanduser(args.cache))
    ws = underlay.Workspace(os.path.join(args.cache, 'ws'))
    try:
        env = setup_index(args, os.environ)
    except index.RosdistroError as error:
        say('racebot deps: %s' % error)
        return 2
    local, names = resolve.targets(args.targets)
    record = ws.record()
    result, src_packages, was_cached = _resolve(args, ws, env, local, names, record, say)
    record.setdefault('repos', {}).update({r: e for r, e in result.repos.items() if r in result.selected.values()})
    packages = sorted((set(record.get('packages', [])) | set(result.selected)) & set(src_packages))
    key = underlay.build_key({r: e for r, e in record['repos'].items()}, packages, below(env))
    built = record.get('build') or {}
    if packages and (args.rebuild or built.get('key') != key or not os.path.isfile(ws.setup)):
        results = underlay.build(ws, packages, src_packages, env, args.jobs, say)
        built = {'key': key, 'results': results}
        was_cached = False
    record.update(packages=packages, build=built)
    ws.save(record)
    ok = report(result, built.get('results', {}), ws, local, say)
    say('racebot deps: %s in %.1f s' % ('cached, nothing to do' if was_cached else 'done', time.time() - started))
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
