"""PNG plots without matplotlib: an RGB canvas, lines, markers, a 5x7 font, zlib.

Enough for the bench's two figures (turning circles against the bicycle model, the hinge step
response). Text is upper case.
"""
import math
import struct
import zlib

WHITE, BLACK, GREY, LIGHT = (255, 255, 255), (0, 0, 0), (140, 140, 140), (225, 225, 225)
COLOURS = [(31, 119, 180), (214, 39, 40), (44, 160, 44), (148, 103, 189), (255, 127, 14)]

# 5x7 glyphs, one 5-bit row per entry (bit 4 = left column).
FONT = {
    '0': (14, 17, 19, 21, 25, 17, 14), '1': (4, 12, 4, 4, 4, 4, 14), '2': (14, 17, 1, 2, 4, 8, 31),
    '3': (31, 2, 4, 2, 1, 17, 14), '4': (2, 6, 10, 18, 31, 2, 2), '5': (31, 16, 30, 1, 1, 17, 14),
    '6': (6, 8, 16, 30, 17, 17, 14), '7': (31, 1, 2, 4, 8, 8, 8), '8': (14, 17, 17, 14, 17, 17, 14),
    '9': (14, 17, 17, 15, 1, 2, 12), 'A': (14, 17, 17, 31, 17, 17, 17), 'B': (30, 17, 17, 30, 17, 17, 30),
    'C': (14, 17, 16, 16, 16, 17, 14), 'D': (28, 18, 17, 17, 17, 18, 28), 'E': (31, 16, 16, 30, 16, 16, 31),
    'F': (31, 16, 16, 30, 16, 16, 16), 'G': (14, 17, 16, 23, 17, 17, 15), 'H': (17, 17, 17, 31, 17, 17, 17),
    'I': (14, 4, 4, 4, 4, 4, 14), 'J': (7, 2, 2, 2, 2, 18, 12), 'K': (17, 18, 20, 24, 20, 18, 17),
    'L': (16, 16, 16, 16, 16, 16, 31), 'M': (17, 27, 21, 21, 17, 17, 17), 'N': (17, 17, 25, 21, 19, 17, 17),
    'O': (14, 17, 17, 17, 17, 17, 14), 'P': (30, 17, 17, 30, 16, 16, 16), 'Q': (14, 17, 17, 17, 21, 18, 13),
    'R': (30, 17, 17, 30, 20, 18, 17), 'S': (15, 16, 16, 14, 1, 1, 30), 'T': (31, 4, 4, 4, 4, 4, 4),
    'U': (17, 17, 17, 17, 17, 17, 14), 'V': (17, 17, 17, 17, 17, 10, 4), 'W': (17, 17, 17, 21, 21, 21, 10),
    'X': (17, 17, 10, 4, 10, 17, 17), 'Y': (17, 17, 17, 10, 4, 4, 4), 'Z': (31, 1, 2, 4, 8, 16, 31),
    '.': (0, 0, 0, 0, 0, 12, 12), ',': (0, 0, 0, 0, 12, 4, 8), '-': (0, 0, 0, 31, 0, 0, 0),
    '+': (0, 4, 4, 31, 4, 4, 0), ':': (0, 12, 12, 0, 12, 12, 0), '/': (0, 1, 2, 4, 8, 16, 0),
    '(': (2, 4, 8, 8, 8, 4, 2), ')': (8, 4, 2, 2, 2, 4, 8), '%': (24, 25, 2, 4, 8, 19, 3),
    '=': (0, 0, 31, 0, 31, 0, 0), ' ': (0,) * 7, '>': (8, 4, 2, 1, 2, 4, 8), '<': (2, 4, 8, 16, 8, 4, 2),
}


