#!/usr/bin/env python3
"""Runs racebot's whole test suite and ends with one line `N passed, N failed[, N skipped]`.

`--repeat N` runs it (or the part -k / --unit-only picks) N times and ends with each test's
failure count over the N runs: the way to tell a flaky test (fails 1 of 10) from a broken one.

Three tiers: ruff over the repository (one test), pytest unit tests in tests/unit (no ROS master)
and every rostest file in tests/integration (each brings up its own master, roslaunch and nodes), --jobs pytest
workers (default 2) and --rostest-jobs rostest files (default one more) at a time. Results are counted
from the JUnit XML both write, so a test node that crashes or never reports counts as failed.
Run it from a shell where `devel/setup.bash` is sourced (the Makefile does that).
"""
import argparse
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, 'out', 'test-results')
# A hang guard around one rostest file, beyond the time-limits of its test nodes (rostest runs them one after another
# and stops each at its own time-limit, default 60 s): its master, the launch of its nodes and their teardown.
# Never tighter than the tests' own limits: a guard that fires first kills rostest before its test node has written
# its results, and reports a slow test as "unreadable results" (bench_quick at a load of 8).
ROSTEST_SLACK_S = 120
ROSTEST_DEFAULT_TIME_LIMIT_S = 60.0
WAIT_POLL_S = 0.1  # how often run_bounded looks whether its command ended (wait4 has no timeout)
# pytest's workers: JOBS, one per core (the unit tests are CPU-bound). Rostest files run JOBS + 1 at a time: each
# brings up a master of its own on a free port (rostest's port 0), its own Xvfb (-displayfd), temporary folders and
# render buffers, and most of a file's time is spent waiting for sim time at real time (a world server then takes
# about half a core, make bench), so on a 2-core machine two at once took 830 s of the serial 1520 and three 678 s
# (2026-12-03). Every test bounds its waits in wall time generously: a test that fails because others run beside it
# is a defect of that test, as on a busy CI host.
JOBS = int(os.environ.get('RACEBOT_TEST_JOBS', '2'))
# Started first, longest first: each takes a minute or more; started last, one would leave a lane running alone at
# the end. The bench's quick run and the soak (both as fast as possible) run beside others: neither judges a timing
# (bench_quick_test checks that figures exist, the soak reads memory at rest), so a test beside them changes only
# how long they take; readme_drive, at real time, is the third of the first three.
LONG = ('bench_quick', 'soak_short', 'readme_drive', 'shutdown_stress', 'compiled_plugins', 'robustness_input',
        'robustness_world', 'racebot_launch', 'viewer', 'faults')
# The corpus of public packages (make corpus) needs the network or clones; the suite never runs it.
CORPUS_NOT_RUN = 'corpus: not run here (no network/clones; make corpus; the last table is docs/CORPUS.md)'


def use_loopback_ros_networking(env):
    """Puts ROS networking in `env` (a dict, or os.environ) on loopback: every node of the suite runs here.

    Without ROS_HOSTNAME or ROS_IP, each node advertises the machine's host name, and roslaunch and
    rostest fail where that name does not resolve (a common container set-up): "Unable to contact my
    own server", "cannot resolve host address for machine [localhost]". Only the suite's processes get
    this; `make run` leaves a user's networking as it is.
    """
    for name in ('ROS_IP', 'ROS_IPV6'):  # a user's address for other machines has no use here
        env.pop(name, None)
    env['ROS_HOSTNAME'] = 'localhost'
    env['ROS_MASTER_URI'] = 'http://localhost:11311'  # rostest starts its own master on a free port
    return env


def failure_reason(element, limit=300):
    """' -- ' and the first line of a JUnit failure's message (or of its text), cut to `limit`."""
    text = (element.get('message') or element.text or '').strip()
    line = text.splitlines()[0] if text else ''
    if not line:
        return ''
    return ' -- ' + (line if len(line) <= limit else line[:limit - 3] + '...')


