"""The topics_agree check: two topics of one message type, published by two implementations of the same plugin
(racebot's Python one and a package's build of upstream's C++ source) on one robot, agree field by field on the
messages of equal header stamps. `differences` is pure (no ROS): tests/unit/tools/test_corpus_topics_agree.py tests it.
"""
import math
import time

from corpus.ros_io import WALL_MARGIN_S, CheckFailed


def fields(msg, prefix=''):
    """[(dotted field name, value)] of a ROS message's leaves (numbers and strings), arrays by index."""
    if hasattr(msg, '__slots__'):
        out = []
        for name in msg.__slots__:
            out += fields(getattr(msg, name), prefix + name + '.')
        return out
    if isinstance(msg, (list, tuple)):
        out = []
        for i, value in enumerate(msg):
            out += fields(value, '%s%d.' % (prefix, i))
        return out
    return [(prefix[:-1], msg)]


# filled in by each publisher's transport, not by the plugin: a count of what that publisher sent so far
TRANSPORT_FIELDS = ('header.seq',)
# the time a message is of, which moves in every stream: no sign that the body did
STAMP_FIELDS = ('header.stamp.secs', 'header.stamp.nsecs')


def differences(a, b):
    """(the largest absolute difference of two messages' numeric fields and the field it is in, [the fields whose
    other values differ: strings, lengths, a NaN on one side only]); TRANSPORT_FIELDS are not compared."""
    fa, fb = ([f for f in fields(m) if f[0] not in TRANSPORT_FIELDS] for m in (a, b))
    if [name for name, _ in fa] != [name for name, _ in fb]:
        return 0.0, '', ['the field lists differ (%d against %d fields)' % (len(fa), len(fb))]
    largest, where, other = 0.0, '', []
    for (name, x), (_, y) in zip(fa, fb):
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not isinstance(y, (int, float)):
            if x != y:
                other.append('%s: %r against %r' % (name, x, y))
        elif math.isnan(x) or math.isnan(y):
            if not (math.isnan(x) and math.isnan(y)):
                other.append('%s: %r against %r' % (name, x, y))
        elif abs(x - y) > largest:
            largest, where = abs(x - y), name
    return largest, where, other


def moving_fields(messages):
    """The numeric fields whose values are not the same in every one of `messages`."""
    columns = {}
    for msg in messages:
        for name, value in fields(msg):
            if name not in TRANSPORT_FIELDS + STAMP_FIELDS and isinstance(value, (int, float)) \
                    and not isinstance(value, bool):
                columns.setdefault(name, set()).add(value)
    return sorted(name for name, values in columns.items() if len(values) > 1)


def check_topics_agree(check, row):
    """`messages` pairs of equal stamps from `topics` (two, of `type`), within `timeout` s of wall time (default
    60); every numeric field within `tolerance` of the other's, every other field equal."""
    import rospy
    from roslib.message import get_message_class
    cls = get_message_class(check['type'])
    if cls is None:
        raise CheckFailed('no message type %s' % check['type'], '')
    first, second = check['topics']
    wanted, tolerance = int(check['messages']), float(check['tolerance'])
    seen = ({}, {})

    def keep(k):
        return lambda msg: seen[k].setdefault(msg.header.stamp.to_nsec(), msg)
    subs = [rospy.Subscriber(topic, cls, keep(k), queue_size=100) for k, topic in enumerate((first, second))]
    deadline = time.time() + float(check.get('timeout', 60)) + WALL_MARGIN_S
    try:
        while time.time() < deadline and len(set(seen[0]) & set(seen[1])) < wanted:
            time.sleep(0.2)
    finally:
        for sub in subs:
            sub.unregister()
    stamps = sorted(set(seen[0]) & set(seen[1]))[:wanted]
    counts = '%d and %d messages, %d of equal stamps' % (len(seen[0]), len(seen[1]), len(stamps))
    if len(stamps) < wanted:
        raise CheckFailed('%s and %s gave %d messages of equal stamps, the row expects %d' % (
            first, second, len(stamps), wanted), counts)
    varied = moving_fields([seen[0][stamp] for stamp in stamps])
    counts += '; %d numeric fields change over them' % len(varied)
    if not varied:
        raise CheckFailed('%s never changed over %d messages: the agreement says nothing of motion' % (
            first, len(stamps)), counts)
    largest, where, other = 0.0, '', []
    for stamp in stamps:
        diff, field, others = differences(seen[0][stamp], seen[1][stamp])
        other += others
        if diff > largest:
            largest, where = diff, field
    numbers = '%s against %s: %s; largest difference %.3g%s' % (
        first, second, counts, largest, ' (%s)' % where if where else '')
    if other:
        raise CheckFailed('%s and %s differ in %s' % (first, second, '; '.join(sorted(set(other))[:3])), numbers)
    if largest > tolerance:
        raise CheckFailed('%s and %s differ by %.3g in %s (tolerance %g)' % (first, second, largest, where,
                                                                              tolerance), numbers)
    return numbers
