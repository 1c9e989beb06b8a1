"""interleaved(): provokes races by letting threads switch before every bytecode of the code under test."""
import contextlib
import sys
import threading


@contextlib.contextmanager
def interleaved(*modules):
    """Threads may switch before every bytecode of `modules` (this thread and threads started
    inside the block)."""
    files = {m.__file__ for m in modules}

    def each_opcode(frame, event, arg):
        return each_opcode

    def on_call(frame, event, arg):
        if frame.f_code.co_filename in files:
            frame.f_trace_opcodes = True
            return each_opcode
        return None
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    threading.settrace(on_call)
    sys.settrace(on_call)
    try:
        yield
    finally:
        sys.settrace(None)
        threading.settrace(None)
        sys.setswitchinterval(interval)
