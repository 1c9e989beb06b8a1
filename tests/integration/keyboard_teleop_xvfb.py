"""Helpers of the X tests (not a test itself): a private Xvfb, its screen's pixels, xset's auto-repeat state."""
import os
import select
import struct
import subprocess
import time

import numpy as np


def start_xvfb(timeout=30.0, fbdir=None, screen='800x600x24'):
    """Xvfb on a display number it picks itself (-displayfd: no clash with other X servers) -> (process, ':N').

    -noreset: without it the server resets its keyboard controls (auto-repeat back on) when its last
    client leaves, which would hide a keyboard node that fails to restore them. With `fbdir`, the
    server keeps its screen in fbdir/Xvfb_screen0 (an XWD file: see screen_pixels)."""
    read_fd, write_fd = os.pipe()
    proc = subprocess.Popen(['Xvfb', '-displayfd', str(write_fd), '-screen', '0', screen,
                             '-nolisten', 'tcp', '-noreset'] + (['-fbdir', fbdir] if fbdir else []),
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


def screen_pixels(fbdir):
    """The screen of an Xvfb started with fbdir, as an (height, width, 3) uint8 RGB array: the XWD
    file Xvfb keeps there (big-endian header, then the colour map, then 32-bit pixels)."""
    with open(os.path.join(fbdir, 'Xvfb_screen0'), 'rb') as f:
        data = f.read()
    fields = struct.unpack('>25I', data[:100])
    header_size, width, height = fields[0], fields[4], fields[5]
    byte_order, bits_per_pixel, bytes_per_line, ncolors = fields[7], fields[11], fields[12], fields[19]
    if bits_per_pixel != 32:
        raise AssertionError('Xvfb screen has %d bits per pixel; start it with depth 24' % bits_per_pixel)
    start = header_size + 12 * ncolors
    raw = np.frombuffer(data, dtype=np.uint8, count=height * bytes_per_line, offset=start)
    pixels = raw.reshape(height, bytes_per_line)[:, :width * 4].reshape(height, width, 4)
    # 0x00RRGGBB words: in memory B, G, R, X when least significant byte first (byte_order 0)
    return pixels[:, :, 2::-1].copy() if byte_order == 0 else pixels[:, :, 1:4].copy()


def auto_repeat(env):
    """'on' or 'off': the X server's key auto-repeat, from `xset q`."""
    out = subprocess.run(['xset', 'q'], env=env, capture_output=True, text=True, timeout=20).stdout
    for line in out.splitlines():
        if 'auto repeat:' in line:
            return line.split('auto repeat:')[1].split()[0]
    raise AssertionError('no "auto repeat:" in `xset q` output: %r' % out)
