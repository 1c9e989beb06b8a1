"""Helpers of the keyboard tests (not a test itself): a private Xvfb, xset's auto-repeat state."""
import os
import select
import subprocess
import time


def start_xvfb(timeout=30.0):
    """Xvfb on a display number it picks itself (-displayfd: no clash with other X servers) -> (process, ':N').

    -noreset: without it the server resets its keyboard controls (auto-repeat back on) when its last
    client leaves, which would hide a keyboard node that fails to restore them."""
    read_fd, write_fd = os.pipe()
    proc = subprocess.Popen(['Xvfb', '-displayfd', str(write_fd), '-screen', '0', '800x600x24',
                             '-nolisten', 'tcp', '-noreset'],
                            pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_fd)
    data = b''
    deadline = time.time() + timeout
    try:
        while not data.endswith(b'\n') and time.time() < deadline:
            ready, _, _ = select.select([read_fd], [], [], 1.0)
            if ready:
                chunk = os.read(read_fd, 32)
                if not chunk:
                    break
                data += chunk
    finally:
        os.close(read_fd)
    if not data.strip().isdigit():
        stop_xvfb(proc)
        raise RuntimeError('Xvfb did not report a display number within %g s (got %r)' % (timeout, data))
    return proc, ':' + data.decode().strip()


def stop_xvfb(proc):
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(10)


def auto_repeat(env):
    """'on' or 'off': the X server's key auto-repeat, from `xset q`."""
    out = subprocess.run(['xset', 'q'], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         universal_newlines=True, timeout=20).stdout
    for line in out.splitlines():
        if 'auto repeat:' in line:
            return line.split('auto repeat:')[1].split()[0]
    raise AssertionError('no "auto repeat:" in `xset q` output: %r' % out)
