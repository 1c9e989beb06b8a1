"""The arithmetic of the corpus's flight check (checks.check_flight): a flying robot's height log, sampled from
the ground truth as (sim time, z), cut into its phases and judged against what the robot's own controllers say.

Pure functions, no ROS: tests/unit/tools/test_corpus_flight.py."""


def rate(samples, start, end):
    """The least-squares slope dz/dt (m/s) of the samples with start <= t <= end; None with fewer than 3."""
    window = [(t, z) for t, z in samples if start <= t <= end]
    if len(window) < 3:
        return None
    n = len(window)
    mt = sum(t for t, _ in window) / n
    mz = sum(z for _, z in window) / n
    var = sum((t - mt) ** 2 for t, _ in window)
    if var <= 0.0:
        return None
    return sum((t - mt) * (z - mz) for t, z in window) / var


def height_at(samples, t):
    """z linearly interpolated at sim time t; None outside the log."""
    for (t0, z0), (t1, z1) in zip(samples, samples[1:]):
        if t0 <= t <= t1:
            return z0 if t1 == t0 else z0 + (z1 - z0) * (t - t0) / (t1 - t0)
    return None


def estop_drop(deceleration, seconds):
    """How far a robot hovering on thrust m*g falls in `seconds` once its thrust ramps down at
    `deceleration` * m per second (hector_quadrotor's AttitudeController estop: thrust -= estop_deceleration * mass
    * period each update): its downward acceleration is deceleration * t, so the drop is deceleration * t^3 / 6.
    Drag and the motors' lag make the real drop a little smaller."""
    return deceleration * seconds ** 3 / 6.0
