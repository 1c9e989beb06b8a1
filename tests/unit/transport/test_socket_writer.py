"""socket_writer.pyx, the compiled writer thread, and queued_publishing's use of it (start_writer, write_data's
writer path, _run closing the channel), over real socket pairs and rospy's own QueuedConnection and
TCPROSTransport. The writer is driven pass by pass with pass_once() (its thread not started) wherever the order of
events matters, so nothing here depends on timing; the Python path (no writer) is the reference for what a
subscriber receives."""
import errno
import os
import socket
import struct
import subprocess
import sys
import sysconfig
import threading
import time

import pytest
from hypothesis import given, settings, strategies as st

from racebot_sim_bridge.transport import queued_publishing
from racebot_sim_bridge.transport.socket_writer import SocketWriter

from queued_transports import close, socket_connection

SMALL_BUFFER = 4096  # SO_SNDBUF of a sender that takes only part of a big message (the kernel doubles it)


def framed(index, size):
    """A message as rospy writes one (a 4-byte length, then the body): its body is its index and `size` bytes
    that depend on the index, so a cut, a mix or a swap of two messages shows."""
    body = struct.pack('<I', index) + bytes((index + k) % 251 for k in range(size))
    return struct.pack('<I', len(body)) + body


def unframed(stream):
    """The indices of the whole messages `stream` is made of; fails on a cut or garbled message."""
    indices, at = [], 0
    while at < len(stream):
        assert at + 4 <= len(stream), 'a message cut in its length'
        (length,) = struct.unpack_from('<I', stream, at)
        body = stream[at + 4:at + 4 + length]
        assert len(body) == length, 'a message cut: %d of its %d bytes' % (len(body), length)
        (index,) = struct.unpack_from('<I', body)
        assert stream[at:at + 4 + length] == framed(index, length - 4), 'message %d garbled' % index
        indices.append(index)
        at += 4 + length
    return indices


def pair(buffer=None):
    """(sender, peer): a connected socket pair; `buffer`: the sender's SO_SNDBUF. The peer never blocks."""
    sender, peer = socket.socketpair()
    if buffer:
        sender.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, buffer)
    peer.setblocking(False)
    return sender, peer


def available(peer, limit=None):
    """What the peer can read now (at most `limit` bytes); b'' at EOF or when nothing waits."""
    got = bytearray()
    while limit is None or len(got) < limit:
        try:
            chunk = peer.recv(1 << 16 if limit is None else min(1 << 16, limit - len(got)))
        except BlockingIOError:
            break
        if not chunk:
            break
        got += chunk
    return bytes(got)


def pump(writer, channel, peer, passes=100000):
    """Passes of the writer, the peer reading between them, until the channel has nothing waiting: what the peer
    read meanwhile."""
    got = bytearray()
    for _ in range(passes):
        writer.pass_once()
        got += available(peer)
        if writer.waiting(channel) == 0:
            return bytes(got + available(peer))
    raise AssertionError('%d messages still waiting after %d passes' % (writer.waiting(channel), passes))


def rospy_connection(queue_size, buffer=None):
    """(QueuedConnection, TCPROSTransport, peer): rospy's own publisher side of one subscriber, over a socket pair,
    with queued_publishing's write_data and _run."""
    from rospy.impl.tcpros_base import TCPROSTransport, TCPROSTransportProtocol
    sender, peer = pair(buffer)
    transport = TCPROSTransport(TCPROSTransportProtocol('/chatter', None), '/chatter')
    transport.set_socket(sender, '/listener')
    return queued_publishing.install()(transport, queue_size), transport, peer


def end(conn):
    """rospy closing the connection: the transport's close ends QueuedConnection's thread."""
    conn._connection.close()
    conn._thread.join(5.0)
    assert not conn._thread.is_alive()


@pytest.fixture
def writer():
    """The process's writer (queued_publishing hands the connections' messages to it), its thread not started:
    the test makes its passes."""
    assert queued_publishing._writer[0] is None
    w = SocketWriter()
    queued_publishing._writer[0] = w
    yield w
    queued_publishing._writer[0] = None
    w.stop()


