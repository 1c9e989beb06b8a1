"""tools/run_tests.py: rostest files run --rostest-jobs at a time, the long ones first."""
import importlib.util
import os
import threading
import time

SPEC = importlib.util.spec_from_file_location(
    'run_tests', os.path.join(os.path.dirname(__file__), '..', '..', '..', 'tools', 'run_tests.py'))
run_tests = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(run_tests)


def files(*names):
    return ['/r/tests/integration/%s.test' % n for n in names]


def test_long_files_start_first():
    order = run_tests.rostest_order(files('a', 'bench_quick', 'faults', 'readme_drive', 'soak_short', 'z'))
    assert [run_tests.test_name(f) for f in order] == ['bench_quick', 'soak_short', 'readme_drive', 'faults', 'a', 'z']


def test_every_long_name_is_a_rostest_file_of_the_suite():
    root = os.path.join(os.path.dirname(__file__), '..', '..', 'integration')
    present = {n[:-len('.test')] for n in os.listdir(root) if n.endswith('.test')}
    assert set(run_tests.LONG) <= present


def test_files_run_two_at_a_time_and_every_result_is_added(monkeypatch):
    running, most, lock = set(), [0], threading.Lock()

    def fake_rostest(test_file):
        name = run_tests.test_name(test_file)
        with lock:
            running.add(name)
            most[0] = max(most[0], len(running))
        time.sleep(0.05)
        with lock:
            running.discard(name)
        return (1, 0, 0, []), '== rostest ' + name

    monkeypatch.setattr(run_tests, 'rostest_cases', fake_rostest)
    results = []
    run_tests.run_rostests(files('a', 'b', 'c', 'd', 'e'), 2, results.append)
    assert len(results) == 5 and most[0] == 2
    most[0] = 0
    run_tests.run_rostests(files('a', 'b', 'c'), 1, results.append)
    assert len(results) == 8 and most[0] == 1
