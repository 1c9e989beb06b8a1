"""The tutorial's launch files kept as test fixtures (tests/fixtures/tutorial_launch) are the seed's text
byte for byte, and racebot's own launch files keep everything the tutorial's say. No ROS master.

tests/integration/tutorial_launch_test.py runs the fixtures unchanged (`roslaunch racebot_gazebo
racebot.launch`, in a workspace overlaying racebot); here they are checked against the seed (when the
project's shared folder is beside the checkout) and always against their stored sha256.
"""
import hashlib
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SEED = REPO.parent / 'shared' / 'seed' / '000_32f260074f6a33b6.txt'
FIXTURES = REPO / 'tests' / 'fixtures' / 'tutorial_launch'
RACEBOT_LAUNCH = FIXTURES / 'racebot_gazebo' / 'launch' / 'racebot.launch'
CONTROL_LAUNCH = FIXTURES / 'racebot_control' / 'launch' / 'racebot_control.launch'
SHA256 = {  # of the seed's text, as extracted on the day the fixtures were made
    RACEBOT_LAUNCH: '4e4445e04a454e0d736af41685eebc1e920a8c132ae98c8b0145f6cf957f071d',
    CONTROL_LAUNCH: 'd623a56f22250f257d7b992e106d254ecc9f35af1d74b97822e151f8c80a7c10',
}
# Attributes racebot's launch files may add to an element of the tutorial's: a switch for an optional
# part (teleop:=false), where a node's output goes, an argument's help text.
ADDED_ATTRIBUTES = {'if', 'output', 'doc'}


def seed_launch_files(text):
    """The seed's launch files as printed: each from a line `<?xml` to the next line `</launch>`."""
    return re.findall(r'^<\?xml.*?^</launch>\n', text, re.S | re.M)


def seed_fixture_texts():
    blocks = seed_launch_files(SEED.read_text(encoding='utf-8'))
    racebot = [b for b in blocks if '$(find gazebo_ros)/launch/empty_world.launch' in b]
    control = [b for b in blocks if 'controller_manager' in b and 'type="transform.py"' in b]
    assert len(racebot) == 1, 'the seed prints %d racebot.launch files, expected one' % len(racebot)
    assert control, 'the seed prints no racebot_control.launch with transform.py'
    return {RACEBOT_LAUNCH: racebot[0], CONTROL_LAUNCH: control[-1]}  # the final version is the last


@pytest.mark.parametrize('path', sorted(SHA256), ids=lambda p: p.name)
def test_fixture_has_its_stored_sha256(path):
    assert hashlib.sha256(path.read_bytes()).hexdigest() == SHA256[path], (
        '%s changed: it must stay the tutorial\'s text byte for byte' % path.relative_to(REPO))


@pytest.mark.skipif(not SEED.is_file(), reason='the seed (%s) is not beside this checkout (CI\'s fresh '
                    'clone has no shared folder); the stored sha256 still pins the fixtures' % SEED)
@pytest.mark.parametrize('path', sorted(SHA256), ids=lambda p: p.name)
def test_fixture_is_the_seed_text(path):
    expected = seed_fixture_texts()[path]
    assert path.read_bytes() == expected.encode('utf-8'), (
        '%s differs from the launch file printed in %s' % (path.relative_to(REPO), SEED))


@pytest.mark.parametrize('link, real', [
    (FIXTURES / 'racebot_control' / 'config', REPO / 'racebot_control' / 'config'),
    (FIXTURES / 'racebot_gazebo' / 'config', REPO / 'racebot_gazebo' / 'config'),
    (FIXTURES / 'racebot_gazebo' / 'worlds', REPO / 'racebot_gazebo' / 'worlds'),
], ids=lambda p: str(p.relative_to(REPO)) if isinstance(p, Path) else p)
def test_fixture_packages_share_the_real_resources(link, real):
    assert link.is_symlink() and link.resolve() == real.resolve(), '%s must link to %s' % (link, real)


# -- racebot's own launch files keep the tutorial's ------------------------------------------------
def normalised(value):
    return ' '.join(value.split())


def arg_defaults(root):
    """The launch file's own arguments (not those it passes to an include) with a default."""
    return {a.get('name'): a.get('default') for a in root.findall('arg') if a.get('default') is not None}


def resolve_own_args(value, own_defaults):
    """`$(arg X)` of an argument only racebot declares -> its default: the tutorial's behaviour."""
    return re.sub(r'\$\(arg (\w+)\)', lambda m: own_defaults.get(m.group(1), m.group(0)), value)


def matches(tutorial, ours, own_defaults):
    """ours carries tutorial: same tag, every attribute the same (ours may add ADDED_ATTRIBUTES), and
    every child of tutorial's carried by one of ours's children."""
    if tutorial.tag != ours.tag or set(ours.attrib) - set(tutorial.attrib) - ADDED_ATTRIBUTES:
        return False
    for name, value in tutorial.attrib.items():
        if normalised(resolve_own_args(ours.get(name, ''), own_defaults)) != normalised(value):
            return False
    return all(any(matches(child, mine, own_defaults) for mine in ours) for child in tutorial)


def missing_elements(tutorial_path, ours_path):
    tutorial, ours = ET.parse(str(tutorial_path)).getroot(), ET.parse(str(ours_path)).getroot()
    tutorial_args = {a.get('name') for a in tutorial.findall('arg')}
    own_defaults = {k: v for k, v in arg_defaults(ours).items() if k not in tutorial_args}
    return [ET.tostring(element, encoding='unicode').strip() for element in tutorial
            if not any(matches(element, mine, own_defaults) for mine in ours)]


@pytest.mark.parametrize('tutorial, ours', [
    (RACEBOT_LAUNCH, REPO / 'racebot_gazebo' / 'launch' / 'racebot.launch'),
    (CONTROL_LAUNCH, REPO / 'racebot_control' / 'launch' / 'racebot_control.launch'),
], ids=lambda p: p.name)
def test_our_launch_file_carries_every_element_of_the_tutorials(tutorial, ours):
    missing = missing_elements(tutorial, ours)
    assert not missing, '%s lacks these elements of the tutorial\'s %s (or changed them):\n%s' % (
        ours.relative_to(REPO), tutorial.name, '\n'.join(missing))


def test_the_comparison_sees_a_changed_element(tmp_path):
    """The check above fails on a launch file that runs the tutorial's node under another name."""
    changed = tmp_path / 'racebot_control.launch'
    changed.write_text(CONTROL_LAUNCH.read_text(encoding='utf-8').replace('type="transform.py"', 'type="transform"'))
    assert missing_elements(CONTROL_LAUNCH, changed) == [
        '<node pkg="racebot_control" type="transform.py" name="transform" output="screen" />']