def copies(sock):
    """How many of this process's file descriptors are the socket `sock` (itself and its dups)."""
    link = os.readlink('/proc/self/fd/%d' % sock.fileno())
    return sum(1 for fd in os.listdir('/proc/self/fd') if _link('/proc/self/fd/' + fd) == link)


def _link(path):
    try:
        return os.readlink(path)
    except OSError:  # listdir's own descriptor, closed meanwhile
        return None


def test_the_build_compiled_the_socket_writer():
    # without it the world server sends from its update loop (start_writer returns None): slower, not wrong
    import racebot_sim_bridge.transport.socket_writer as module
    assert module.__file__.endswith(sysconfig.get_config_var('EXT_SUFFIX')), module.__file__


MESSAGES = [framed(i, size) for i, size in enumerate([0, 10, 300000, 1, 5000, 70000, 3, 200000, 17])]


def test_what_arrives_is_what_the_python_path_delivers_in_order_and_whole(writer):
    total = sum(map(len, MESSAGES))
    # the reference: the Python path (no writer), rospy's thread sending what the socket did not take at once
    queued_publishing._writer[0] = None
    conn, transport, peer = rospy_connection(0, SMALL_BUFFER)
    try:
        for message in MESSAGES:
            conn.write_data(message)
        peer.setblocking(True)
        peer.settimeout(10.0)
        reference = b''
        while len(reference) < total:
            reference += peer.recv(1 << 16)
        # rospy's thread counts a message after its send returns, which may be after the peer has the bytes: the
        # counts are final once it has gone back to waiting (nothing queued, nothing in hand)
        deadline = time.monotonic() + 10.0
        while time.monotonic() < deadline:
            with conn._lock:
                if not conn._queue and not conn._sending:
                    break
            time.sleep(0.001)
        python_stats = (transport.stat_bytes, transport.stat_num_msg)
    finally:
        end(conn)
    assert reference == b''.join(MESSAGES)
    # the writer's path, over the same kind of socket
    queued_publishing._writer[0] = writer
    conn, transport, peer = rospy_connection(0, SMALL_BUFFER)
    try:
        for message in MESSAGES:
            conn.write_data(message)
        assert conn._channel is not None and conn._queue == []  # all handed to the writer, none to rospy's thread
        received = pump(writer, conn._channel[1], peer)
        assert received == reference
        assert unframed(received) == list(range(len(MESSAGES)))
        assert (transport.stat_bytes, transport.stat_num_msg) == python_stats
    finally:
        end(conn)


def test_messages_rospys_thread_has_in_hand_are_never_passed_by_the_writer(writer):
    # the writer appears (or a connection has no channel yet) while the Python path has the rest of a message
    # queued or in rospy's thread: the next messages must follow it, not go to the writer ahead of it
    queued_publishing._writer[0] = None
    conn, transport, peer = rospy_connection(0, SMALL_BUFFER)
    try:
        big = framed(0, 300000)
        conn.write_data(big)  # part sent at once, the rest for rospy's thread, which blocks: the peer reads nothing
        queued_publishing._writer[0] = writer
        conn.write_data(framed(1, 10))
        assert conn._channel is None  # behind rospy's thread, on the Python path
        peer.setblocking(True)
        peer.settimeout(10.0)
        stream = b''
        while len(stream) < len(big) + len(framed(1, 10)):
            stream += peer.recv(1 << 16)
        assert unframed(stream) == [0, 1]
        with conn._lock:
            for _ in range(1000):  # till rospy's thread is done with its batch
                if not (conn._queue or conn._sending):
                    break
                conn._cond_data_available.wait(0.01)
        conn.write_data(framed(2, 10))  # nothing before it: the writer's from now on
        assert conn._channel is not None
        peer.setblocking(False)
        assert unframed(pump(writer, conn._channel[1], peer)) == [2]
    finally:
        end(conn)


