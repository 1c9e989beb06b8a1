"""Where a corpus repository comes from, and its checkout at the pinned commit.

Three sources, first match wins:
  RACEBOT_CORPUS_DIR=DIR       existing clones, used as they are (no network, nothing fetched or checked
                               out in them): DIR/<name>, DIR/<owner>/<name> or DIR/<owner>+<name>
  RACEBOT_CORPUS_MIRRORS=ROOT  local mirrors to clone from (no network): ROOT/<owner>+<name>/repo[/.git],
                               ROOT/<owner>/<name>.git or ROOT/<owner>/<name>
  otherwise                    https://github.com/<owner>/<name>.git (RACEBOT_CORPUS_URL overrides the
                               pattern, with {owner} and {name})
Clones go to the cache (RACEBOT_CORPUS_CACHE, default ~/.cache/racebot/corpus): one clone per repository
in git/, one checkout per (repository, commit) in src/. resolve() is pure; checkout() runs git. A copy that lacks
some files of the commit (a snapshot that left large files out: a mesh, a recorded bag) is checked out without
exactly those, and the row's note names them (make deps checks its sources out the same way).
"""
import os
import re
import subprocess

DEFAULT_URL = 'https://github.com/{owner}/{name}.git'


def cache_dir(env=os.environ):
    return os.path.expanduser(env.get('RACEBOT_CORPUS_CACHE') or os.path.join('~', '.cache', 'racebot', 'corpus'))


def _is_git(path):
    return os.path.isdir(os.path.join(path, '.git')) or os.path.isfile(os.path.join(path, 'HEAD'))


def clone_candidates(root, repo):
    owner, name = repo.split('/')
    return [os.path.join(root, name), os.path.join(root, owner, name), os.path.join(root, '%s+%s' % (owner, name))]


def mirror_candidates(root, repo):
    owner, name = repo.split('/')
    flat = os.path.join(root, '%s+%s' % (owner, name))
    return [os.path.join(flat, 'repo', '.git'), os.path.join(flat, 'repo'), flat,
            os.path.join(root, owner, name + '.git'), os.path.join(root, owner, name)]


def resolve(repo, env=os.environ):
    """('dir', path) for an existing clone to use in place, ('clone', source) for a mirror or URL to clone
    from, or ('missing', why) when a folder was named but holds no clone of `repo`."""
    clones = env.get('RACEBOT_CORPUS_DIR')
    if clones:
        found = next((p for p in clone_candidates(clones, repo) if _is_git(p)), None)
        if found:
            return 'dir', found
        mirrors = env.get('RACEBOT_CORPUS_MIRRORS')
        if not mirrors:
            return 'missing', 'no clone of %s in RACEBOT_CORPUS_DIR=%s (looked for %s)' % (
                repo, clones, ', '.join(os.path.relpath(p, clones) for p in clone_candidates(clones, repo)))
    mirrors = env.get('RACEBOT_CORPUS_MIRRORS')
    if mirrors:
        found = next((p for p in mirror_candidates(mirrors, repo) if _is_git(p)), None)
        if found:
            return 'clone', found
        return 'missing', 'no mirror of %s under RACEBOT_CORPUS_MIRRORS=%s' % (repo, mirrors)
    owner, name = repo.split('/')
    return 'clone', (env.get('RACEBOT_CORPUS_URL') or DEFAULT_URL).format(owner=owner, name=name)