def count_junit(path):
    """(passed, failed, skipped, failures) of one JUnit XML file; a failure is the case's name and
    the first line of its message, so the summary at the end of a CI log says why, not only what."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as err:
        return 0, 1, 0, ['%s: unreadable results (%s)' % (os.path.relpath(path, OUT), err)]
    passed = failed = skipped = 0
    failures = []
    for case in root.iter('testcase'):
        name = '%s.%s' % (case.get('classname', ''), case.get('name', ''))
        bad = case.find('failure')
        if bad is None:
            bad = case.find('error')
        if bad is not None:
            failed += 1
            failures.append(name + failure_reason(bad))
        elif case.find('skipped') is not None:
            skipped += 1
        else:
            passed += 1
    return passed, failed, skipped, failures


def run_unit(python, jobs=1):
    xml = os.path.join(OUT, 'unit.xml')
    cmd = [python, '-m', 'pytest', os.path.join(ROOT, 'tests', 'unit'), '-q', '-p', 'no:cacheprovider',
           '--junitxml', xml]
    if jobs > 1:  # pytest-xdist: the unit tests are CPU-bound, one worker per core
        cmd += ['-n', str(jobs)]
    print('== unit tests: %s' % ' '.join(cmd), flush=True)
    code = subprocess.call(cmd, cwd=ROOT)
    if not os.path.exists(xml):
        return 0, 1, 0, ['pytest exited %d without results' % code]
    result = count_junit(xml)
    if code not in (0, 1) and result[1] == 0:  # collection/usage errors: pytest wrote no failing case
        return result[0], result[1] + 1, result[2], result[3] + ['pytest exited %d' % code]
    return result


def run_lint(python):
    """ruff over the repository (ruff.toml: one line length, pycodestyle and pyflakes): one test,
    failed with ruff's findings."""
    cmd = [python, '-m', 'ruff', 'check', '--no-cache', '--output-format', 'concise', ROOT]
    print('== lint: %s' % ' '.join(cmd), flush=True)
    done = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode == 0:
        print('   ruff: no findings', flush=True)
        return 1, 0, 0, []
    findings = [line for line in done.stdout.splitlines() if line.strip()]
    print('\n'.join('   ' + line for line in findings), flush=True)
    return 0, 1, 0, ['lint: ruff reported %d finding(s) (run `make lint`; fix them)' % max(len(findings) - 1, 1)]


def rostest_timeout(test_file):
    """Wall seconds one rostest file may take: its test nodes' time-limits, one after another, and the slack."""
    tests = ET.parse(test_file).getroot().iter('test')
    return sum(float(t.get('time-limit', ROSTEST_DEFAULT_TIME_LIMIT_S)) for t in tests) + ROSTEST_SLACK_S


# The process groups of the rostests under way: each runs in a session of its own (so that a timeout can end all of
# it), which also keeps a Ctrl-C at the terminal from reaching it, so the runner passes an interrupt on itself.
_RUNNING = set()
_RUNNING_LOCK = threading.Lock()


def end_group(proc, grace):
    """SIGINT to proc's process group (roslaunch's and rostest's own teardown), then after at most `grace` s
    SIGKILL to whatever is left of it."""
    try:
        os.killpg(proc.pid, signal.SIGINT)
    except ProcessLookupError:
        return
    try:
        proc.wait(timeout=grace)
    except subprocess.TimeoutExpired:
        pass
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # what outlived the teardown (or rostest itself, if it hung)
    except ProcessLookupError:
        pass
    proc.wait()


def run_bounded(cmd, out, timeout, grace=15.0, usage=None):
    """Runs cmd in a session of its own with output to `out`; its exit code, or 'timeout after N s' when it ran
    past `timeout` and its whole process group (rostest, its master, roslaunch and test nodes) was ended.
    `usage`, a dict, gets 'cpu_s': the user and system CPU seconds of cmd and of every descendant reaped below it
    (rostest reaps its nodes, they reap theirs), from wait4: what a test costs the machine, whatever runs beside."""
    proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
    with _RUNNING_LOCK:
        _RUNNING.add(proc)
    deadline = time.monotonic() + timeout
    try:
        while True:
            pid, status, rusage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                proc.returncode = os.waitstatus_to_exitcode(status)
                if usage is not None:
                    usage['cpu_s'] = rusage.ru_utime + rusage.ru_stime
                return proc.returncode
            if time.monotonic() >= deadline:
                end_group(proc, grace)
                return 'timeout after %d s' % timeout
            time.sleep(WAIT_POLL_S)
    finally:
        with _RUNNING_LOCK:
            _RUNNING.discard(proc)


def end_running(grace=15.0):
    """Ends every rostest under way (the runner was interrupted)."""
    with _RUNNING_LOCK:
        running = list(_RUNNING)
    for proc in running:
        end_group(proc, grace)


