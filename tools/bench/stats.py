"""The bench's statistics: medians, percentiles, and the median of repeated measurements with its
spread. Pure functions, no ROS.

The spread is the range (min-max) of the repeats: with three to five side-by-side pairs an
interquartile range is not well defined, and the range is what a reader checks a new median against.
"""
import math

MIN_PAIRS = 3  # a speed ratio is the median of at least this many side-by-side pairs


def median(values):
    values = sorted(v for v in values if v is not None)
    if not values:
        return None
    n = len(values)
    return values[n // 2] if n % 2 else 0.5 * (values[n // 2 - 1] + values[n // 2])


def percentile(values, p):
    """Nearest-rank percentile (p in 0..100) of a list; None for an empty one."""
    values = sorted(values)
    if not values:
        return None
    rank = max(1, int(math.ceil(p / 100.0 * len(values))))
    return values[rank - 1]


def spread(values):
    """Repeated measurements of one figure -> {'median', 'min', 'max', 'n'} (None values, i.e. repeats
    that measured nothing, left out); None when nothing was measured."""
    values = [v for v in values if v is not None and math.isfinite(v)]
    if not values:
        return None
    return {'median': median(values), 'min': min(values), 'max': max(values), 'n': len(values)}


def of_pairs(pairs, keys):
    """Side-by-side pairs (dicts, one per pair) -> {key: spread of that key over the pairs}."""
    return {k: spread([p.get(k) for p in pairs]) for k in keys}


def with_spread(s, fmt='%.2f', unit=''):
    """'0.78 (0.74-0.81 over 5)': a spread for the table; the median alone for one measurement."""
    if s is None:
        return '-'
    text = (fmt % s['median']) + unit
    if s.get('n', 1) > 1:
        text += ' (%s-%s over %d)' % (fmt % s['min'], fmt % s['max'], s['n'])
    return text
