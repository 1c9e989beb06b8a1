"""Noetic's xacro (1.14.17) on top of the pinned xacro 1.13.3 from PyPI.

Neither PyPI (1.13.3, then the ROS 2 2.x) nor Debian 12 has xacro 1.14, so `$(find xacro)/xacro`
imports 1.13.3 and install() replaces the parts of it that 1.14 changed with ours: the names an
expression sees (symbols.py: the `xacro.`, `python.` and `math.` namespaces), load_yaml
(yaml_loading.py), the document walk (engine.py) and the command line (cli.py). What 1.14 kept
from 1.13.3 (parsing, file handling, substitution args, output) stays the pinned module's.
"""
import sys
import xml.parsers.expat

import xacro

from . import cli, engine, messages, symbols, yaml_loading

_REPLACED = ('check_attrs', 'eval_text', 'grab_property', 'grab_macro', 'parse_macro_arg',
             'process_include', 'resolve_macro', 'handle_macro_call', 'eval_all', 'process_doc',
             'print_location')


def _evaluate_with_globals(text):
    return symbols.safe_eval(text, {}, engine.GLOBAL_SYMBOLS)


def install():
    """Make the imported xacro module behave as 1.14 (idempotent)."""
    if getattr(xacro, 'noetic_installed', False):
        return
    load_yaml = yaml_loading.make_load_yaml(_evaluate_with_globals)
    engine.GLOBAL_SYMBOLS.update(symbols.build_global_symbols(dict(
        load_yaml=load_yaml,
        abs_filename=xacro.abs_filename_spec,
        dotify=yaml_loading.DottedDict,
        arg=lambda name: xacro.substitution_args_context['arg'][name],
        print_location=engine.print_location,
    )))
    for name in _REPLACED:
        setattr(xacro, name, getattr(engine, name))
    xacro.load_yaml = load_yaml
    xacro.tokenize = symbols.tokenize
    xacro.global_symbols = engine.GLOBAL_SYMBOLS
    xacro.allow_non_prefixed_tags = False
    xacro.noetic_installed = True


def main(argv=None):
    """`xacro [options] <input> [name:=value ...]`: print the expanded document, or on an error
    print it with its location and exit with code 2."""
    install()
    options, input_file = cli.parse_args(sys.argv[1:] if argv is None else argv)
    xacro.verbosity = options.verbosity
    try:
        doc = xacro.process_file(input_file, **vars(options))
        out = xacro.open_output(options.output)
    except xml.parsers.expat.ExpatError as e:
        messages.message('XML parsing error: %s' % e, color='red')
        if xacro.verbosity > 0:
            engine.print_location()
            print(file=sys.stderr)
            print('Check that:', file=sys.stderr)
            print(' - Your XML is well-formed', file=sys.stderr)
            print(' - You have the xacro xmlns declaration:',
                  'xmlns:xacro="http://www.ros.org/wiki/xacro"', file=sys.stderr)
        sys.exit(2)
    except Exception as e:
        messages.error(str(e) or repr(e))
        if xacro.verbosity > 0:
            engine.print_location()
        if xacro.verbosity > 1:
            print(file=sys.stderr)
            raise  # the stack trace, as -v -v asks
        sys.exit(2)

    if options.just_deps:
        out.write(' '.join(set(xacro.all_includes)))
        print()
        return
    out.write(doc.toprettyxml(indent='  '))
    print()
    if options.output:
        out.close()