def rostest_cases(test_file):
    """Runs one rostest file; counts the test cases its test nodes report.

    Each test node writes rosunit-<test-name>.xml with its cases; rostest's own summary file
    (rostest-*.xml) has one case per node and marks a node that crashed or wrote nothing.
    """
    name = test_name(test_file)
    results_dir = os.path.join(OUT, name)
    cmd = ['rostest', '--results-base-dir', results_dir, '--package', 'racebot_tests', test_file]
    report = ['== rostest %s' % os.path.relpath(test_file, ROOT)]
    start = time.time()
    log = os.path.join(OUT, 'rostest-%s.log' % name)
    usage = {}
    with open(log, 'w') as out:
        code = run_bounded(cmd, out, rostest_timeout(test_file), usage=usage)
    passed = failed = skipped = 0
    failures = []
    for xml in sorted(glob.glob(os.path.join(results_dir, '**', 'rosunit-*.xml'), recursive=True)):
        p, f, s, names = count_junit(xml)
        passed, failed, skipped = passed + p, failed + f, skipped + s
        failures += ['%s: %s' % (name, n) for n in names]
    if failed == 0:  # node-level failures (a test node that crashed or reported nothing)
        for xml in glob.glob(os.path.join(results_dir, '**', 'rostest-*.xml'), recursive=True):
            _, f, _, names = count_junit(xml)
            failed += f
            failures += ['%s: %s' % (name, n) for n in names]
    if (code != 0 and failed == 0) or passed + failed + skipped == 0 or isinstance(code, str):
        failed += 1
        failures.append('%s: rostest exited %s' % (name, code))
    report.append('   %d passed, %d failed in %.0f s, %s CPU s (log: %s)'
                  % (passed, failed, time.time() - start, '%.0f' % usage['cpu_s'] if 'cpu_s' in usage else '?',
                     os.path.relpath(log, ROOT)))
    if failures:
        with open(log) as f:
            tail = f.read()[-4000:]
        report.append('   --- last lines of the log ---\n' + tail)
        for path in died_node_logs(results_dir, log):
            with open(path, errors='replace') as f:
                report.append('   --- last lines of %s ---\n%s' % (os.path.relpath(path, ROOT), f.read()[-3000:]))
    return (passed, failed, skipped, failures), '\n'.join(report)


DIED_LOG = re.compile(r'process has died \[[^\]]*\]\.\s+log file: (\S+?\.log)')


def died_node_logs(results_dir, log):
    """The log files of the nodes roslaunch saw die (its "process has died [...]. log file: PATTERN", in rostest's
    output or its summary XML): a test node's traceback is there, not in rostest's output, and the run's ROS_LOG_DIR
    may be gone with its clone by the time anybody reads the report."""
    texts = []
    for path in [log] + glob.glob(os.path.join(results_dir, '**', 'rostest-*.xml'), recursive=True):
        with open(path, errors='replace') as f:
            texts.append(f.read())
    found = []
    for pattern in DIED_LOG.findall('\n'.join(texts)):
        for path in sorted(glob.glob(pattern)):
            if path not in found and os.path.getsize(path):
                found.append(path)
    return found


def test_name(test_file):
    return os.path.splitext(os.path.basename(test_file))[0]


def rostest_order(test_files):
    """The rostest files in the order they start: the LONG ones first, then the others as given."""
    rank = {name: i for i, name in enumerate(LONG)}
    return sorted(test_files, key=lambda f: rank.get(test_name(f), len(LONG)))


def run_rostests(test_files, jobs, add):
    """Runs the rostest files `jobs` at a time; hands each result to `add` and prints each file's report whole, as
    it ends (the reports of files that run together never interleave)."""
    lock = threading.Lock()

    def run(test_file):
        result, report = rostest_cases(test_file)
        with lock:
            print(report, flush=True)
            add(result)

    with ThreadPoolExecutor(max(1, jobs)) as pool:
        futures = [pool.submit(run, f) for f in rostest_order(test_files)]
        try:
            for done in futures:
                done.result()
        except BaseException:  # Ctrl-C or SIGTERM (main): the rostests run in sessions of their own (run_bounded)
            for future in futures:
                future.cancel()
            end_running()
            raise


def failed_test(failure):
    """The test a failure line names, without its reason: the key failures are counted by."""
    return failure.split(' -- ', 1)[0]


def failure_counts(runs):
    """[(failures, test)] over `runs` (one list of failure lines per run), most failures first;
    a test that failed twice in one run counts once."""
    counts = {}
    for failures in runs:
        for test in set(failed_test(f) for f in failures):
            counts[test] = counts.get(test, 0) + 1
    return sorted(((n, test) for test, n in counts.items()), key=lambda item: (-item[0], item[1]))


def repeat_summary(runs, tests_per_run):
    """The lines `--repeat` ends with: each failing test's count, then the runs' totals."""
    n = len(runs)
    lines = ['', '== %d runs: failures per test' % n]
    counted = failure_counts(runs)
    for failures, test in counted:
        lines.append('  %d of %d  %s' % (failures, n, test))
    lines.append('  0 of %d  every other test (%d tests a run)' % (n, max(tests_per_run or [0]) - len(counted))
                 if counted else '  0 of %d  every test (%d tests a run)' % (n, max(tests_per_run or [0])))
    lines.append('%d of %d runs passed' % (sum(1 for failures in runs if not failures), n))
    return lines


