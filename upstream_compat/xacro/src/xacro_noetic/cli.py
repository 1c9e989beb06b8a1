"""xacro's command line as Noetic (1.14.0) has it.

1.14 dropped --legacy, --check-order, --includes and --xacro-ns (their use is an error, as there);
`--inorder`/`-i` stays accepted and only says that it is the default. `name:=value` arguments
set `$(arg name)` / `xacro.arg('name')`.
"""
import textwrap

import xacro.cli

from . import messages


def parse_args(argv):
    parser = xacro.cli.ColoredOptionParser(usage='usage: %prog [options] <input>',
                                           formatter=xacro.cli.IndentedHelpFormatterWithNL())
    parser.add_option('-o', dest='output', metavar='FILE',
                      help='write output to FILE instead of stdout')
    parser.add_option('--deps', action='store_true', dest='just_deps',
                      help='print file dependencies')
    parser.add_option('--inorder', '-i', action='store_true', dest='in_order',
                      help='processing in read order (default, can be omitted)')
    parser.add_option('-q', action='store_const', dest='verbosity', const=0,
                      help='quiet operation, suppressing warnings')
    parser.add_option('-v', action='count', dest='verbosity', help='increase verbosity')
    parser.add_option('--verbosity', metavar='level', dest='verbosity', type='int',
                      help=textwrap.dedent("""\
                      set verbosity level
                      0: quiet, suppressing warnings
                      1: default, showing warnings and error locations
                      2: show stack trace
                      3: log property definitions and usage on top level
                      4: log property definitions and usage on all levels"""))
    parser.set_defaults(just_deps=False, just_includes=False, verbosity=1)

    from rosgraph.names import load_mappings, REMAP
    mappings = load_mappings(argv)
    options, inputs = parser.parse_args([a for a in argv if REMAP not in a])
    if options.in_order:
        messages.message('xacro: in-order processing became default in ROS Melodic. You can drop the option.')
    options.in_order = True
    if len(inputs) != 1:
        parser.error('expected exactly one input file as argument')
    options.mappings = mappings
    return options, inputs[0]