def test_an_empty_write_is_nothing_to_send_and_ends_nothing(writer):
    # the Python path sends b'' as nothing and goes on; the writer must not take send()'s 0 for a closed peer
    sender, peer = pair()
    channel = writer.open(sender.fileno())
    assert writer.write(channel, b'', 0) == 0
    assert writer.write(channel, b'after', 0) == 0
    assert pump(writer, channel, peer) == b'after'
    assert writer.write(channel, b'later', 0) == 0 and pump(writer, channel, peer) == b'later'


def test_a_socket_that_takes_part_gets_the_rest_at_later_passes_never_cut_and_the_begun_message_is_never_dropped(
        writer):
    sender, peer = pair(SMALL_BUFFER)
    channel = writer.open(sender.fileno())
    big = framed(0, 300000)
    assert writer.write(channel, big, 2) == 0
    writer.pass_once()
    assert writer.waiting(channel) == 1  # the socket took part of it
    first = available(peer)
    assert 0 < len(first) < len(big)
    for _ in range(3):  # the socket full, the peer not reading: passes take what room there is, nothing fails
        writer.pass_once()
    # queue_size 2: more than 2 waiting drops the oldest not begun (1, 2, 3, 4), never the begun rest of 0
    for i in range(1, 6):
        assert writer.write(channel, framed(i, 100), 2) == 0
        assert writer.waiting(channel) <= 2
    stream = first + pump(writer, channel, peer)
    assert unframed(stream) == [0, 5]


def test_with_more_than_queue_size_waiting_behind_a_full_socket_the_oldest_not_begun_are_dropped(writer):
    sender, peer = pair(SMALL_BUFFER)
    channel = writer.open(sender.fileno())
    big = framed(0, 300000)
    assert writer.write(channel, big, 3) == 0
    writer.pass_once()  # the socket takes part of it: full, the subscriber is behind
    assert writer.blocked(channel)
    for i in range(1, 7):
        assert writer.write(channel, framed(i, 10), 3) == 0
    assert writer.waiting(channel) == 3
    assert unframed(available(peer) + pump(writer, channel, peer)) == [0, 5, 6]
    # queue_size 0: no limit, as rospy's
    assert writer.write(channel, big, 0) == 0
    writer.pass_once()
    assert writer.blocked(channel)
    for i in range(7, 50):
        writer.write(channel, framed(i, 10), 0)
    assert unframed(available(peer) + pump(writer, channel, peer)) == [0] + list(range(7, 50))


def test_messages_waiting_for_the_next_pass_on_a_socket_with_room_are_never_dropped(writer):
    # /clock at every update in real time has queue_size 1 and comes twice between two passes: the Python path
    # sends both at once, so must the writer (only a subscriber that is behind loses messages)
    sender, peer = pair()
    channel = writer.open(sender.fileno())
    for i in range(20):
        assert writer.write(channel, framed(i, 10), 1) == 0
    assert not writer.blocked(channel) and writer.waiting(channel) == 20
    assert unframed(pump(writer, channel, peer)) == list(range(20))


# an interleaving of the caller's writes (a message's size), the writer's passes and the peer's reads (bytes)
OPS = st.lists(st.one_of(st.tuples(st.just('write'), st.integers(0, 40000)),
                         st.tuples(st.just('pass'), st.none()),
                         st.tuples(st.just('read'), st.integers(1, 50000))), max_size=60)


@settings(max_examples=150, deadline=None)
@given(OPS, st.integers(1, 4))
def test_whatever_the_interleaving_a_sequence_of_whole_messages_arrives_in_order(ops, queue_size):
    w = SocketWriter()
    sender, peer = pair(SMALL_BUFFER)
    try:
        channel = w.open(sender.fileno())
        stream, written = bytearray(), 0
        for op, value in ops:
            if op == 'write':
                assert w.write(channel, framed(written, value), queue_size) == 0
                written += 1
                # behind a full socket at most queue_size wait, + the begun one, which is never dropped
                assert w.waiting(channel) <= queue_size + 1 or not w.blocked(channel)
            elif op == 'pass':
                w.pass_once()
            else:
                stream += available(peer, value)
        stream += pump(w, channel, peer)
        indices = unframed(bytes(stream))
        assert indices == sorted(set(indices))  # in order, none twice
        assert written == 0 or indices[-1] == written - 1  # the newest is never dropped
    finally:
        w.stop()
        sender.close()
        peer.close()