class Canvas(object):
    def __init__(self, width, height, background=WHITE):
        self.w, self.h = width, height
        self.px = bytearray(bytes(background) * (width * height))

    def set(self, x, y, colour):
        x, y = int(round(x)), int(round(y))
        if 0 <= x < self.w and 0 <= y < self.h:
            i = 3 * (y * self.w + x)
            self.px[i:i + 3] = bytes(colour)

    def dot(self, x, y, colour, r=1):
        for dx in range(-r, r + 1):
            for dy in range(-r, r + 1):
                if dx * dx + dy * dy <= r * r:
                    self.set(x + dx, y + dy, colour)

    def line(self, x0, y0, x1, y1, colour, width=1, dash=None):
        n = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
        for i in range(n + 1):
            if dash and (i // dash) % 2:
                continue
            t = i / float(n)
            x, y = x0 + (x1 - x0) * t, y0 + (y1 - y0) * t
            if width <= 1:
                self.set(x, y, colour)
            else:
                self.dot(x, y, colour, width // 2)

    def text(self, x, y, s, colour=BLACK, scale=1):
        for ch in str(s).upper():
            rows = FONT.get(ch, FONT[' '])
            for r, bits in enumerate(rows):
                for c in range(5):
                    if bits & (16 >> c):
                        for sx in range(scale):
                            for sy in range(scale):
                                self.set(x + c * scale + sx, y + r * scale + sy, colour)
            x += 6 * scale

    def png(self, path):
        raw = b''.join(b'\x00' + bytes(self.px[3 * y * self.w:3 * (y + 1) * self.w]) for y in range(self.h))

        def chunk(kind, data):
            return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
        with open(path, 'wb') as f:
            f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', self.w, self.h, 8, 2, 0, 0, 0))
                    + chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))


def nice_ticks(lo, hi, n=5):
    span = hi - lo
    if span <= 0:
        return [lo]
    raw = span / n
    mag = 10 ** math.floor(math.log10(raw))
    step = min((m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw), default=10 * mag)
    t = math.ceil(lo / step) * step
    out = []
    while t <= hi + 1e-9 * span:
        out.append(round(t, 10))
        t += step
    return out


class Axes(object):
    """A plot area on a canvas mapping data (x, y) to pixels; equal=True keeps metres square."""

    def __init__(self, canvas, box, xlim, ylim, equal=False, title='', xlabel='', ylabel=''):
        self.c = canvas
        self.x0, self.y0, self.x1, self.y1 = box
        (xa, xb), (ya, yb) = xlim, ylim
        if equal:
            sx = (self.x1 - self.x0) / (xb - xa)
            sy = (self.y1 - self.y0) / (yb - ya)
            s = min(sx, sy)
            cx, cy = (xa + xb) / 2, (ya + yb) / 2
            hw, hh = (self.x1 - self.x0) / s / 2, (self.y1 - self.y0) / s / 2
            xa, xb, ya, yb = cx - hw, cx + hw, cy - hh, cy + hh
        self.xlim, self.ylim = (xa, xb), (ya, yb)
        self._frame(title, xlabel, ylabel)

    def px(self, x, y):
        (xa, xb), (ya, yb) = self.xlim, self.ylim
        return (self.x0 + (x - xa) / (xb - xa) * (self.x1 - self.x0),
                self.y1 - (y - ya) / (yb - ya) * (self.y1 - self.y0))

    def _frame(self, title, xlabel, ylabel):
        c = self.c
        for t in nice_ticks(*self.xlim):
            x, _ = self.px(t, 0)
            c.line(x, self.y0, x, self.y1, LIGHT)
            label = ('%g' % t)
            c.text(x - 3 * len(label), self.y1 + 6, label)
        for t in nice_ticks(*self.ylim):
            _, y = self.px(0, t)
            c.line(self.x0, y, self.x1, y, LIGHT)
            label = ('%g' % t)
            c.text(self.x0 - 6 * len(label) - 5, y - 3, label)
        for a, b, d, e in ((self.x0, self.y0, self.x1, self.y0), (self.x0, self.y1, self.x1, self.y1),
                           (self.x0, self.y0, self.x0, self.y1), (self.x1, self.y0, self.x1, self.y1)):
            c.line(a, b, d, e, BLACK)
        c.text(self.x0, self.y0 - 40, title, scale=2)
        c.text((self.x0 + self.x1) / 2 - 3 * len(xlabel), self.y1 + 20, xlabel)
        c.text(self.x0 - 5, self.y0 - 10, ylabel)

    def polyline(self, points, colour, width=1, dash=None):
        prev = None
        for x, y in points:
            p = self.px(x, y)
            if prev is not None:
                self.c.line(prev[0], prev[1], p[0], p[1], colour, width, dash)
            prev = p

    def legend(self, entries, x=None, y=None):
        x = self.x0 + 10 if x is None else x
        y = self.y0 + 10 if y is None else y
        for i, (label, colour, dashed) in enumerate(entries):
            yy = y + 14 * i
            self.c.line(x, yy + 3, x + 20, yy + 3, colour, 2, 4 if dashed else None)
            self.c.text(x + 26, yy, label)


