"""Where the sources come from: rosinstall_generator names each package's repository and Noetic release
(`--upstream`: the source repository at the tag of the released version; where a copy of it lacks that tag, the
release repository's tag of the same version, as rosinstall_generator names it without --upstream), vcstool
checks them out. Offline, each
https://github.com/<owner>/<name>.git is taken from a local copy instead, looked up as make corpus looks
(tools/corpus/sources.py): a folder of existing clones (--clones, RACEBOT_CORPUS_DIR: DIR/<name>, DIR/<owner>/<name>,
DIR/<owner>+<name>) or mirrors (--mirrors, RACEBOT_CORPUS_MIRRORS: ROOT/<owner>+<name>/repo, ...); a repository in
neither is cloned from its URL.
"""
import os
import re
import shutil
import subprocess
import sys

import yaml

from corpus import sources as corpus_sources
from deps.index import DISTRO

GITHUB = re.compile(r'^https://github\.com/([^/]+)/([^/]+?)(?:\.git)?/?$')
UNRELEASED = re.compile(r'following unreleased packages/stacks will be ignored: (.*)')
CHECKOUT_FAILED = 'cannot check out'
VCS_SECTION = re.compile(r'^=== (\S+) \((\w+)\) ===$')
# the object a copy lacks, as the remote side of a fetch names it (a blob: unable to read; a folder: bad tree object)
UNREADABLE = re.compile(r'(?:unable to read|bad tree object|bad object) ([0-9a-f]{40})\b')


def generate(names, env, upstream=True):
    """(the .repos data rosinstall_generator gives for `names` ({local name: {type, url, version}}), the names
    it does not know as Noetic packages, its one-line error or ''). `upstream`: each source repository at the tag
    of its release; else each package's release repository at its release tag (`release/noetic/<pkg>/<version>`,
    the sources the Noetic binaries were built from), one entry per package."""
    cmd = ['rosinstall_generator', '--rosdistro', DISTRO] + (['--upstream'] if upstream else []) + \
        ['--format', 'repos'] + sorted(names)
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    unreleased = set()
    for line in done.stderr.splitlines():
        found = UNRELEASED.search(line)
        if found:
            unreleased.update(n.strip() for n in found.group(1).split(','))
    if done.returncode != 0:
        if 'No packages/stacks left after ignoring unreleased' in done.stderr:
            return {}, set(names), ''
        last = [line for line in done.stderr.splitlines() if line.strip()][-1:] or ['exit %d' % done.returncode]
        return {}, unreleased, 'rosinstall_generator failed: %s' % last[0].strip()
    data = yaml.safe_load(done.stdout) or {}
    return dict(data.get('repositories') or {}), unreleased, ''


def release_entries(data):
    """rosinstall_generator's release entries ({'navigation/amcl': {url: .../navigation-release.git, version:
    release/noetic/amcl/1.17.3-1}}) under local names of their own, '<release repository>/<package>'
    ('navigation-release/amcl'), so that they never share a folder with a checkout of the source repository."""
    named = {}
    for key, entry in data.items():
        repo = github_repo(entry.get('url')) or key.split('/')[0]
        package = str(entry.get('version', '')).split('/')[2:3] or [key.split('/')[-1]]
        named['%s/%s' % (repo.split('/')[-1], package[0])] = entry
    return named


def repositories_of(names, env):
    """{name: the rosdistro's repository releasing it} for the `names` the Noetic distribution file releases."""
    import rosdistro
    url = env.get('ROSDISTRO_INDEX_URL') or rosdistro.get_index_url()
    try:
        dist = rosdistro.get_distribution_file(rosdistro.get_index(url), DISTRO)
    except Exception:  # an index that cannot be read: the reasons fall back to the round's repositories
        return {}
    return {n: dist.release_packages[n].repository_name for n in names if n in dist.release_packages}


def github_repo(url):
    """'owner/name' of a GitHub URL, or None."""
    found = GITHUB.match(url or '')
    return '%s/%s' % found.groups() if found else None


