"""tools/run_tests.py: rostest files run --jobs at a time, the long ones first, the bench and the soak alone."""
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


def test_long_files_start_first_and_solo_files_are_kept_apart():
    shared, solo = run_tests.rostest_order(files('a', 'bench_quick', 'faults', 'readme_drive', 'soak_short', 'z'))
    assert [run_tests.test_name(f) for f in shared] == ['readme_drive', 'faults', 'a', 'z']
    assert [run_tests.test_name(f) for f in solo] == ['bench_quick', 'soak_short']


def test_every_solo_and_long_name_is_a_rostest_file_of_the_suite():
    root = os.path.join(os.path.dirname(__file__), '..', '..', 'integration')
    present = {n[:-len('.test')] for n in os.listdir(root) if n.endswith('.test')}
    assert set(run_tests.SOLO + run_tests.LONG) <= present


def test_shared_files_overlap_solo_files_run_alone_and_every_result_is_added(monkeypatch):
    running, seen, lock = set(), [], threading.Lock()

    def fake_rostest(test_file):
        name = run_tests.test_name(test_file)
        with lock:
            seen.append((name, frozenset(running)))
            running.add(name)
        time.sleep(0.05)
        with lock:
            running.discard(name)
        return (1, 0, 0, []), '== rostest ' + name

    monkeypatch.setattr(run_tests, 'rostest_cases', fake_rostest)
    results = []
    run_tests.run_rostests(files('a', 'b', 'c', 'soak_short', 'bench_quick'), 2, results.append)
    assert len(results) == 5
    together = {name: others for name, others in seen}
    assert together['soak_short'] == frozenset() and together['bench_quick'] == frozenset()
    assert any(others for name, others in seen if name in ('a', 'b', 'c'))  # two lanes: some start beside another
