"""The names a `${...}` expression sees, as Noetic's xacro (1.14) defines them, and the guarded eval.

xacro 1.13.3 offers a short list of builtins, the whole math module and a bare `load_yaml`. Noetic's
1.14 keeps those (so old documents still work) and adds three namespaces:

* `python.`: a wider set of builtins (`python.range`, `python.set`, `python.zip`, `python.abs`, ...);
* `math.`: the public math functions and constants (`math.pi`, `math.radians`, ...);
* `xacro.`: xacro's own functions (`load_yaml`, `dotify`, `abs_filename`, `arg`, `tokenize`,
  `message`, `warning`, `error`, `fatal`, `print_location`).

`sorted`, `range`, `load_yaml`, `abs_filename` and `dotify` are also reachable without a namespace,
with a deprecation warning on each use, as upstream does. Names starting with a double underscore
are refused before evaluation (1.14.9 closed `${''.__class__...}` style escapes that way).
"""
import math
import re

import xacro

from . import messages

# Builtins 1.13.3 already exposed directly; 1.14 keeps them there and adds `len` (1.13.4).
DIRECT_BUILTINS = ('list', 'dict', 'map', 'len', 'str', 'float', 'int', 'True', 'False',
                   'min', 'max', 'round')
# Builtins 1.14 put into `python.` (all of the above, plus these).
PYTHON_NAMESPACE_BUILTINS = DIRECT_BUILTINS + (
    'sorted', 'range', 'abs', 'all', 'any', 'complex', 'divmod', 'enumerate', 'filter',
    'frozenset', 'hash', 'isinstance', 'issubclass', 'ord', 'repr', 'reversed', 'slice', 'set',
    'sum', 'tuple', 'type', 'zip')
# Reachable without `python.` too, but each use warns (1.14.10 moved them into the namespace).
DEPRECATED_DIRECT_BUILTINS = ('sorted', 'range')

_DEPRECATION = 'Using {name}() directly is deprecated. Use {ns}.{name}() instead.'


class SymbolNamespace(dict):
    """`python.`, `math.` and `xacro.`: a dict whose items are also attributes; an unknown
    attribute reads as Python's own NameError, as it does upstream."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise NameError("name '{}' is not defined".format(name))


def _builtin(name):
    import builtins
    return getattr(builtins, name)


def _warn_on_use(function, name, namespace):
    def deprecated(*args, **kwargs):
        messages.warning(_DEPRECATION.format(name=name, ns=namespace))
        return function(*args, **kwargs)
    return deprecated


def tokenize(text, sep=',; ', skip_empty=True):
    """`xacro.tokenize('a, b;c')` -> ['a', 'b', 'c']: split at any of the characters in sep."""
    pieces = re.split('[' + re.escape(sep) + ']', text)
    return [p for p in pieces if p] if skip_empty else pieces


def build_global_symbols(xacro_functions):
    """The evaluation globals. xacro_functions maps the `xacro.` names that need the running
    processor (load_yaml, abs_filename, dotify, arg, print_location) to their implementations."""
    result = {name: _builtin(name) for name in DIRECT_BUILTINS}

    python = SymbolNamespace((name, _builtin(name)) for name in PYTHON_NAMESPACE_BUILTINS)
    result['python'] = python
    for name in DEPRECATED_DIRECT_BUILTINS:
        result[name] = _warn_on_use(python[name], name, 'python')

    public_math = {k: v for k, v in vars(math).items() if not k.startswith('_')}
    result['math'] = SymbolNamespace(public_math)
    result.update(public_math)  # 1.13.3 had them directly; 1.14 keeps that without a warning

    print_location = xacro_functions['print_location']
    namespace = SymbolNamespace(xacro_functions)
    namespace.update(
        tokenize=tokenize,
        fatal=messages.fatal,
        message=messages.expression_message(messages.message, print_location, False),
        warning=messages.expression_message(messages.warning, print_location, True),
        error=messages.expression_message(messages.error, print_location, True),
        # called from an expression it evaluates to '', so that it can stand in text
        print_location=messages.returning_empty(print_location),
    )
    result['xacro'] = namespace
    for name in ('load_yaml', 'abs_filename', 'dotify'):
        result[name] = _warn_on_use(namespace[name], name, 'xacro')
    return result


class _EvalGlobals(dict):
    """The globals of one evaluation: no builtins; a name is looked up in the document's
    properties first, then in the global symbols. Being the globals (not the locals) is what
    makes properties visible inside comprehensions, `[x * scale for x in values]`, as in 1.14."""

    def __init__(self, properties, global_symbols):
        dict.__init__(self, __builtins__={})
        self._properties = properties
        self._global_symbols = global_symbols

    def __missing__(self, name):
        try:
            return self._properties[name]
        except KeyError:
            return self._global_symbols[name]


def safe_eval(expression, properties, global_symbols):
    """Evaluate one `${...}` expression. Raises NameError for unknown names, XacroException for
    any name starting with '__' (those would reach Python's internals)."""
    code = compile(expression.strip(), '<expression>', 'eval')
    forbidden = [name for name in code.co_names if name.startswith('__')]
    if forbidden:
        raise xacro.XacroException('Use of invalid name(s): ', ', '.join(forbidden))
    return eval(code, _EvalGlobals(properties, global_symbols))