def _is_git(path):
    return os.path.isdir(os.path.join(path, '.git')) or os.path.isfile(os.path.join(path, 'HEAD'))


def local_copy(url, clones=None, mirrors=None):
    """The path of a local clone or mirror of `url`, or None (then the URL itself is used)."""
    repo = github_repo(url)
    if not repo:
        return None
    candidates = (corpus_sources.clone_candidates(clones, repo) if clones else []) + \
        (corpus_sources.mirror_candidates(mirrors, repo) if mirrors else [])
    return next((path for path in candidates if _is_git(path)), None)


def _git(args, cwd):
    return subprocess.run(['git'] + args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)


def at_version(path, version):
    """True when the checkout at `path` has `version` (a tag, branch or commit) checked out, every tracked file
    there (a clone whose checkout failed has HEAD at the version and files missing)."""
    if not os.path.isdir(os.path.join(path, '.git')):
        return False
    head = _git(['rev-parse', 'HEAD'], path).stdout.strip()
    want = _git(['rev-parse', '--verify', '-q', version + '^{commit}'], path).stdout.strip()
    return bool(head) and head == want and not corpus_sources.dirty(path)


def vcs():
    """vcstool's `vcs` (installed into .venv by tools/requirements.txt)."""
    beside = os.path.join(os.path.dirname(sys.executable), 'vcs')
    return beside if os.path.exists(beside) else (shutil.which('vcs') or 'vcs')


def _vcs_errors(output, src=None):
    """{local name: its error in one line} from `vcs import` output: vcstool's summary of the failed step
    ("Could not clone repository '...'"), followed by git's own first `error:` or `fatal:` line where the summary
    does not hold it (a clone whose checkout failed prints "Cloning into '.'..." first). A local name is the
    section's path below `src` (a release repository's `navigation-release/fake_localization`), or its last part."""
    sections, current = {}, None
    for line in output.splitlines():
        found = VCS_SECTION.match(line.strip())
        if found:
            path = found.group(1)
            current = os.path.relpath(path, src) if src and os.path.isabs(path) else os.path.basename(path)
            sections.setdefault(current, [])
        elif current and line.strip():
            sections[current].append(line.strip())
    errors = {}
    for name, lines in sections.items():
        first = next((text for text in lines
                      if any(word in text.lower() for word in ('error', 'fatal', 'could not', 'failed'))), None)
        if first is None:
            continue
        # git names the object it could not read on the remote side's stderr, which reaches the output before or
        # after the local side's "git-pack-objects died" as the two processes happen to write: that is the cause
        unreadable = next((text for text in lines if UNREADABLE.search(text)), None)
        if unreadable:
            cause = unreadable[len('remote: '):] if unreadable.startswith('remote: ') else unreadable
        elif not re.search(r'(^|: )(error|fatal):', first):
            cause = next((text for text in lines if text.startswith(('error:', 'fatal:'))), None)
        else:
            cause = None
        if cause and cause != first:  # git's own line replaces git's line, and follows vcstool's summary
            first = cause if re.match(r'(remote: )?(error|fatal):', first) else \
                '%s: %s' % (first.split(': ', 1)[0], cause)
        errors[name] = first
    return errors