def stray_packages(root):
    """Package folders catkin finds in the source space `root` that the repository does not hold (a test's or the
    bench's generated package under out/ would stop the next `catkin_make`: 'does not contain a CMakeLists.txt')."""
    from catkin_pkg.packages import find_package_paths
    try:
        tracked = subprocess.run(['git', '-C', root, 'ls-files', '*package.xml'], capture_output=True, text=True,
                                 check=True).stdout.split()
        ours = {os.path.dirname(path) for path in tracked}
    except (OSError, subprocess.CalledProcessError):  # not a git checkout: only the folders we write are suspect
        ours = None
    found = find_package_paths(root)
    if ours is None:
        return sorted(path for path in found if path.split(os.sep)[0] in ('out', 'build', 'devel'))
    return sorted(path for path in found if path not in ours)


def check_source_space():
    """One test: after the suite, catkin still finds only the repository's packages, so `make run` (or any
    catkin_make) after `make test` builds. (passed, failed, skipped, failures) as count_junit gives them."""
    stray = stray_packages(ROOT)
    if stray:
        return 0, 1, 0, ['source space: packages written by the suite where catkin looks: ' + ', '.join(stray)]
    return 1, 0, 0, []


def main():
    global OUT
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--unit-only', action='store_true', help='only the unit tests')
    parser.add_argument('-k', dest='only', help='only the rostest files whose name contains this')
    parser.add_argument('--repeat', type=int, default=1, metavar='N',
                        help='run N times; end with each test\'s failure count')
    parser.add_argument('--out', default=OUT, help='results directory (emptied first; default %(default)s)')
    parser.add_argument('--jobs', '-j', type=int, default=JOBS, metavar='N',
                        help='pytest workers (default %(default)s, or RACEBOT_TEST_JOBS); rostest files run N + 1 at '
                             'a time unless --rostest-jobs says otherwise')
    parser.add_argument('--rostest-jobs', type=int, metavar='N', help='rostest files at a time (default: --jobs + 1)')
    args = parser.parse_args()
    if args.rostest_jobs is None:
        args.rostest_jobs = args.jobs + 1
    if args.repeat < 1:
        parser.error('--repeat N needs N >= 1, got %d' % args.repeat)
    if args.jobs < 1:
        parser.error('--jobs N needs N >= 1, got %d (RACEBOT_TEST_JOBS?)' % args.jobs)
    if args.rostest_jobs < 1:
        parser.error('--rostest-jobs N needs N >= 1, got %d' % args.rostest_jobs)
    # SIGTERM as an exception in the main thread, as Ctrl-C is: run_rostests then ends the rostests under way
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(128 + signum))
    if 'ROS_PACKAGE_PATH' not in os.environ or ROOT not in os.environ['ROS_PACKAGE_PATH']:
        sys.exit('racebot: source devel/setup.bash first (or use `make test`)')
    use_loopback_ros_networking(os.environ)
    os.makedirs(os.path.join(ROOT, 'out'), exist_ok=True)  # out/ is no part of the source space (Makefile: build)
    open(os.path.join(ROOT, 'out', 'CATKIN_IGNORE'), 'a').close()
    os.environ.setdefault('ROS_LOG_DIR', os.path.join(ROOT, 'out', 'ros_log'))
    base = os.path.abspath(args.out)
    runs, tests_per_run = [], []
    for run in range(args.repeat):
        OUT = base if args.repeat == 1 else os.path.join(base, 'run-%d' % (run + 1))
        if args.repeat > 1:
            print('\n==== run %d of %d' % (run + 1, args.repeat), flush=True)
        totals, failures = run_once(args)
        runs.append(failures)
        tests_per_run.append(sum(totals))
    if args.repeat > 1:
        print('\n'.join(repeat_summary(runs, tests_per_run)))
    sys.exit(0 if not any(runs) and all(tests_per_run) else 1)


def run_once(args):
    """One run of the tests `args` pick, into OUT: ([passed, failed, skipped], failure lines)."""
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    totals = [0, 0, 0]
    failures = []

    def add(result):
        for i in range(3):
            totals[i] += result[i]
        failures.extend(result[3])

    if not args.only:
        add(run_lint(sys.executable))
        add(run_unit(sys.executable, args.jobs))
    if not args.unit_only:
        test_files = [f for f in sorted(glob.glob(os.path.join(ROOT, 'tests', 'integration', '*.test')))
                      if not args.only or args.only in os.path.basename(f)]
        run_rostests(test_files, args.rostest_jobs, add)
    if not args.only and not args.unit_only:
        add(check_source_space())
    print(CORPUS_NOT_RUN, flush=True)
    if failures:
        print('\nfailed:\n  ' + '\n  '.join(failures))
    line = '%d passed, %d failed' % (totals[0], totals[1])
    if totals[2]:
        line += ', %d skipped' % totals[2]
    print(line, flush=True)
    if totals[0] == 0 and not failures:
        failures.append('no test ran')
    return totals, failures


if __name__ == '__main__':
    main()
