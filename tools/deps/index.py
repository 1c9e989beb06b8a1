"""The rosdistro index and rosdep's rules, offline when a copy of ros/rosdistro is at hand.

Where the index comes from, first match wins:
  ROSDISTRO_INDEX_URL set          used as it is (rosdistro's own variable; a file:// URL works offline)
  --rosdistro PATH                 a checkout of ros/rosdistro, a folder laid out like one (index-v4.yaml,
                                   noetic/distribution.yaml, rosdep/*.yaml), or a git directory of it
  MIRRORS/ros+rosdistro/repo       the mirror root's copy (RACEBOT_CORPUS_MIRRORS, as make corpus takes it)
  otherwise                        rosdistro's default index on the network
A local copy is materialised in the cache (CACHE/rosdistro/<commit or content hash>/) with index-v4.yaml, noetic/
and rosdep/, and a noetic distribution cache written there by rosdistro's own DistributionCache (the published
cache is a download; rosinstall_generator refuses to work without one). That cache holds the distribution file but
no package.xml files, which is why make deps never asks rosinstall_generator for --deps: it walks dependencies
itself from the package.xml files of what it fetched (run.py).

rosdep reads its rules through a sources list in the cache (ROSDEP_SOURCE_PATH): Debian's own
/usr/share/python3-rosdep2/debian.yaml first (how Debian's python3-rosdep2 maps ROS package names to Debian's
ros-*, lib*-dev and python3-* packages), then the rosdistro copy's rosdep/base.yaml, python.yaml and ruby.yaml.
`rosdep update` runs (with ROS_HOME in the cache) only when that list changes.
"""
import hashlib
import io
import os
import shutil
import subprocess
import tarfile

import yaml

DISTRO = 'noetic'
DEBIAN_RULES = '/usr/share/python3-rosdep2/debian.yaml'
ROSDEP_FILES = ('base.yaml', 'python.yaml', 'ruby.yaml')


class RosdistroError(RuntimeError):
    """The rosdistro copy cannot be read or rosdep cannot load it; the message says why."""


def find_rosdistro(option, mirrors):
    """The ros/rosdistro copy to use (a folder or a git directory), or None for the network."""
    if option:
        return option
    if mirrors:
        for path in (os.path.join(mirrors, 'ros+rosdistro', 'repo'), os.path.join(mirrors, 'ros', 'rosdistro')):
            if os.path.isdir(path):
                return path
    return None


def _git_dir(path):
    for candidate in (path, os.path.join(path, '.git')):
        if os.path.isfile(os.path.join(candidate, 'HEAD')) and os.path.isdir(os.path.join(candidate, 'objects')):
            return candidate
    return None


def _is_checkout(path):
    return os.path.isfile(os.path.join(path, 'index-v4.yaml'))


def _content_hash(path):
    digest = hashlib.sha1()
    for rel in ['index-v4.yaml', os.path.join(DISTRO, 'distribution.yaml')] + \
            [os.path.join('rosdep', name) for name in ROSDEP_FILES]:
        full = os.path.join(path, rel)
        if os.path.isfile(full):
            digest.update(rel.encode() + b'\0')
            with open(full, 'rb') as f:
                digest.update(f.read())
    return digest.hexdigest()[:12]


def _export_git(git_dir, target):
    """index-v4.yaml, noetic/ and rosdep/ of the git directory's HEAD into `target`; the commit's id."""
    commit = subprocess.run(['git', '--git-dir', git_dir, 'rev-parse', 'HEAD'], stdout=subprocess.PIPE, text=True,
                            check=True).stdout.strip()
    archive = subprocess.run(['git', '--git-dir', git_dir, 'archive', commit, 'index-v4.yaml', DISTRO, 'rosdep'],
                             capture_output=True)
    if archive.returncode != 0:
        raise RosdistroError('git archive of %s failed: %s' % (git_dir, archive.stderr.decode().strip()))
    with tarfile.open(fileobj=io.BytesIO(archive.stdout)) as tar:
        tar.extractall(target)
    return commit


