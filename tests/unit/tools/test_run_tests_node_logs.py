"""tools/run_tests.py: a failed rostest's report carries the logs of the nodes roslaunch saw die, found from the
"log file:" pattern rostest writes into its summary XML (escaped twice, a colour code after the pattern, which
itself holds nothing escaped)."""
import importlib.util
import os

SPEC = importlib.util.spec_from_file_location(
    'run_tests', os.path.join(os.path.dirname(__file__), '..', '..', '..', 'tools', 'run_tests.py'))
run_tests = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(run_tests)


def test_the_logs_of_a_node_that_died_are_found_from_rostests_summary_xml(tmp_path):
    logs = tmp_path / 'ros_log' / 'run-1'
    logs.mkdir(parents=True)
    (logs / 'sdf_robot-1-stdout.log').write_text('Traceback (most recent call last):\nRuntimeError: x\n')
    (logs / 'sdf_robot-1.log').write_text('')  # empty: nothing to show
    (logs / 'other-1.log').write_text('not this node\n')
    results = tmp_path / 'results' / 'racebot_tests'
    results.mkdir(parents=True)
    pattern = str(logs / 'sdf_robot-1*.log')
    # as rostest writes it: the launch's coloured stderr line, XML-escaped inside a CDATA, escaped again
    (results / 'rostest-integration_sdf_robot.xml').write_text(
        '<testsuite><system-err>&lt;![CDATA[\n&amp;#x001B;[31m[sdf_robot-1] process has died [pid 5624, exit code 1, '
        'cmd /x/sdf_robot_test.py __name:=sdf_robot __log:=%s/sdf_robot-1.log].\nlog file: %s&amp;#x001B;[0m\n'
        ']]&gt;</system-err></testsuite>' % (logs, pattern))
    rostest_log = tmp_path / 'rostest-sdf_robot.log'
    rostest_log.write_text('SUMMARY\n * RESULT: FAIL\n')
    assert run_tests.died_node_logs(str(tmp_path / 'results'), str(rostest_log)) == [
        str(logs / 'sdf_robot-1-stdout.log')]


def test_no_died_node_no_logs(tmp_path):
    rostest_log = tmp_path / 'rostest-x.log'
    rostest_log.write_text('[ROSTEST] test [x] results summary: 0 errors, 1 failures, 3 tests\n')
    assert run_tests.died_node_logs(str(tmp_path), str(rostest_log)) == []
