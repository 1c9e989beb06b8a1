"""xacro's messages on stderr, and `xacro.message/warning/error/fatal` as expressions call them.

Noetic's xacro lets a document report from inside `${...}`:

    ${xacro.message('text', 2, 3.14, color=32, print_location=True)}
    ${xacro.warning('careful')}     (prints where it happened unless print_location=False)
    ${xacro.error('wrong', print_location=False)}
    ${xacro.fatal('cannot go on')}  (stops: error message, location, exit code 2)

Each prints its arguments joined by spaces and evaluates to '' so it can stand in text. A color is
a name ('red', 'yellow') or an ANSI code (32 is green); it is used only when stderr is a terminal.
"""
import sys

import xacro

_NAMED_COLORS = {'red': 91, 'yellow': 93}


def _emit(args, color=None, prefix=''):
    text = ' '.join(str(a) for a in args)
    stream = sys.stderr
    code = _NAMED_COLORS.get(color, color)
    if code and hasattr(stream, 'isatty') and stream.isatty():
        text = '\033[%sm%s\033[0m' % (code, text)
    else:
        text = prefix + text
    print(text, file=stream)


def message(*args, **kwargs):
    _emit(args, color=kwargs.get('color'))


def warning(*args, **kwargs):
    _emit(args, color=kwargs.get('color', 'yellow'), prefix='warning: ')


def error(*args, **kwargs):
    _emit(args, color=kwargs.get('color', 'red'), prefix='error: ')


def fatal(*args):
    """Stop processing: the message becomes xacro's error and the exit code is non-zero."""
    raise xacro.XacroException(' '.join(str(a) for a in args))


def expression_message(emit, print_location, location_by_default):
    """emit as an expression calls it: takes print_location=, ignores file=, returns ''."""
    def from_expression(*args, **kwargs):
        with_location = kwargs.pop('print_location', location_by_default)
        kwargs.pop('file', None)
        emit(*args, **kwargs)
        if with_location:
            print_location()
        return ''
    return from_expression


def returning_empty(function):
    def call(*args, **kwargs):
        function(*args, **kwargs)
        return ''
    return call