def write_distribution_cache(folder):
    """folder/noetic-cache.yaml from noetic/distribution.yaml (rosdistro's DistributionCache, no package.xml
    files), and the index's noetic entry pointed at it. Index entries of other distributions are left out:
    their files are not copied."""
    from rosdistro.distribution_cache import DistributionCache
    with open(os.path.join(folder, 'index-v4.yaml')) as f:
        index = yaml.safe_load(f)
    entry = dict(index['distributions'][DISTRO])
    data = []
    for rel in entry['distribution'] if isinstance(entry['distribution'], list) else [entry['distribution']]:
        with open(os.path.join(folder, rel)) as f:
            data.append(yaml.safe_load(f))
    cache = DistributionCache(DISTRO, distribution_file_data=data if len(data) > 1 else data[0])
    with open(os.path.join(folder, '%s-cache.yaml' % DISTRO), 'w') as f:
        yaml.safe_dump(cache.get_data(), f)
    entry['distribution_cache'] = '%s-cache.yaml' % DISTRO
    index['distributions'] = {DISTRO: entry}
    with open(os.path.join(folder, 'index-v4.yaml'), 'w') as f:
        yaml.safe_dump(index, f)


def materialise(source, cache):
    """The folder in the cache holding the index copy of `source` (made on first use); RosdistroError when
    `source` is neither a checkout nor a git directory of ros/rosdistro."""
    git_dir = None if _is_checkout(source) else _git_dir(source)
    if git_dir:
        key = subprocess.run(['git', '--git-dir', git_dir, 'rev-parse', 'HEAD'], stdout=subprocess.PIPE,
                             text=True).stdout.strip()[:12]
    elif _is_checkout(source):
        key = _content_hash(source)
    else:
        raise RosdistroError('%s is neither a rosdistro checkout (index-v4.yaml) nor a git directory of one' % source)
    target = os.path.join(cache, 'rosdistro', key)
    if os.path.isfile(os.path.join(target, '%s-cache.yaml' % DISTRO)):
        return target
    partial = target + '.partial'
    shutil.rmtree(partial, ignore_errors=True)
    os.makedirs(partial)
    if git_dir:
        _export_git(git_dir, partial)
    else:
        for rel in ('index-v4.yaml', DISTRO, 'rosdep'):
            full = os.path.join(source, rel)
            if os.path.isdir(full):
                shutil.copytree(full, os.path.join(partial, rel))
            elif os.path.isfile(full):
                shutil.copy(full, os.path.join(partial, rel))
    try:
        write_distribution_cache(partial)
    except (OSError, KeyError, TypeError, yaml.YAMLError) as error:
        raise RosdistroError('cannot read the rosdistro copy %s: %s' % (source, str(error).splitlines()[0]))
    shutil.rmtree(target, ignore_errors=True)
    os.rename(partial, target)
    return target


def sources_list(rosdistro_folder):
    """The text of rosdep's sources list: Debian's rules first, then the rosdistro copy's (or the network's)."""
    lines = ['# written by racebot make deps (tools/deps/index.py)']
    if os.path.isfile(DEBIAN_RULES):
        lines.append('yaml file://%s debian' % DEBIAN_RULES)
    base = 'file://%s/rosdep' % rosdistro_folder if rosdistro_folder else \
        'https://raw.githubusercontent.com/ros/rosdistro/master/rosdep'
    for name in ROSDEP_FILES:
        if not rosdistro_folder or os.path.isfile(os.path.join(rosdistro_folder, 'rosdep', name)):
            lines.append('yaml %s/%s' % (base, name))
    return '\n'.join(lines) + '\n'


def rosdep_env(cache, rosdistro_folder, env):
    """`env` with ROSDISTRO_INDEX_URL, ROSDEP_SOURCE_PATH and ROS_HOME set for rosinstall_generator and rosdep;
    the sources list is written, and `rosdep update` run, when the list changed."""
    env = dict(env)
    if rosdistro_folder and not env.get('ROSDISTRO_INDEX_URL'):
        env['ROSDISTRO_INDEX_URL'] = 'file://%s/index-v4.yaml' % rosdistro_folder
    folder = os.path.join(cache, 'rosdep')
    lists = os.path.join(folder, 'sources.list.d')
    os.makedirs(lists, exist_ok=True)
    env['ROSDEP_SOURCE_PATH'] = lists
    env['ROS_HOME'] = os.path.join(folder, 'home')
    text = sources_list(rosdistro_folder) + '# index %s\n' % env.get('ROSDISTRO_INDEX_URL', '(default)')
    path = os.path.join(lists, '20-racebot.list')
    stamp = os.path.join(folder, 'updated')
    if os.path.isfile(stamp) and open(stamp).read() == text and os.path.isfile(path):
        return env
    with open(path, 'w') as f:
        f.write(text)
    done = subprocess.run(['rosdep', 'update', '--rosdistro', DISTRO, '--include-eol-distros'], env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        raise RosdistroError('rosdep update failed: %s' % done.stdout.strip().splitlines()[-1:])
    with open(stamp, 'w') as f:
        f.write(text)
    return env
