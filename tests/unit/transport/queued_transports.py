"""What rospy's QueuedConnection writes to, for the queued publishing tests: a transport that records what its
writer sends (RecordingTransport) or sends it over a real socket pair (SocketTransport); a patched
QueuedConnection over the latter (socket_connection), and its close."""
import threading

from racebot_sim_bridge.transport import queued_publishing


class RecordingTransport:
    """What QueuedConnection wraps: its writer thread calls write_data; `done` ends that thread. With `hold`, the
    first write waits for it: the writer is busy and what the caller writes meanwhile stays queued."""

    def __init__(self, hold=None):
        self.sent, self.done, self.hold = [], False, hold
        self.writing = threading.Event()

    def set_cleanup_callback(self, callback):
        self.cleanup = callback

    def write_data(self, data):
        self.writing.set()
        if self.hold is not None:
            self.hold.wait(10.0)
        self.sent.append(data)


class SocketTransport(RecordingTransport):
    """A transport over a real socket pair, as rospy's TCPROSTransport: the writer sendall()s on `socket`."""

    def __init__(self, hold=None):
        super().__init__(hold)
        import socket
        self.socket, self.peer = socket.socketpair()
        self.stat_bytes = self.stat_num_msg = 0

    def write_data(self, data):
        self.writing.set()
        if self.hold is not None:
            self.hold.wait(10.0)
        self.socket.sendall(data)
        self.stat_bytes += len(data)
        self.stat_num_msg += 1

    def received(self, count, timeout=5.0):
        self.peer.settimeout(timeout)
        got = b''
        while len(got) < count:
            chunk = self.peer.recv(count - len(got))
            if not chunk:
                raise EOFError('the stream ended after %d of %d bytes' % (len(got), count))
            got += chunk
        return got


def socket_connection(queue_size, buffer=None):
    import socket
    transport = SocketTransport()
    if buffer:
        transport.socket.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, buffer)
    return queued_publishing.install()(transport, queue_size), transport


def close(conn, transport):
    transport.done = True
    conn._closed_connection_callback(transport)
    conn._thread.join(5.0)