def turning_circles(path, runs):
    """runs: {mode: [circle results]} -> one panel per steering mode."""
    modes = [m for m in ('parallel', 'ackermann') if runs.get(m)]
    if not modes:
        return None
    panel = 460
    canvas = Canvas(panel * len(modes) + 40, panel + 90)
    for i, mode in enumerate(modes):
        circles = runs[mode]
        xs = [p[0] for c in circles for p in c['trajectory']] + [0.0]
        ys = [p[1] for c in circles for p in c['trajectory']] + [0.0]
        for c in circles:
            r = c['reference_m']
            xs += [-r, r]
            ys += [-0.2, 2 * r + 0.2]
        pad = 0.3
        ax = Axes(canvas, (80 + i * panel, 60, i * panel + panel - 10, panel + 30),
                  (min(xs) - pad, max(xs) + pad), (min(ys) - pad, max(ys) + pad), equal=True,
                  title='%s steering' % mode, xlabel='x (m)', ylabel='y (m)')
        entries = []
        for j, c in enumerate(circles):
            colour = COLOURS[j % len(COLOURS)]
            r = c['reference_m']
            # bicycle model: the rear axle middle starts at (-0.13, 0) heading +x, centre to its left
            cx, cy = -0.13, r
            ax.polyline([(cx + r * math.sin(a / 90.0 * math.pi), cy - r * math.cos(a / 90.0 * math.pi))
                         for a in range(181)], GREY, 1, dash=5)
            ax.polyline(c['trajectory'], colour, 2)
            entries.append(('D %.1f: R %.2f VS %.2f M (%.1f%%)' % (c['steering_rad'], c['measured_m'], r,
                                                                   c['error_pct']), colour, False))
        entries.append(('BICYCLE MODEL, R = L/TAN(D)', GREY, False))
        ax.legend(entries)
    canvas.png(path)
    return path


def hinge_step(path, samples, figures, target):
    canvas = Canvas(640, 430)
    t_end = samples[-1][0]
    top = max(max(v for _, v in samples), target) * 1.15
    ax = Axes(canvas, (70, 60, 620, 380), (0.0, t_end), (min(0.0, min(v for _, v in samples)), top),
              title='steering hinge step 0 to %.1f rad' % target, xlabel='time after the step (s)',
              ylabel='angle (rad)')
    ax.polyline([(0.0, target), (t_end, target)], GREY, 1, dash=5)
    for f in (0.98, 1.02):
        ax.polyline([(0.0, target * f), (t_end, target * f)], LIGHT, 1, dash=2)
    ax.polyline(samples, COLOURS[0], 2)
    rise, over, settle = figures['rise_time_s'], figures['overshoot_pct'], figures['settling_time_s']
    ax.legend([('LEFT HINGE (P 10, D 0.5)', COLOURS[0], False), ('COMMAND, 2% BAND', GREY, False)],
              x=330, y=260)
    canvas.text(330, 300, 'RISE 10-90%%: %s' % ('%.3f S' % rise if rise is not None else '-'))
    canvas.text(330, 314, 'OVERSHOOT: %.1f%%' % over)
    canvas.text(330, 328, 'SETTLING 2%%: %s' % ('%.3f S' % settle if settle is not None else 'NOT WITHIN 2%'))
    canvas.text(330, 342, 'FINAL: %.4f RAD' % figures['final_rad'])
    canvas.png(path)
    return path
