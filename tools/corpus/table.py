"""The corpus table: what `make corpus` prints and writes (out/corpus/corpus.md, corpus.json). Pure.

A row's result (run.py makes it): name, covers, repos [{repo, commit, note}], commands, build
('ok', 'failed: ...', 'not run'), checks [{kind, ok, numbers, reason}], status ('pass', 'fail',
'not run'), reason (the first cause), notes (missing packages, nodes that died), seconds.
"""
import json

CELL_LIMIT = 160


def cell(text, limit=CELL_LIMIT):
    """Text fit for one Markdown table cell: one line, pipes escaped, cut to `limit`."""
    text = ' '.join(str(text or '').split()).replace('|', '\\|')
    return text if len(text) <= limit else text[:limit - 3] + '...'


def first_reason(result):
    """The row's first cause of failure: the source, the build, then the first failed check in manifest order."""
    if result.get('status') == 'pass':
        return ''
    if result.get('reason'):
        return result['reason']
    build = result.get('build', '')
    if build.startswith('failed'):
        return 'build ' + build
    for check in result.get('checks', []):
        if not check.get('ok'):
            return '%s: %s' % (check['kind'], check.get('reason') or 'failed')
    return ''


def status(result):
    """'pass' only when the build and every check passed; 'not run' when nothing ran."""
    if result.get('status') == 'not run':
        return 'not run'
    checks = result.get('checks') or []
    if checks and all(c.get('ok') for c in checks) and result.get('build') == 'ok':
        return 'pass'
    return 'fail'


def summary(results):
    counts = {}
    for r in results:
        counts[r['status']] = counts.get(r['status'], 0) + 1
    return '%d of %d rows pass' % (counts.get('pass', 0), len(results)) + ''.join(
        ', %d %s' % (n, s) for s, n in sorted(counts.items()) if s != 'pass')


def markdown(results, header):
    """The table, then each row's checks with their numbers. `header`: lines above the table (date, commit)."""
    lines = list(header) + ['', summary(results) + '.', '',
                            '| row | covers | command | build | checks | result | first reason |',
                            '| --- | --- | --- | --- | --- | --- | --- |']
    for r in results:
        checks = r.get('checks') or []
        passed = sum(1 for c in checks if c.get('ok'))
        lines.append('| %s | %s | `%s` | %s | %s | **%s** | %s |' % (
            r['name'], cell(', '.join(r.get('covers', [])), 80), cell(' ; '.join(r.get('commands', [])), 90),
            cell(r.get('build', ''), 40), '%d/%d' % (passed, len(checks)) if checks else '-', r['status'],
            cell(first_reason(r))))
    lines += ['', '## Each row', '']
    for r in results:
        lines.append('### %s (%s)' % (r['name'], r['status']))
        for repo in r.get('repos', []):
            lines.append('- `%s` at `%s`%s' % (repo['repo'], repo['commit'][:12],
                                              ' (%s)' % repo['note'] if repo.get('note') else ''))
        if r.get('env'):
            lines.append('- env: ' + ' '.join('`%s=%s`' % kv for kv in sorted(r['env'].items())))
        if r.get('files'):
            lines.append("- the user's own files, in the folder the commands run in (the row's files in the manifest): "
                         + ', '.join('`%s`' % name for name in r['files']))
        if r.get('user_packages'):
            lines.append("- the user's own catkin packages, built in the workspace beside the row's (in the manifest): "
                         + ', '.join('`%s`' % name for name in r['user_packages']))
        for command in r.get('commands', []):
            lines.append('- `%s`' % command)
        if r.get('blacklist'):
            lines.append('- left out of the build: ' + '; '.join('`%s` (%s)' % kv for kv in r['blacklist'].items()))
        lines.append('- build: %s' % r.get('build', ''))
        for c in r.get('checks') or []:
            verdict = 'pass' if c.get('ok') else 'FAIL'
            lines.append('- %s **%s**: %s%s' % (verdict, c['kind'], cell(c.get('numbers'), 600),
                                                 '' if c.get('ok') else ' -- ' + cell(c.get('reason'), 400)))
        for note in r.get('notes') or []:
            lines.append('- note: %s' % cell(note, 400))
        lines.append('')
    return '\n'.join(lines) + '\n'


def console(results):
    """The table as plain text for the terminal: one line a row."""
    width = max([len(r['name']) for r in results] + [4])
    out = []
    for r in results:
        checks = r.get('checks') or []
        passed = sum(1 for c in checks if c.get('ok'))
        out.append('%-*s  %-7s  checks %s  %s' % (width, r['name'], r['status'],
                                                   '%d/%d' % (passed, len(checks)) if checks else '-  ',
                                                   cell(first_reason(r), 150)))
    out.append(summary(results))
    return '\n'.join(out)


def to_json(results, meta):
    return json.dumps(dict(meta, rows=results), indent=2, sort_keys=True) + '\n'
