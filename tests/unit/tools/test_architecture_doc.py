"""docs/ARCHITECTURE.md names every module of racebot_sim_bridge, each under its subpackage's heading: the map
must follow the code (issue 28: "names every module with one line each")."""
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
PACKAGE = REPO / 'racebot_sim_bridge' / 'src' / 'racebot_sim_bridge'
DOC = REPO / 'docs' / 'ARCHITECTURE.md'


def sections():
    """{heading text: body} of the page's ### sections."""
    text = DOC.read_text()
    parts = re.split(r'^### (.+)$', text, flags=re.M)
    return {parts[i].strip(): parts[i + 1] for i in range(1, len(parts), 2)}


def section_of(folder):
    """The ### section about `folder/` (its heading starts with the folder), or 'at the top' for the top level."""
    found = sections()
    heading = 'at the top' if folder == '' else next((h for h in found if h.startswith(folder + '/')), None)
    assert heading in found, 'docs/ARCHITECTURE.md has no "### %s/" section' % folder
    return found[heading]


def test_every_module_is_named_once_in_its_subpackage_section():
    missing = []
    for path in sorted(PACKAGE.rglob('*.py')):
        if path.name == '__init__.py':
            continue
        folder = str(path.parent.relative_to(PACKAGE)).replace('.', '')
        body = section_of(folder)
        if not re.search(r'^\| `%s`' % re.escape(path.name), body, flags=re.M):
            missing.append(str(path.relative_to(PACKAGE)))
    assert not missing, 'docs/ARCHITECTURE.md does not name these modules in their section: %s' % missing


def test_no_module_named_that_does_not_exist():
    stale = []
    for heading, body in sections().items():
        folder = '' if heading == 'at the top' else heading.split('/')[0]
        for name in re.findall(r'^\| `([a-z_0-9]+\.py)`', body, flags=re.M):
            if not (PACKAGE / folder / name).is_file():
                stale.append('%s/%s' % (folder, name) if folder else name)
    assert not stale, 'docs/ARCHITECTURE.md names modules that do not exist: %s' % stale
