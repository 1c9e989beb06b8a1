"""tools/run_tests.py's closing check: after the suite catkin finds only the repository's packages."""
import importlib.util
import os
import subprocess

SPEC = importlib.util.spec_from_file_location(
    'run_tests', os.path.join(os.path.dirname(__file__), '..', '..', '..', 'tools', 'run_tests.py'))
run_tests = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(run_tests)


def _package(folder, name):
    os.makedirs(folder)
    with open(os.path.join(folder, 'package.xml'), 'w') as xml:
        xml.write('<package format="2"><name>%s</name><version>1.0.0</version><description>d</description>'
                  '<maintainer email="m@example.com">m</maintainer><license>BSD</license></package>' % name)


def test_a_package_the_suite_writes_under_out_is_stray_until_out_is_ignored(tmp_path):
    """make test, then make run: a package the bench generated under out/ stopped the next catkin_make."""
    root = str(tmp_path)
    subprocess.run(['git', 'init', '-q', root], check=True)
    _package(os.path.join(root, 'robot'), 'robot')
    subprocess.run(['git', '-C', root, 'add', 'robot'], check=True)
    _package(os.path.join(root, 'out', 'bench', 'big_world'), 'big_world')
    assert run_tests.stray_packages(root) == [os.path.join('out', 'bench', 'big_world')]
    open(os.path.join(root, 'out', 'CATKIN_IGNORE'), 'w').close()
    assert run_tests.stray_packages(root) == []
