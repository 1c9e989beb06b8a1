"""The walk from what the targets need to the set of packages to build from source.

Each name the targets need goes to its provider (provide.py: racebot, installed, Debian through rosdep). The rest
are built from source: a name already in the underlay's src/ is taken from there, the others are handed to
rosinstall_generator in one call per round, vcstool checks out the repositories it names, and the package.xml
files of the packages taken (build, export and exec dependencies; their tests are not built) give the next round's
names. A name rosinstall_generator does not know, or whose repository cannot be checked out, is `unknown`, with
why. The rounds end when no new name comes.
"""
import os
import time

from deps import needs as needs_mod
from deps import repos as repos_mod


class Resolution:
    """What the walk found: `providers` {name: Provider}, `selected` {package: repository folder in src},
    `repos` {local name: .repos entry}, `unknown` {name: why}, `needed_by` {name: sorted needers}."""

    def __init__(self):
        self.providers, self.selected, self.repos, self.unknown, self.needed_by = {}, {}, {}, {}, {}

    def to_json(self):
        return {'providers': {name: {'kind': p.kind, 'where': p.where, 'packages': p.packages, 'missing': p.missing}
                              for name, p in self.providers.items()},
                'selected': self.selected, 'repos': self.repos, 'unknown': self.unknown, 'needed_by': self.needed_by}


def targets(args):
    """({name: (folder, Package)} of the packages under the folders among `args`, [the other args: names])."""
    local, names = {}, []
    for arg in args:
        if os.path.isdir(arg):
            found = needs_mod.local_packages(os.path.abspath(arg))
            if not found:
                raise SystemExit('racebot deps: no package.xml at or below %s' % arg)
            local.update(found)
        else:
            names.append(arg)
    return local, names


def src_packages_of(ws):
    """{package: (folder, Package)} of the underlay's src/ (none before its first checkout)."""
    return needs_mod.local_packages(ws.src) if os.path.isdir(ws.src) else {}


def _repo_of(folder, src, keys=()):
    """The local name of the checkout holding `folder`: the longest of `keys` it lies in, else its first folder."""
    rel = os.path.relpath(folder, src).replace(os.sep, '/')
    inside = [k for k in keys if rel == k or rel.startswith(k + '/')]
    return max(inside, key=len) if inside else rel.split('/')[0]


def _checkout(result, data, ctx):
    """Checks out the entries of `data` that are new to `result`; a failure's reason is kept in ctx['failed']
    ({local name: why}), where later rounds that meet the same repository find it."""
    new = {k: v for k, v in data.items() if result.repos.get(k) != v}
    result.repos.update(data)
    started = time.time()
    failed = repos_mod.checkout(new, ctx['ws'].src, ctx['ws'].root, ctx.get('clones'), ctx.get('mirrors'),
                                say=ctx.get('say', print))
    if new:
        ctx.get('say', print)('racebot deps: vcs import of %d repositories (%.0f s)' % (
            len(new), time.time() - started))
    ctx.setdefault('failed', {}).update(failed)


def _from_release_repositories(result, names, ctx):
    """The names whose source repository could not be checked out at its release tag (a copy that lacks it), from
    their release repositories' tags of the same release -> {name: its release repository's local name}."""
    data, _, error = repos_mod.generate(names, ctx['env'], upstream=False)
    data = {} if error else repos_mod.release_entries(data)
    ctx.get('say', print)('racebot deps: rosinstall_generator (release repositories): %s -> %s' % (
        ' '.join(sorted(names)), ' '.join('%s@%s' % (r, e['version']) for r, e in sorted(data.items())) or '-'))
    _checkout(result, data, ctx)
    return {local.split('/')[-1]: local for local in data}


def _fetch(result, wanted, ctx):
    """One round: rosinstall_generator for `wanted` names, vcs import of what is new (the release repositories for
    names whose source repository's tag is not at hand); the src packages after."""
    say = ctx.get('say', print)
    started = time.time()
    data, unreleased, error = repos_mod.generate(wanted, ctx['env'])
    say('racebot deps: rosinstall_generator: %s -> %s (%.0f s)' % (
        ' '.join(sorted(wanted)), ' '.join('%s@%s' % (r, e['version']) for r, e in sorted(data.items())) or '-',
        time.time() - started))
    for name in wanted:
        if error:
            result.unknown[name] = error
        elif name in unreleased:
            result.unknown[name] = 'no rosdep rule for debian:bookworm and no Noetic release in the rosdistro'
    _checkout(result, data, ctx)
    failed = ctx['failed']
    packages = src_packages_of(ctx['ws'])
    missing = sorted(n for n in wanted if n not in result.unknown and n not in packages)
    holders, released = {}, {}
    if missing and any(repo in failed for repo in data):
        holders = repos_mod.repositories_of(missing, ctx['env'])
        released = _from_release_repositories(result, missing, ctx)
        packages = src_packages_of(ctx['ws'])
    for name in wanted:
        if name in result.unknown or name in packages:
            continue
        # its own repository's failure (all of the round's when the rosdistro cannot say which holds it)
        reasons = [failed[holders[name]]] if holders.get(name) in failed else \
            [why for repo, why in sorted(failed.items()) if repo in data and not holders]
        if released.get(name) in failed:
            reasons.append('release repository: ' + failed[released[name]])
        result.unknown[name] = '; '.join(reasons) if reasons else \
            'rosinstall_generator named no repository holding it (it named: %s)' % (', '.join(sorted(data)) or 'none')
    return packages


def walk(local, names, providers, ctx):
    """Resolution for the target packages `local` and the package names `names`; ctx holds env, ws (the
    underlay Workspace), clones and mirrors."""
    result = Resolution()
    frontier = needs_mod.needs_of(local, tests=True)
    for name in names:
        frontier.setdefault(name, set()).add('(command line)')
    src_packages = src_packages_of(ctx['ws'])
    while frontier:
        wanted = {}
        for name, who in sorted(frontier.items()):
            result.needed_by[name] = sorted(set(result.needed_by.get(name, [])) | set(who))
            if name in result.providers or name in result.unknown or name in wanted:
                continue
            provider = providers.provider(name)
            result.providers[name] = provider
            if provider.kind == 'source' and name not in src_packages:
                wanted[name] = who
        if wanted:
            src_packages = _fetch(result, wanted, ctx)
        frontier = {}
        for name, provider in result.providers.items():
            if provider.kind != 'source' or name in result.selected or name not in src_packages:
                continue
            folder, package = src_packages[name]
            result.selected[name] = _repo_of(folder, ctx['ws'].src, result.repos)
            for dep in needs_mod.declared(package, tests=False):
                if dep not in local and dep != name:
                    frontier.setdefault(dep, set()).add(name)
    return result, src_packages