def _vcs_import(wanted, src, work, log):
    """`vcs import --shallow` of `wanted` into `src` without vcstool's retries: a retry of a clone whose checkout
    failed clones into the half-written folder and reports only "destination path '.' already exists", hiding
    git's error (a missing object, a path the filesystem refuses). Shallow, because the underlay builds one
    release and never reads history, and because a full clone first checks out the default branch: a copy whose
    branch lacks objects the release tag does not need (a snapshot that left large files out) would fail there.
    Returns {local name: one-line error}."""
    listing = os.path.join(work, 'import.repos')
    with open(listing, 'w') as f:
        yaml.safe_dump({'repositories': wanted}, f, default_flow_style=False)
    done = subprocess.run([vcs(), 'import', '--force', '--shallow', '--retry', '0', '--input', listing, src],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    log.write(done.stdout)
    return _vcs_errors(done.stdout, os.path.abspath(src))


def _name_object(error, url, version):
    """`error` with the path of the object git could not read (a shallow fetch names only its hash), looked up in
    the version's tree of a local copy: which file the copy lacks is what its user can act on."""
    found = UNREADABLE.search(error)
    if not found or not os.path.isdir(url):
        return error
    listing = _git(['ls-tree', '-r', '-t', version], url).stdout
    path = next((line.split('\t', 1)[1] for line in listing.splitlines()
                 if '\t' in line and line.split()[2] == found.group(1)), None)
    return error if path is None else error[:found.end()] + ' (%s)' % path + error[found.end():]


def _checkout_lacking(url, version, dest):
    """Checks out `version` of the local copy `url` in `dest` without the files whose objects the copy lacks
    (corpus_sources.checkout_without; the objects are read from the copy, as `clone --shared` reads them, so no
    missing one is ever packed); whether it did (False when none is missing or the checkout fails)."""
    shutil.rmtree(dest, ignore_errors=True)
    if subprocess.run(['git', 'clone', '-q', '--shared', '--no-checkout', url, dest], stdout=subprocess.DEVNULL,
                      stderr=subprocess.DEVNULL).returncode != 0:
        return False
    missing = corpus_sources.missing_files(dest, version)
    if not missing or not corpus_sources.checkout_without(dest, version, missing) or not at_version(dest, version):
        shutil.rmtree(dest, ignore_errors=True)
        return False
    return True


def checkout(repos, src, work, clones=None, mirrors=None, say=print):
    """Checks out every repository of `repos` ({local name: entry}) in `src` at its version with `vcs import`,
    each from its local copy when there is one; {local name: one-line error} for those that failed. A local copy
    that lacks some of the version's files (git cannot read their objects) is checked out without them, in one
    line to `say`: the build goes on where it does not need them (a test's recorded bag), and fails as before, on
    the file, where it does."""
    wanted = {name: dict(entry, url=local_copy(entry['url'], clones, mirrors) or entry['url'])
              for name, entry in repos.items() if not at_version(os.path.join(src, name), str(entry['version']))}
    if not wanted:
        return {}
    os.makedirs(src, exist_ok=True)
    with open(os.path.join(work, 'vcs-import.log'), 'w') as log:
        errors = _vcs_import(wanted, src, work, log)
        # a remote repository gets one more try (the network), from an empty folder, as vcstool's retry meant to
        again = {name: entry for name, entry in wanted.items() if name in errors and not os.path.isdir(entry['url'])
                 and not at_version(os.path.join(src, name), str(entry['version']))}
        for name in again:
            shutil.rmtree(os.path.join(src, name), ignore_errors=True)
        if again:
            errors.update(_vcs_import(again, src, work, log))
    for name, entry in wanted.items():
        # a local copy not checked out at its version (git could not read some of its objects, and says so in
        # the error or, from a checkout that exits 0, only in the files it leaves missing)
        if os.path.isdir(entry['url']) and not at_version(os.path.join(src, name), str(entry['version'])):
            dest = os.path.join(src, name)
            if _checkout_lacking(entry['url'], str(entry['version']), dest):
                say('racebot deps: %s at %s %s' % (name, entry['version'],
                                                  corpus_sources.lacking_note(dest, entry['url'])))
    failed = {}
    for name, entry in wanted.items():
        if not at_version(os.path.join(src, name), str(entry['version'])):
            shutil.rmtree(os.path.join(src, name), ignore_errors=True)  # never build another version than the pinned
            error = _name_object(errors[name], entry['url'], str(entry['version'])) if name in errors else \
                'see %s' % os.path.join(work, 'vcs-import.log')
            failed[name] = '%s %s at %s from %s: %s' % (CHECKOUT_FAILED, name, entry['version'], entry['url'], error)
    return failed
