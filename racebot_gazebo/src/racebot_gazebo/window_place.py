"""Where the keyboard window goes: beside the 3D window, not under it, when no window manager places windows.

Under a bare X server (Xvfb, a minimal session) a window opens where its creator puts it. PyBullet's
window (gzclient's 3D window, 1024 x 768) always opens at (0, 0): its X11 code takes no position. Tk's
opens there too unless told. So the keyboard node looks for the 3D window among the screen's
top-level windows, by its title, through libX11 (ctypes; Tk has loaded it already: no extra tool).
When the 3D window is there as the keyboard window opens, or opens over it later (racebot.launch
starts the keyboard first; the 3D window comes once the world is loaded), the keyboard window goes
to its right, or below it when the screen is too narrow (`beside`).

Under a window manager the top-level windows are its frames, which hold the titles one level down:
the 3D window is not found there, and the manager places both windows as it likes.
"""
import ctypes
import ctypes.util

TITLE_3D = b'Bullet Physics'  # PyBullet's window: "Bullet Physics ExampleBrowser using OpenGL3+ [btgl] Release build"
GAP = 8                       # pixels between the windows
IS_VIEWABLE = 2               # XWindowAttributes.map_state of a window on the screen


def overlap(a, b):
    """Whether two (x, y, width, height) rectangles share a pixel."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    return ax < bx + bw and bx < ax + aw and ay < by + bh and by < ay + ah


def beside(other, size, screen, gap=GAP):
    """(x, y) for a window of `size` (width, height) next to `other` (x, y, width, height) on a screen of
    `screen` (width, height): to its right; below it when the screen is too narrow; when neither fits,
    the screen's bottom right corner (over `other`, but the most of it left to see)."""
    x, y, width, height = other
    own_w, own_h = size
    screen_w, screen_h = screen
    if x + width + gap + own_w <= screen_w:
        return x + width + gap, min(max(y, 0), max(screen_h - own_h, 0))
    if y + height + gap + own_h <= screen_h:
        return min(max(x, 0), max(screen_w - own_w, 0)), y + height + gap
    return max(screen_w - own_w, 0), max(screen_h - own_h, 0)


class _WindowAttributes(ctypes.Structure):  # Xlib's XWindowAttributes
    _fields_ = [('x', ctypes.c_int), ('y', ctypes.c_int), ('width', ctypes.c_int), ('height', ctypes.c_int),
                ('border_width', ctypes.c_int), ('depth', ctypes.c_int), ('visual', ctypes.c_void_p),
                ('root', ctypes.c_ulong), ('class_', ctypes.c_int), ('bit_gravity', ctypes.c_int),
                ('win_gravity', ctypes.c_int), ('backing_store', ctypes.c_int), ('backing_planes', ctypes.c_ulong),
                ('backing_pixel', ctypes.c_ulong), ('save_under', ctypes.c_int), ('colormap', ctypes.c_ulong),
                ('map_installed', ctypes.c_int), ('map_state', ctypes.c_int), ('all_event_masks', ctypes.c_long),
                ('your_event_mask', ctypes.c_long), ('do_not_propagate_mask', ctypes.c_long),
                ('override_redirect', ctypes.c_int), ('screen', ctypes.c_void_p)]


_ErrorHandler = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p)
_ignore_errors = _ErrorHandler(lambda _display, _event: 0)


class TopWindows:
    """The screen's top-level windows, on an X connection of its own (DISPLAY). OSError if it cannot open."""

    def __init__(self):
        self.x11 = x11 = ctypes.CDLL(ctypes.util.find_library('X11') or 'libX11.so.6')
        x11.XOpenDisplay.restype = ctypes.c_void_p
        x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
        x11.XDefaultRootWindow.restype = ctypes.c_ulong
        x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
        x11.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_ulong),
                                   ctypes.POINTER(ctypes.c_ulong), ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                                   ctypes.POINTER(ctypes.c_uint)]
        x11.XFetchName.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_char_p)]
        x11.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(_WindowAttributes)]
        x11.XFree.argtypes = [ctypes.c_void_p]
        x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
        x11.XSetErrorHandler.restype = ctypes.c_void_p
        x11.XSetErrorHandler.argtypes = [ctypes.c_void_p]
        x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
        self.display = x11.XOpenDisplay(None)
        if not self.display:
            raise OSError('cannot open the X display')
        self.root = x11.XDefaultRootWindow(self.display)

    def find(self, title=TITLE_3D):
        """{window id: (x, y, width, height)} of the top-level windows on the screen whose title starts with `title`."""
        x11, display = self.x11, self.display
        # A window may go between the listing and the questions about it. Xlib's default answer to that
        # error ends the process, and Tk has its own handler: ours while we ask (Tk runs nothing meanwhile).
        tk_handler = x11.XSetErrorHandler(ctypes.cast(_ignore_errors, ctypes.c_void_p))
        try:
            return self._find(title)
        finally:
            x11.XSync(display, 0)
            x11.XSetErrorHandler(tk_handler)

    def _find(self, title):
        x11, display = self.x11, self.display
        root, parent, count = ctypes.c_ulong(), ctypes.c_ulong(), ctypes.c_uint()
        children = ctypes.POINTER(ctypes.c_ulong)()
        if not x11.XQueryTree(display, self.root, ctypes.byref(root), ctypes.byref(parent), ctypes.byref(children),
                              ctypes.byref(count)):
            return {}
        try:
            windows = [children[i] for i in range(count.value)]
        finally:
            if children:
                x11.XFree(children)
        found = {}
        for window in windows:
            name = ctypes.c_char_p()
            if not x11.XFetchName(display, window, ctypes.byref(name)) or name.value is None:
                continue
            matches = name.value.startswith(title)
            x11.XFree(name)
            attributes = _WindowAttributes()
            if matches and x11.XGetWindowAttributes(display, window, ctypes.byref(attributes)) \
                    and attributes.map_state == IS_VIEWABLE:
                found[window] = (attributes.x, attributes.y, attributes.width, attributes.height)
        return found

    def close(self):
        if self.display:
            self.x11.XCloseDisplay(self.display)
            self.display = None
