# cython: language_level=3, boundscheck=False, wraparound=False
"""A writer thread that sends the world server's messages without the interpreter lock: queued_publishing hands
each message over (a copy, under a mutex: ~0.3 us) and returns; the thread, every PERIOD_US on another core, writes
what is queued to each subscriber's socket, and sleeps while there is nothing to write.

Why: as fast as possible, the update loop publishes thousands of messages a wall second, and on a 2-core machine a
send to a subscriber whose thread sleeps on the other core costs the sender 11-18 us (the loopback TCP path and the
wake-up; measured in the world server: 5-6 % of its loop with 1 or 8 robots). roscpp, which Gazebo's plugins publish
through, leaves the writing to its own thread too. A Python thread cannot: it needs the interpreter lock between
two sends, which the update loop holds. Compiled by racebot_sim_bridge/CMakeLists.txt; without it queued_publishing
sends from the caller (its Python path, which the tests compare this one with).

Each connection is a channel: a dup() of its socket, owned here, so that the socket rospy closes is never written
after (a closed fd's number may be reused), and closed here when rospy is done with the connection. Messages go in
order, each whole: a send the socket does not take all of is carried on at the next pass (MSG_DONTWAIT: a subscriber
that reads slowly holds up nobody else); while its socket is full, past queue_size messages waiting, the oldest not
yet begun are dropped, as rospy's queue_size means (and as queued_publishing's Python path does). A send that fails (the subscriber went away) ends the channel and write() returns its errno,
so that rospy closes the connection as its own writer would.
"""
from libc.errno cimport EAGAIN, EINTR, EPIPE, errno
from libc.stdlib cimport free, malloc, realloc
from libc.string cimport memcpy
from posix.unistd cimport close, dup, usleep

cdef extern from "<pthread.h>" nogil:
    ctypedef struct pthread_mutex_t:
        pass
    ctypedef struct pthread_cond_t:
        pass
    int pthread_mutex_init(pthread_mutex_t*, void*)
    int pthread_mutex_lock(pthread_mutex_t*)
    int pthread_mutex_unlock(pthread_mutex_t*)
    int pthread_cond_init(pthread_cond_t*, void*)
    int pthread_cond_wait(pthread_cond_t*, pthread_mutex_t*)
    int pthread_cond_signal(pthread_cond_t*)

cdef extern from "<errno.h>" nogil:
    int EWOULDBLOCK

cdef extern from "<sys/socket.h>" nogil:
    ssize_t send(int, const void*, size_t, int)
    int MSG_DONTWAIT
    int MSG_NOSIGNAL

PERIOD_US = 200  # between two passes of the writer: a message waits at most this long before its send begins
# After this many passes with nothing to write (2 ms), the writer sleeps until a write or a close wakes it (a
# signal, paid by that caller once): a world nobody listens to costs no wake-ups, a busy one no signals.
# set_idle_passes(1) (the world server in real time, whose messages come in one burst per update) sleeps after
# each burst instead of polling through the gap: a signal per update against ~5 wake-ups.
IDLE_PASSES = 10


ctypedef struct Message:
    Message* next
    size_t size
    size_t sent  # bytes of it the socket has taken
    char* data


ctypedef struct Channel:
    int fd  # the writer's dup() of the socket; -1: a free slot
    int error  # errno of the send that ended the channel, 0 while it is good
    int closing  # rospy is done with it: the writer drops what waits and closes fd
    int sending  # the writer is sending the head outside the lock: it must not be dropped
    int blocked  # the socket took less than it was given at the last send: the subscriber is behind
    size_t count
    Message* head
    Message* tail


cdef void _free_messages(Channel* c) noexcept nogil:
    cdef Message* m = c.head
    cdef Message* n
    while m != NULL:
        n = m.next
        free(m)
        m = n
    c.head = c.tail = NULL
    c.count = 0


