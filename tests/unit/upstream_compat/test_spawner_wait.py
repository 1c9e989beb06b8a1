"""The spawner's wait for the controller manager: its --timeout counts from when the simulator's time
started, so a /clock that arrives near the end of a wait begun before it does not cut the robot's spawn
short (robustness_world test_4 failed so under load). A fake rospy; no master."""
import argparse

import pytest

from controller_manager import spawner


class ROSException(Exception):
    pass


class ROSInterruptException(ROSException):
    pass


class FakeRospy:
    """The simulated time is 0 until the first wait times out; the service appears during the
    `service_on_wait`-th wait (None: never)."""
    ROSException = ROSException
    ROSInterruptException = ROSInterruptException

    def __init__(self, service_on_wait):
        self.service_on_wait = service_on_wait
        self.waits = 0
        self.time = 0.0
        self.logs = []

    def wait_for_service(self, name, timeout=None):
        self.waits += 1
        if self.waits == 1:
            self.time = 0.5  # the simulator starts near the end of the first wait
        if self.service_on_wait is not None and self.waits >= self.service_on_wait:
            return
        raise ROSException('timeout exceeded while waiting for service %s' % name)

    def get_time(self):
        return self.time

    def get_param(self, name, default=None):
        return {'/use_sim_time': True}.get(name, default)

    def is_shutdown(self):
        return self.waits > 5

    def resolve_name(self, name):
        return '/racebot/' + name.lstrip('/')

    def get_namespace(self):
        return '/racebot/'

    def get_name(self):
        return '/racebot/spawner'

    def loginfo(self, msg, *args):
        self.logs.append(('info', msg % args if args else msg))

    logwarn = loginfo

    def logerr(self, msg, *args):
        self.logs.append(('error', msg % args if args else msg))


def make(fake):
    options = argparse.Namespace(timeout=10.0, no_timeout=False, namespace=None, stopped=False,
                                 wait_for=None, shutdown_timeout=None, controllers=['c'])
    s = spawner.Spawner.__new__(spawner.Spawner)
    s.rospy, s.options, s.timeout = fake, options, spawner.startup_timeout(options)
    return s


def test_a_full_timeout_after_the_simulator_time_started():
    fake = FakeRospy(service_on_wait=2)
    assert make(fake).wait_for_service('controller_manager/load_controller')
    assert fake.waits == 2
    assert not [m for level, m in fake.logs if level == 'error']


def test_still_gives_up_a_full_timeout_after_the_time_started():
    fake = FakeRospy(service_on_wait=None)
    assert not make(fake).wait_for_service('controller_manager/load_controller')
    assert fake.waits == 2
    assert any(level == 'error' and "couldn't find" in m for level, m in fake.logs)


if __name__ == '__main__':
    pytest.main([__file__])
