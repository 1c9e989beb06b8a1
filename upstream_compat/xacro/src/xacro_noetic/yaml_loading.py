"""`xacro.load_yaml()` as Noetic's xacro has it: safe loading, dotted access, unit tags.

* The result gives dotted access at every depth: `${cfg.wheel.radius}` as well as
  `${cfg['wheel']['radius']}`, also for dicts reached through lists and loops (1.14.3/5/14).
  `hasattr(cfg, 'key')` works (1.14.16). `xacro.dotify(d)` gives the same access to any dict.
* Scalars tagged `!radians`, `!degrees` (1.14.5; an expression is allowed, 1.14.9:
  `!degrees 90 / 2`) and, on noetic-devel after 1.14.17, `!meters`, `!millimeters`, `!foot`,
  `!inches` become floats in radians or meters.
* Files are read with yaml.safe_load (1.13.5): no arbitrary Python objects.
"""
import math

import xacro

# tag -> factor to radians (angles) or meters (lengths)
UNIT_TAGS = {
    '!radians': 1.0,
    '!degrees': math.pi / 180.0,
    '!meters': 1.0,
    '!millimeters': 0.001,
    '!foot': 0.3048,
    '!inches': 0.0254,
}


class _MissingKey(KeyError, AttributeError):
    """A missing key: KeyError for `d['k']` and `in` style code, AttributeError for hasattr()."""

    def __str__(self):
        return "The yaml dictionary has no key '{}'".format(self.args[0])


def dotted(value):
    """Wrap dicts and lists (not scalars) so that what is read out of them is wrapped too."""
    if isinstance(value, dict) and not isinstance(value, DottedDict):
        return DottedDict(value)
    if isinstance(value, list) and not isinstance(value, DottedList):
        return DottedList(value)
    return value


class DottedDict(dict):
    """A dict whose keys are also attributes: d.a.b == d['a']['b']."""

    def __getitem__(self, key):
        try:
            return dotted(dict.__getitem__(self, key))
        except KeyError:
            raise _MissingKey(key)

    def __getattr__(self, key):
        return self[key]


class DottedList(list):
    """A list whose items (by index, slice or iteration) keep dotted access."""

    def __getitem__(self, index):
        return dotted(list.__getitem__(self, index))

    def __iter__(self):
        return (dotted(item) for item in list.__iter__(self))


def make_loader(evaluate):
    """A yaml SafeLoader class with the unit tags; evaluate(text) evaluates a tagged scalar."""
    import yaml

    class UnitLoader(yaml.SafeLoader):
        pass

    def unit_constructor(factor):
        def construct(loader, node):
            text = loader.construct_scalar(node)
            try:
                return float(evaluate(text)) * factor
            except SyntaxError:
                raise xacro.XacroException('invalid expression: %s' % text)
        return construct

    for tag, factor in UNIT_TAGS.items():
        UnitLoader.add_constructor(tag, unit_constructor(factor))
    return UnitLoader


def make_load_yaml(evaluate):
    """The `xacro.load_yaml(filename)` function; a relative name is relative to the file being
    processed. A missing file stops processing with 'No such file or directory: <path>'."""
    loader = []  # built on first use: importing yaml costs time most documents do not need

    def load_yaml(filename):
        try:
            import yaml
        except ImportError:
            raise xacro.XacroException('yaml support not available; install python3-yaml')
        if not loader:
            loader.append(make_loader(evaluate))
        path = xacro.abs_filename_spec(filename)
        with open(path) as stream:
            old_stack = xacro.push_file(path)
            try:
                return dotted(yaml.load(stream, Loader=loader[0]))
            finally:
                xacro.restore_filestack(old_stack)
                xacro.all_includes.append(path)

    return load_yaml
