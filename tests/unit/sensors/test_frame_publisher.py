"""sensors/frame_publisher.FramePublisher: a camera's frames published in order on its own thread, so that the
render worker's reader thread only hands them over."""
import threading

from racebot_sim_bridge.sensors.frame_publisher import FramePublisher

WAIT = 10.0


def test_jobs_run_in_order_on_another_thread():
    done, threads = [], set()
    finished = threading.Event()
    publisher = FramePublisher('camera test')
    for k in range(200):
        publisher.run(lambda k=k: (done.append(k), threads.add(threading.get_ident())))
    publisher.run(finished.set)
    assert finished.wait(WAIT)
    assert done == list(range(200))
    assert threads and threading.get_ident() not in threads
    publisher.close()


def test_a_failing_job_is_logged_and_the_next_runs():
    errors, finished = [], threading.Event()
    publisher = FramePublisher('camera test', errors.append)
    publisher.run(lambda: 1 / 0)
    publisher.run(finished.set)
    assert finished.wait(WAIT)
    assert errors and 'ZeroDivisionError' in errors[0] and 'camera test' in errors[0]
    publisher.close()


def test_close_cancels_what_has_not_started():
    started, release = threading.Event(), threading.Event()
    ran, cancelled = [], []
    publisher = FramePublisher('camera test')
    publisher.run(lambda: (started.set(), release.wait(WAIT)))
    assert started.wait(WAIT)
    for k in range(3):
        publisher.run(lambda k=k: ran.append(k), cancel=lambda k=k: cancelled.append(k))
    publisher.close()
    release.set()
    publisher._thread.join(WAIT)
    assert not publisher._thread.is_alive()
    assert ran == [] and cancelled == [0, 1, 2]  # every frame buffer given back, none published
    assert publisher.run(lambda: ran.append('late'), cancel=lambda: cancelled.append('late')) is False
    assert cancelled[-1] == 'late' and not ran


def test_a_slow_camera_does_not_hold_up_another():
    slow_started, release, fast_done = threading.Event(), threading.Event(), threading.Event()
    slow, fast = FramePublisher('camera slow'), FramePublisher('camera fast')
    slow.run(lambda: (slow_started.set(), release.wait(WAIT)))
    assert slow_started.wait(WAIT)
    fast.run(fast_done.set)  # the reader thread hands both over and goes on
    assert fast_done.wait(WAIT)
    release.set()
    slow.close()
    fast.close()