def test_a_closed_peer_ends_the_channel_and_write_returns_the_errno(writer):
    sender, peer = pair()
    channel = writer.open(sender.fileno())
    assert writer.write(channel, b'first', 10) == 0
    peer.close()
    writer.pass_once()  # the send fails
    assert writer.write(channel, b'second', 10) == errno.EPIPE
    assert writer.waiting(channel) == 0  # nothing queued on an ended channel


def test_a_closed_peer_is_rospys_transport_terminated_and_closes_the_transport(writer):
    from rospy.exceptions import TransportTerminated
    conn, transport, peer = rospy_connection(10)
    try:
        conn.write_data(framed(0, 10))
        assert conn._channel is not None
        peer.close()
        writer.pass_once()  # the writer's send fails: the subscriber went away
        with pytest.raises(TransportTerminated):
            conn.write_data(framed(1, 10))
        assert transport.done and transport.socket is None  # closed, as rospy's own write_data does on EPIPE
        conn._thread.join(5.0)
        assert not conn._thread.is_alive() and conn._channel is None  # rospy's thread ended, the channel closed
    finally:
        if not transport.done:
            end(conn)


def test_closing_the_channel_closes_the_writers_copy_of_the_socket(writer):
    conn, transport = socket_connection(10)
    peer = transport.peer
    peer.setblocking(False)
    try:
        assert copies(transport.socket) == 1
        conn.write_data(b'hello')
        assert conn._channel is not None
        assert copies(transport.socket) == 2  # the writer's dup
        assert pump(writer, conn._channel[1], peer) == b'hello'
        # rospy's transport closes its own socket (no shutdown: the peer sees the end once every copy is closed)
        link = os.readlink('/proc/self/fd/%d' % transport.socket.fileno())
        transport.socket.close()
        close(conn, transport)  # done: rospy's thread ends and closes the channel
        assert conn._channel is None
        with pytest.raises(BlockingIOError):
            peer.recv(1)  # the writer's copy keeps the connection open until its next pass
        writer.pass_once()
        assert peer.recv(1) == b''  # EOF
        assert link not in {_link('/proc/self/fd/' + fd) for fd in os.listdir('/proc/self/fd')}  # no copy left
    finally:
        if not transport.done:
            close(conn, transport)
        peer.close()


def test_a_closed_channels_slot_is_reused_without_its_old_messages(writer):
    old_sender, old_peer = pair()
    old = writer.open(old_sender.fileno())
    assert writer.write(old, b'old message', 0) == 0
    old_sender.close()
    writer.close(old)  # before any pass: what waits is dropped with the channel
    assert writer.write(old, b'too late', 0) != 0  # a closing channel takes nothing more
    writer.pass_once()
    assert old_peer.recv(100) == b''  # EOF, and none of the old message
    sender, peer = pair()
    channel = writer.open(sender.fileno())
    assert channel == old  # the slot freed is reused
    assert writer.waiting(channel) == 0
    assert writer.write(channel, b'new', 0) == 0
    assert pump(writer, channel, peer) == b'new'


def _writer_threads():
    return {t for t in threading.enumerate() if t.name == 'racebot_socket_writer'}


def test_the_started_thread_sends_and_stop_ends_it_closing_the_channels():
    before = _writer_threads()
    w = SocketWriter()
    sender, peer = pair()
    channel = w.open(sender.fileno())
    w.start()
    started = _writer_threads() - before
    assert len(started) == 1 and all(t.daemon for t in started)
    try:
        assert w.write(channel, framed(0, 100000), 0) == 0
        peer.setblocking(True)
        peer.settimeout(10.0)
        got = b''
        while len(got) < len(framed(0, 100000)):
            got += peer.recv(1 << 16)  # sent by the thread: nobody else makes a pass
        assert unframed(got) == [0]
    finally:
        w.stop()
    assert not any(t.is_alive() for t in started)
    sender.close()  # the writer's copy is the last one open, if stop left it
    assert peer.recv(1) == b''  # EOF: stop closed the channel
    assert w.write(channel, b'after', 0) == errno.EPIPE


