"""rospy's queued publishing without a thread switch per message, for the world server's process.

A rospy publisher with a queue_size hands each message to a writer thread per subscriber
(rospy.impl.tcpros_pubsub.QueuedConnection) and then yields the interpreter (`time.sleep(0)`) so that the writer
sends it at once. In the update loop that yield is a thread switch per message per subscriber: with 8 robots'
lasers, IMUs, odometry and tf it was ~40 % of the loop (py-spy, tools/bench/profiling.py), ~70 us per message
against ~13 us without it (measured on this machine, a publisher with 20 us of work between messages).

roscpp, which Gazebo's plugins publish through, writes a message to the socket at once when nothing is waiting
before it, and queues it for later only when the socket cannot take it. install() gives QueuedConnection that
behaviour: when its queue is empty and its writer idle, the message goes to the socket from the caller's thread,
without blocking (MSG_DONTWAIT); what the socket does not take (a subscriber that reads slowly) is queued for the
writer as before, and the caller yields only once the queue is half full, so the writer sends a batch before the
queue would drop anything. Drop-oldest stays what queue_size means (rospy's and roscpp's): only a subscriber that
cannot keep up loses messages. A queue_size of 1 yields after every queued message, as rospy.

Where the compiled socket_writer is built and the process may use two cores, start_writer() goes one step further,
as roscpp does: the caller only hands the message over and a writer thread of its own, which needs no interpreter
lock, writes it (socket_writer.pyx says why: a send costs the update loop 11-18 us on a 2-core machine). Order,
queue_size and the end of a connection whose subscriber went away stay as above.
"""
import os
import socket
import time

_installed = []
_writer = [None]  # the started socket_writer.SocketWriter the connections hand their messages to, or None


class _Rest(bytes):
    """The part of a message the socket did not take: sent before anything else, never dropped (the stream would
    be cut in the middle of a message)."""


def _send_now(conn, data):
    """Sends `data` on the connection's socket without blocking: the number of bytes the socket took (0 when it
    took none, or cannot be written this way: the writer then meets what is wrong as rospy does)."""
    sock = getattr(conn, 'socket', None)
    if sock is None or getattr(conn, 'done', True):
        return 0
    try:
        sent = sock.send(data, socket.MSG_DONTWAIT)
    except OSError:  # EAGAIN (buffer full), or a connection error the writer reports
        return 0
    conn.stat_bytes += sent
    if sent == len(data):
        conn.stat_num_msg += 1
    return sent


def write_data(self, data):
    """QueuedConnection.write_data: to the writer thread when one is started, else straight to the socket when
    nothing is before it, else queued, yielding only when the writer is behind (rospy 1.15's queues and yields
    every time)."""
    with self._lock:
        # if there was previously an error within the dispatch thread, raise it (as rospy)
        if self._error:
            error, self._error = self._error, None
            raise error
        writer, channel = _writer[0], self._channel
        if writer is not None and channel is None and not self._queue and not self._sending:
            channel = self._channel = _open_channel(writer, self._connection)
        if writer is None or channel is None or channel[0] is not writer:  # (a channel of a writer since stopped)
            failed, backlog = 0, _send_or_queue(self, data)
        else:
            failed = writer.write(channel[1], data, self._queue_size)
            if not failed:
                self._connection.stat_bytes += len(data)
                self._connection.stat_num_msg += 1
                return True
    if failed:
        # the writer's send failed (the subscriber went away): what rospy's transport does on a failed write
        from rospy.exceptions import TransportTerminated
        self._connection.close()
        raise TransportTerminated('writing to %s failed: %s' % (self._connection.endpoint_id, os.strerror(failed)))
    if backlog * 2 >= (self._queue_size or 2):
        time.sleep(0)  # let the writer send what is queued before the queue would drop any of it
    return True


def _send_or_queue(self, data):
    """The Python path, under the connection's lock: sends now what the socket takes when nothing is before it,
    queues the rest for rospy's writer thread; the length of its queue after."""
    if not self._queue and not self._sending:
        sent = _send_now(self._connection, data)
        if sent:
            if sent == len(data):
                return 0
            data = _Rest(data[sent:])
    queue = self._queue
    if self._queue_size > 0 and len(queue) >= self._queue_size:
        for i, queued in enumerate(queue):
            if not isinstance(queued, _Rest):
                del queue[i]  # drop the oldest, as rospy
                break
    queue.append(data)
    self._cond_data_available.notify()
    return len(queue)


def _open_channel(writer, connection):
    """(writer, its channel) for the connection's socket; None when it has none (the caller's path is then
    rospy's). The writer is kept with it: a channel number means nothing to a writer started after it."""
    sock = getattr(connection, 'socket', None)
    if sock is None or getattr(connection, 'done', True):
        return None
    return writer, writer.open(sock.fileno())


def start_writer(log=None):
    """Starts the compiled writer thread for this process's connections when it is built and the process may use
    two cores or more (on one it would take turns with the update loop); returns it, or None (the Python path)."""
    try:
        from racebot_sim_bridge.transport.socket_writer import SocketWriter
    except ImportError:
        if log is not None:
            log('racebot_sim_bridge.transport.socket_writer is not built: messages are sent from the update loop '
                "(slower); 'make build' compiles it (Cython)")
        return None
    if len(os.sched_getaffinity(0)) < 2:
        return None
    if _writer[0] is None:
        writer = SocketWriter()
        writer.start()
        _writer[0] = writer
    return _writer[0]


def writer_pace(bursts):
    """`bursts`: the process publishes in one burst per update of a paced loop (the world server in real time), so
    the writer sleeps after each burst until the next wakes it; else (as fast as possible) it keeps polling while
    messages keep coming."""
    writer = _writer[0]
    if writer is not None:
        from racebot_sim_bridge.transport.socket_writer import IDLE_PASSES
        writer.set_idle_passes(1 if bursts else IDLE_PASSES)


def stop_writer():
    """Stops the writer thread (what waits in it is dropped); later messages go the Python path."""
    writer, _writer[0] = _writer[0], None
    if writer is not None:
        writer.stop()


def _run(self):
    """QueuedConnection._run (rospy 1.15's), marking `_sending` while it relays, so that write_data sends
    nothing past it."""
    while not self._connection.done:
        queue = []
        with self._lock:
            self._sending = False
            # wait for available data
            while not self._queue and not self._connection.done:
                self._cond_data_available.wait()
            # take all data from queue for processing outside of the lock
            if self._queue:
                queue = self._queue
                self._queue = []
                self._sending = True
        # relay all data
        for data in queue:
            try:
                self._connection.write_data(data)
            except Exception as e:
                with self._lock:
                    self._error = e
    with self._lock:
        self._sending = False
        channel, self._channel = self._channel, None
    if channel is not None:
        channel[0].close(channel[1])  # the writer's own copy of the socket is closed too (stop() did, if it ran)


def install():
    """Replaces rospy's QueuedConnection.write_data and _run in this process (once); returns the class patched."""
    from rospy.impl.tcpros_pubsub import QueuedConnection
    if not _installed:
        _installed.append((QueuedConnection.write_data, QueuedConnection._run))
        QueuedConnection._sending = False  # until the writer takes its first batch
        QueuedConnection._channel = None  # (socket_writer, its channel), once it has one
        QueuedConnection.write_data = write_data
        QueuedConnection._run = _run
    return QueuedConnection
