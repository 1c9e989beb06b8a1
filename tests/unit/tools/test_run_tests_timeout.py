"""tools/run_tests.py: the hang guard around a rostest file is never tighter than the file's own time-limits, and
when it fires it ends the whole process group, not only rostest."""
import glob
import importlib.util
import os
import time

SPEC = importlib.util.spec_from_file_location(
    'run_tests', os.path.join(os.path.dirname(__file__), '..', '..', '..', 'tools', 'run_tests.py'))
run_tests = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(run_tests)
INTEGRATION = os.path.join(os.path.dirname(__file__), '..', '..', 'integration')


def write(tmp_path, body):
    path = tmp_path / 'x.test'
    path.write_text('<?xml version="1.0"?>\n<launch>\n%s\n</launch>\n' % body)
    return str(path)


def test_the_guard_is_the_sum_of_the_nodes_time_limits_and_the_slack(tmp_path):
    test_file = write(tmp_path, '<node pkg="a" type="b" name="c"/>\n'
                                '<test test-name="one" pkg="p" type="t" time-limit="600"/>\n'
                                '<test test-name="two" pkg="p" type="t"/>')  # rostest's default 60 s
    assert run_tests.rostest_timeout(test_file) == 600 + 60 + run_tests.ROSTEST_SLACK_S


def test_every_suite_file_gets_more_than_its_longest_test():
    # bench_quick (time-limit 600) was killed at a fixed 420 s under load and reported as "unreadable results"
    for test_file in glob.glob(os.path.join(INTEGRATION, '*.test')):
        limits = [float(t.get('time-limit', 60)) for t in run_tests.ET.parse(test_file).getroot().iter('test')]
        assert run_tests.rostest_timeout(test_file) > sum(limits), test_file


def test_a_timeout_ends_the_whole_process_group(tmp_path):
    pid_file = tmp_path / 'child.pid'
    # a parent that ignores SIGINT and a child of it that sleeps: both must be gone after the guard fires
    script = 'trap "" INT; sleep 300 & echo $! > %s; wait' % pid_file
    with open(tmp_path / 'out.log', 'w') as out:
        start = time.monotonic()
        code = run_tests.run_bounded(['bash', '-c', script], out, timeout=1.0, grace=0.5)
    assert code == 'timeout after 1 s'
    assert time.monotonic() - start < 10
    child = int(pid_file.read_text())
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and os.path.exists('/proc/%d' % child):
        if open('/proc/%d/stat' % child).read().split()[2] == 'Z':
            break  # a zombie of an ended parent, reaped by init
        time.sleep(0.05)
    alive = os.path.exists('/proc/%d' % child) and open('/proc/%d/stat' % child).read().split()[2] != 'Z'
    assert not alive, 'the sleeping child outlived the guard'


def test_an_exit_code_is_returned_as_it_is(tmp_path):
    with open(tmp_path / 'out.log', 'w') as out:
        assert run_tests.run_bounded(['bash', '-c', 'exit 3'], out, timeout=30) == 3


def test_a_signal_is_returned_as_popen_returns_it(tmp_path):
    with open(tmp_path / 'out.log', 'w') as out:
        assert run_tests.run_bounded(['bash', '-c', 'kill -TERM $$'], out, timeout=30) == -15


def test_the_cpu_of_the_command_and_the_descendants_it_reaped_is_reported(tmp_path):
    # a grandchild (bash -> python) spins 0.4 s of CPU; the shell reaps it, so wait4 counts it for the command
    spin = 'import time\nt = time.process_time()\nwhile time.process_time() - t < 0.4:\n    pass\n'
    usage = {}
    with open(tmp_path / 'out.log', 'w') as out:
        code = run_tests.run_bounded(['bash', '-c', 'python3 -c "$0"; true', spin], out, timeout=30, usage=usage)
    assert code == 0
    assert 0.4 <= usage['cpu_s'] < 5.0, usage