def _until(condition, timeout=10.0):
    deadline = time.monotonic() + timeout
    while not condition() and time.monotonic() < deadline:
        time.sleep(0.001)
    return condition()


@pytest.mark.parametrize('idle_passes', [None, 1])  # as fast as possible / real time (queued_publishing.writer_pace)
def test_with_nothing_to_write_the_thread_sleeps_and_a_write_or_a_close_wakes_it(idle_passes):
    w = SocketWriter()
    if idle_passes is not None:
        w.set_idle_passes(idle_passes)
    sender, peer = pair()
    channel = w.open(sender.fileno())
    w.start()
    try:
        assert _until(w.sleeping)  # nothing to write: asleep, no wake-ups every PERIOD_US
        peer.setblocking(True)
        peer.settimeout(10.0)
        for i in range(3):
            assert _until(w.sleeping)
            assert w.write(channel, framed(i, 1000), 0) == 0  # wakes it: sent without another write or pass
            got = b''
            while len(got) < len(framed(i, 1000)):
                got += peer.recv(1 << 16)
            assert unframed(got) == [i]
        assert _until(w.sleeping)
        sender.close()  # rospy's own socket; the writer's copy stays open until the close is carried out
        w.close(channel)  # wakes it
        assert peer.recv(1) == b''
    finally:
        w.stop()


CHILD = """
import os
cores = sorted(os.sched_getaffinity(0))
os.sched_setaffinity(0, cores[:{cores}])
from racebot_sim_bridge.transport import queued_publishing
writer = queued_publishing.start_writer()
print(type(writer).__name__)
queued_publishing.stop_writer()
"""


def start_writer_with(cores):
    """What start_writer() returns (its type's name) in a process that may use `cores` cores."""
    done = subprocess.run([sys.executable, '-c', CHILD.format(cores=cores)], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_start_writer_gives_none_on_one_core():
    # one core: the writer thread would take turns with the update loop, sending from the caller is cheaper
    assert start_writer_with(1) == 'NoneType'
    if len(os.sched_getaffinity(0)) >= 2:
        assert start_writer_with(2) == 'SocketWriter'


def test_stop_writer_returns_the_connections_to_the_python_path():
    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip('start_writer starts no writer on one core')
    before = _writer_threads()
    w = queued_publishing.start_writer()
    try:
        assert isinstance(w, SocketWriter) and queued_publishing.start_writer() is w  # one per process
        assert len(_writer_threads() - before) == 1
    finally:
        queued_publishing.stop_writer()
    assert queued_publishing._writer[0] is None and not any(t.is_alive() for t in _writer_threads() - before)
    conn, transport = socket_connection(10)
    try:
        conn.write_data(b'python path')
        assert conn._channel is None and transport.received(11) == b'python path'
    finally:
        close(conn, transport)


def test_a_channel_of_a_stopped_writer_is_never_written_through_the_next_one(writer):
    # stop_writer then start_writer: a connection's channel number means nothing to the new writer (whose slot of
    # that number may be another subscriber's, or not be there at all: it crashed the process)
    conn, transport = socket_connection(10)
    transport.peer.setblocking(False)
    try:
        conn.write_data(b'first')
        assert pump(writer, conn._channel[1], transport.peer) == b'first'
        queued_publishing._writer[0] = None
        writer.stop()
        queued_publishing._writer[0] = SocketWriter()  # no channel yet
        try:
            conn.write_data(b'second')  # the Python path: the old writer's channel is closed, the new has none
            assert transport.received(6) == b'second'
        finally:
            queued_publishing._writer[0].stop()
            queued_publishing._writer[0] = writer
    finally:
        close(conn, transport)
