"""tools/run_tests.py --repeat: each test's failure count over the runs."""
import importlib.util
import os

SPEC = importlib.util.spec_from_file_location(
    'run_tests', os.path.join(os.path.dirname(__file__), '..', '..', '..', 'tools', 'run_tests.py'))
run_tests = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(run_tests)


def test_failures_are_counted_per_test_whatever_their_reason():
    runs = [
        ['robustness_input: t.test_03 -- hinge at 0.650 rad', 'unit: a.test_x -- boom'],
        [],
        ['robustness_input: t.test_03 -- hinge at 0.640 rad'],
    ]
    assert run_tests.failure_counts(runs) == [(2, 'robustness_input: t.test_03'), (1, 'unit: a.test_x')]


def test_a_test_failing_twice_in_one_run_counts_once():
    assert run_tests.failure_counts([['x: t.a -- one', 'x: t.a -- two']]) == [(1, 'x: t.a')]


def test_the_summary_names_each_failing_test_and_the_passing_runs():
    lines = run_tests.repeat_summary([['x: t.a -- why'], [], []], [10, 10, 10])
    assert '  1 of 3  x: t.a' in lines
    assert '  0 of 3  every other test (9 tests a run)' in lines
    assert lines[-1] == '2 of 3 runs passed'
    clean = run_tests.repeat_summary([[], []], [5, 5])
    assert '  0 of 2  every test (5 tests a run)' in clean and clean[-1] == '2 of 2 runs passed'

