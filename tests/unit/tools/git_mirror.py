"""A repository's mirror that lacks some of its objects, as a snapshot that left large files out (for make corpus's
and make deps' checkouts of such a copy: test_corpus.py, test_deps.py)."""
import subprocess


def git(*args, cwd=None):
    """git's output, stripped; a failing git fails the test."""
    return subprocess.run(['git', '-c', 'user.email=t@t', '-c', 'user.name=t'] + list(args), cwd=cwd, check=True,
                          capture_output=True, text=True).stdout.strip()


def mirror_lacking(work, files, mirror, lacking, tag=None):
    """A repository at `work` holding `files` ({path: bytes}), one commit (tagged `tag` if given), mirrored to
    `mirror` without the objects of the paths `lacking` (files: their blobs; folders: their trees); the commit."""
    for path, data in files.items():
        (work / path).parent.mkdir(parents=True, exist_ok=True)
        (work / path).write_bytes(data)
    git('init', '-q', cwd=work)
    git('add', '.', cwd=work)
    git('commit', '-qm', 'one', cwd=work)
    if tag:
        git('tag', tag, cwd=work)
    git('clone', '-q', '--mirror', str(work), str(mirror))
    for path in lacking:
        sha = git('rev-parse', 'HEAD:' + path, cwd=work)
        (mirror / 'objects' / sha[:2] / sha[2:]).unlink()
    return git('rev-parse', 'HEAD', cwd=work)