cdef class SocketWriter:
    cdef pthread_mutex_t mutex
    cdef pthread_cond_t wake  # signalled, under mutex, when the writer is idle and there is work
    cdef int idle  # the writer waits on wake (under mutex)
    cdef volatile int idle_passes  # empty passes before it does
    cdef Channel** channels
    cdef int used, capacity
    cdef volatile int stopping
    cdef object thread

    def __cinit__(self):
        pthread_mutex_init(&self.mutex, NULL)
        pthread_cond_init(&self.wake, NULL)
        self.idle = 0
        self.idle_passes = IDLE_PASSES
        self.channels = NULL
        self.used = self.capacity = 0
        self.stopping = 0

    def start(self):
        """Starts the writer thread (a daemon: the process never waits for it)."""
        import threading
        if self.thread is None:
            self.thread = threading.Thread(target=self._run, name='racebot_socket_writer', daemon=True)
            self.thread.start()

    def open(self, int fd):
        """A channel writing to (a dup of) socket fd: its number, for write() and close()."""
        cdef int own = dup(fd)
        cdef int i
        cdef Channel* c = NULL
        if own < 0:
            raise OSError(errno, 'dup() of socket %d failed' % fd)
        pthread_mutex_lock(&self.mutex)
        for i in range(self.used):
            if self.channels[i].fd < 0:
                c = self.channels[i]
                break
        if c == NULL:
            if self.used == self.capacity:
                self.capacity = 16 if self.capacity == 0 else 2 * self.capacity
                self.channels = <Channel**>realloc(self.channels, self.capacity * sizeof(Channel*))
            c = <Channel*>malloc(sizeof(Channel))
            self.channels[self.used] = c
            i = self.used
            self.used += 1
        c.fd = own
        c.error = c.closing = c.sending = c.blocked = 0
        c.count = 0
        c.head = c.tail = NULL
        pthread_mutex_unlock(&self.mutex)
        return i

    def write(self, int channel, bytes data, int queue_size):
        """Queues `data` on the channel: 0, or the errno of the send that ended the channel (nothing queued)."""
        cdef Py_ssize_t size = len(data)
        cdef Message* m = <Message*>malloc(sizeof(Message) + size)
        cdef Message* drop
        cdef Channel* c
        cdef int error
        if m == NULL:
            raise MemoryError()
        m.next = NULL
        m.size = size
        m.sent = 0
        m.data = <char*>(m + 1)
        memcpy(m.data, <char*>data, size)
        pthread_mutex_lock(&self.mutex)
        c = self.channels[channel]
        error = c.error
        if error or c.closing or c.fd < 0:
            pthread_mutex_unlock(&self.mutex)
            free(m)
            return error or EPIPE
        # Only a subscriber that is behind (its socket full) loses messages, as on the Python path, which sends at
        # once what the socket takes: messages merely waiting for the next pass count for nothing (/clock at every
        # update in real time, queue_size 1, comes twice between two passes). Behind, the oldest not begun go
        # until queue_size are left: the head, unless the socket has taken part of it or it is being sent.
        while c.blocked and queue_size > 0 and c.count >= <size_t>queue_size:
            if c.head.sent or c.sending:
                drop = c.head.next
                if drop == NULL:
                    break
                c.head.next = drop.next
                if c.tail == drop:
                    c.tail = c.head
            else:
                drop = c.head
                c.head = drop.next
                if c.tail == drop:
                    c.tail = NULL
            free(drop)
            c.count -= 1
        if c.tail == NULL:
            c.head = c.tail = m
        else:
            c.tail.next = m
            c.tail = m
        c.count += 1
        if self.idle:
            pthread_cond_signal(&self.wake)
        pthread_mutex_unlock(&self.mutex)
        return 0

    def waiting(self, int channel):
        """Messages queued on the channel and not yet wholly sent."""
        cdef size_t count
        pthread_mutex_lock(&self.mutex)
        count = self.channels[channel].count
        pthread_mutex_unlock(&self.mutex)
        return count

    def blocked(self, int channel):
        """Whether the channel's socket was full at the writer's last send (then past queue_size the oldest go)."""
        pthread_mutex_lock(&self.mutex)
        cdef int blocked = self.channels[channel].blocked
        pthread_mutex_unlock(&self.mutex)
        return bool(blocked)

    def close(self, int channel):
        """rospy is done with the connection: the writer drops what waits and closes its socket."""
        pthread_mutex_lock(&self.mutex)
        self.channels[channel].closing = 1
        if self.idle:
            pthread_cond_signal(&self.wake)
        pthread_mutex_unlock(&self.mutex)

    def stop(self):
        """Ends the writer thread, closing every channel."""
        cdef int i
        pthread_mutex_lock(&self.mutex)
        self.stopping = 1
        pthread_cond_signal(&self.wake)
        pthread_mutex_unlock(&self.mutex)
        if self.thread is not None:
            self.thread.join(5.0)
            self.thread = None
        pthread_mutex_lock(&self.mutex)
        for i in range(self.used):
            if self.channels[i].fd >= 0:
                close(self.channels[i].fd)
                self.channels[i].fd = -1
            _free_messages(self.channels[i])
        pthread_mutex_unlock(&self.mutex)

    def pass_once(self):
        """One pass of the writer (what its thread does every PERIOD_US): for tests."""
        with nogil:
            self._pass()

    def set_idle_passes(self, int passes):
        """How many passes that find nothing to write the thread makes before it sleeps until a write (>= 1)."""
        self.idle_passes = max(1, passes)

    def sleeping(self):
        """Whether the writer thread sleeps until a write or a close (IDLE_PASSES passes found nothing)."""
        pthread_mutex_lock(&self.mutex)
        cdef int idle = self.idle
        pthread_mutex_unlock(&self.mutex)
        return bool(idle)

    def _run(self):
        cdef unsigned int period = PERIOD_US
        cdef int quiet = 0
        with nogil:
            while not self.stopping:
                quiet = 0 if self._pass() else quiet + 1
                if quiet < self.idle_passes:
                    usleep(period)
                    continue
                quiet = 0
                pthread_mutex_lock(&self.mutex)
                if not self._has_work() and not self.stopping:  # else a write came meanwhile: no sleep
                    self.idle = 1
                    pthread_cond_wait(&self.wake, &self.mutex)
                    self.idle = 0
                pthread_mutex_unlock(&self.mutex)

    cdef int _has_work(self) noexcept nogil:
        """Under mutex: a channel has a message to send or a close to carry out."""
        cdef int i
        cdef Channel* c
        for i in range(self.used):
            c = self.channels[i]
            if c.fd >= 0 and (c.closing or (c.head != NULL and not c.error)):
                return 1
        return 0

    cdef int _pass(self) noexcept nogil:
        """Sends what each channel's socket takes and carries out closes; whether there was anything to do."""
        cdef int i, n, fd, err, worked = 0
        cdef ssize_t r
        cdef Channel* c
        cdef Message* m
        pthread_mutex_lock(&self.mutex)
        n = self.used
        pthread_mutex_unlock(&self.mutex)
        for i in range(n):
            while True:
                pthread_mutex_lock(&self.mutex)
                c = self.channels[i]
                if c.fd < 0:
                    pthread_mutex_unlock(&self.mutex)
                    break
                if c.closing:
                    _free_messages(c)
                    close(c.fd)
                    c.fd = -1
                    worked = 1
                    pthread_mutex_unlock(&self.mutex)
                    break
                if c.error or c.head == NULL:
                    pthread_mutex_unlock(&self.mutex)
                    break
                worked = 1
                m = c.head
                c.sending = 1
                fd = c.fd
                pthread_mutex_unlock(&self.mutex)
                r = send(fd, m.data + m.sent, m.size - m.sent, MSG_DONTWAIT | MSG_NOSIGNAL)
                err = errno
                pthread_mutex_lock(&self.mutex)
                c.sending = 0
                if r > 0 or m.size == 0:  # send() takes an empty message as 0 bytes: sent, not a closed peer
                    m.sent += r
                    c.blocked = m.sent < m.size  # the socket took only part: it is full
                    if m.sent == m.size:
                        c.head = m.next
                        if c.head == NULL:
                            c.tail = NULL
                        c.count -= 1
                        free(m)
                    pthread_mutex_unlock(&self.mutex)
                    continue
                if r < 0 and (err == EAGAIN or err == EWOULDBLOCK or err == EINTR):
                    c.blocked = err != EINTR
                    pthread_mutex_unlock(&self.mutex)
                    break  # the socket is full: the next pass goes on
                c.error = err if r < 0 else EPIPE
                _free_messages(c)
                pthread_mutex_unlock(&self.mutex)
                break
        return worked
