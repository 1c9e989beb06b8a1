"""The README is a front page that links to the reference in docs/: every relative link and image there must
lead to a file (and a #section to a heading of it), every docs page must be reachable from the README, and the
README stays short."""
import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
README = REPO / 'README.md'
PAGES = [README] + sorted((REPO / 'docs').glob('*.md'))
README_MAX_LINES = 250

FENCE = re.compile(r'^\s*(```|~~~)')
CODE_SPAN = re.compile(r'`[^`]*`')
INLINE_LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
REFERENCE_DEF = re.compile(r'^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+"[^"]*")?\s*$')
HEADING = re.compile(r'^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$')


def prose_lines(text):
    """The lines outside fenced code blocks, with inline code removed (a link shown as code is no link)."""
    inside = False
    for line in text.split('\n'):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield CODE_SPAN.sub('', line)


def links(path):
    """Every link and image target of a markdown file, as written."""
    found = []
    for line in prose_lines(path.read_text(encoding='utf-8')):
        found += INLINE_LINK.findall(line)
        definition = REFERENCE_DEF.match(line)
        if definition:
            found.append(definition.group(1))
    return found


def anchors(path):
    """The #fragments GitHub gives a markdown file's headings (lower case, punctuation dropped, spaces to
    hyphens, a repeated heading numbered)."""
    seen = {}
    result = set()
    for line in prose_lines(path.read_text(encoding='utf-8')):
        heading = HEADING.match(line)
        if not heading:
            continue
        text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading.group(1))  # a link in a heading: its text
        slug = re.sub(r'[^\w\- ]', '', text.strip().lower()).replace(' ', '-')
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        result.add(slug if count == 0 else '%s-%d' % (slug, count))
    return result


def broken_links(path):
    """The relative links of a markdown file that lead nowhere, each with the reason."""
    broken = []
    for target in links(path):
        if re.match(r'^[a-z][a-z0-9+.-]*:', target, re.IGNORECASE):  # http:, https:, mailto:, ...
            continue
        name, _, fragment = target.partition('#')
        destination = (path.parent / name).resolve() if name else path
        if not destination.exists():
            broken.append('%s: no such file %s' % (target, destination))
        elif fragment and destination.suffix == '.md' and fragment not in anchors(destination):
            broken.append('%s: %s has no heading #%s' % (target, destination.name, fragment))
    return broken


@pytest.mark.parametrize('page', PAGES, ids=lambda page: str(page.relative_to(REPO)))
def test_every_relative_link_and_image_resolves(page):
    broken = broken_links(page)
    assert not broken, "\n".join(broken)


def test_every_docs_page_is_linked_from_the_readme():
    linked = {(README.parent / target.partition('#')[0]).resolve() for target in links(README)}
    assert [str(page.relative_to(REPO)) for page in PAGES[1:] if page.resolve() not in linked] == []


def test_the_readme_is_a_front_page_of_at_most_250_lines():
    assert len(README.read_text(encoding='utf-8').splitlines()) <= README_MAX_LINES


def test_the_checker_finds_a_broken_link_an_image_and_a_missing_section(tmp_path):
    (tmp_path / 'there.md').write_text('# A page\n\n## Its section\n')
    page = tmp_path / 'page.md'
    page.write_text('See [it](there.md), [its section](there.md#its-section) and [away](https://example.org).\n'
                    '![gone](images/gone.png) and [lost](lost.md), [no section](there.md#nowhere).\n'
                    '`[code](not_a_link.md)`\n```\n[fenced](not_a_link_either.md)\n```\n')
    assert broken_links(page) == [
        'images/gone.png: no such file %s' % (tmp_path / 'images' / 'gone.png'),
        'lost.md: no such file %s' % (tmp_path / 'lost.md'),
        'there.md#nowhere: there.md has no heading #nowhere',
    ]