def _git(args, cwd=None, log=None):
    done = subprocess.run(['git'] + args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    if log is not None:
        log.append('$ git %s\n%s' % (' '.join(args), done.stdout))
    return done


class SourceError(RuntimeError):
    """A repository could not be had at its commit; the message says why."""


def dirty(tree):
    """Whether a tracked file of the checkout `tree` differs from its commit (one git could not write)."""
    return bool(_git(['status', '--porcelain', '--untracked-files=no'], cwd=tree).stdout.strip())


def head_commit(path):
    if not os.path.isdir(path):
        return None
    done = _git(['rev-parse', 'HEAD'], cwd=path)
    return done.stdout.strip() if done.returncode == 0 else None


def _cache_paths(repo, commit, env):
    """(the cache's bare clone of `repo`, its checkout at `commit`)."""
    cache = cache_dir(env)
    owner, name = repo.split('/')
    return (os.path.join(cache, 'git', '%s+%s.git' % (owner, name)),
            os.path.join(cache, 'src', '%s+%s' % (owner, name), commit[:12]))


def cached(repo, commit, env=os.environ):
    """True when the cache can give `repo` at `commit` without the network (a checkout or a clone holding it)."""
    bare, tree = _cache_paths(repo, commit, env)
    if head_commit(tree) == commit:
        return True
    return os.path.isdir(bare) and _git(['cat-file', '-e', commit + '^{commit}'], cwd=bare).returncode == 0


def missing_files(git_dir, version):
    """The paths of `version`'s files whose objects the clone at `git_dir` (or the copy its objects come from)
    lacks; [] when none is missing or the version's tree cannot be listed (a folder's tree is missing too)."""
    listing = _git(['ls-tree', '-r', '-z', version], cwd=git_dir)
    if listing.returncode != 0:
        return []
    blobs = [(line.split()[2], line.split('\t', 1)[1]) for line in listing.stdout.split('\0')
             if '\t' in line and line.split()[1] == 'blob']
    check = subprocess.run(['git', 'cat-file', '--batch-check'], cwd=git_dir,
                           input=''.join(sha + '\n' for sha, _ in blobs), stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, text=True).stdout.splitlines()
    return [path for (_, path), line in zip(blobs, check) if line.endswith(' missing')]


def checkout_without(tree, version, paths):
    """Checks `version` out in the clone `tree` without the files `paths` (a sparse checkout leaving out exactly
    those, so their objects are never read); True when git says it did."""
    _git(['config', 'core.sparseCheckout', 'true'], cwd=tree)
    with open(os.path.join(tree, '.git', 'info', 'sparse-checkout'), 'w') as f:
        f.write('/*\n' + ''.join('!/%s\n' % re.sub(r'([\\*?\[\]!# ])', r'\\\1', path) for path in paths))
    return _git(['checkout', '-q', '--detach', '--force', version], cwd=tree).returncode == 0


def left_out(tree):
    """The files a sparse checkout_without left out of `tree` ([] for a whole checkout)."""
    sparse = os.path.join(tree, '.git', 'info', 'sparse-checkout')
    if not os.path.isfile(sparse):
        return []
    with open(sparse) as f:
        return [re.sub(r'\\(.)', r'\1', line.strip()[2:]) for line in f if line.startswith('!/')]


def lacking_note(tree, where, under=('.',)):
    """The row's note on a checkout that left out files of the folders `under` (the row's packages; '.' the whole
    repository), naming them and counting the others; '' when it left none of those out."""
    paths = left_out(tree)
    if not paths:
        return ''
    folders = [u.strip('/') for u in under]
    mine = [p for p in paths if any(f in ('', '.') or p == f or p.startswith(f + '/') for f in folders)]
    if not mine:  # nothing the row takes
        return ''
    others = len(paths) - len(mine)
    return 'checked out without %s%s: %s lacks them (a snapshot that left large files out; a clone from the ' \
        'network has them)' % (', '.join(mine), ' (and %d files of other folders)' % others if others else '', where)


def checkout(repo, commit, env=os.environ, log=None, packages=('.',)):
    """(path of a work tree of `repo` at `commit`, note): a checkout in the cache, or with
    RACEBOT_CORPUS_DIR the user's clone as it is (the note says when its HEAD is not the pinned commit, or which
    files of the folders `packages` the copy lacked)."""
    kind, where = resolve(repo, env)
    if kind == 'missing':
        raise SourceError(where)
    if kind == 'dir':
        head = head_commit(where)
        note = '' if head == commit else 'clone at %s, manifest pins %s' % ((head or '?')[:12], commit[:12])
        return where, note
    bare, tree = _cache_paths(repo, commit, env)
    if head_commit(tree) == commit:
        return tree, lacking_note(tree, where, packages)
    if not os.path.isdir(bare):
        os.makedirs(os.path.dirname(bare), exist_ok=True)
        done = _git(['clone', '--quiet', '--bare', where, bare], log=log)
        if done.returncode != 0:
            raise SourceError('git clone %s failed: %s' % (where, done.stdout.strip().splitlines()[-1:]))
    if _git(['cat-file', '-e', commit + '^{commit}'], cwd=bare).returncode != 0:
        _git(['fetch', '--quiet', where, '+refs/heads/*:refs/heads/*', '+refs/tags/*:refs/tags/*'], cwd=bare, log=log)
        if _git(['cat-file', '-e', commit + '^{commit}'], cwd=bare).returncode != 0:
            _git(['fetch', '--quiet', where, commit], cwd=bare, log=log)
    if _git(['cat-file', '-e', commit + '^{commit}'], cwd=bare).returncode != 0:
        raise SourceError('commit %s is not in %s' % (commit, where))
    if os.path.isdir(tree):
        done = _git(['checkout', '--quiet', '--detach', '--force', commit], cwd=tree, log=log)
    else:
        os.makedirs(os.path.dirname(tree), exist_ok=True)
        done = _git(['clone', '--quiet', '--shared', '--no-checkout', bare, tree], log=log)
        if done.returncode == 0:
            done = _git(['checkout', '--quiet', '--detach', commit], cwd=tree, log=log)
    # a copy lacking some of the commit's files (git's checkout says "unable to read" and may still exit 0, with
    # those files missing from the tree): the rest, and the note names them
    whole = done.returncode == 0 and not dirty(tree)
    if not whole:
        missing = missing_files(tree, commit)
        whole = bool(missing) and checkout_without(tree, commit, missing) and not dirty(tree)
    if not whole or head_commit(tree) != commit:
        raise SourceError('checkout of %s at %s failed: %s' % (repo, commit[:12], done.stdout.strip()[-300:]))
    return tree, lacking_note(tree, where, packages)
