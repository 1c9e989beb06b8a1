"""The ``controller_manager`` command, as ros_control has it.

    rosrun controller_manager controller_manager <command> [names...]

Services are found relative to the namespace (ROS_NAMESPACE=/racebot or ``__ns:=/racebot``).
Unlike ros_control's script, the exit status is 1 when an operation failed (2 for bad usage).
"""


import sys

USAGE = '''Commands:
    load <name>          - Load the controller named <name>
    unload <name>        - Unload the controller named <name>
    start <name>         - Start the controller named <name>
    stop <name>          - Stop the controller named <name>
    spawn <name>         - Load and start the controller named <name>
    kill <name>          - Stop and unload the controller named <name>
    list                 - List active controllers
    list-types           - List controller Types
    reload-libraries     - Reloads all plugin controller libraries
                           (--restore: load and restart the controllers afterwards)

The controller_manager services are looked up relative to the namespace, e.g.
    ROS_NAMESPACE=/racebot rosrun controller_manager controller_manager list'''

#: command -> (canonical name, needs controller names)
COMMANDS = {
    'load': ('load', True), 'unload': ('unload', True),
    'start': ('start', True), 'stop': ('stop', True),
    'spawn': ('spawn', True), 'sp': ('spawn', True),
    'kill': ('kill', True), 'kl': ('kill', True),
    'list': ('list', False), 'lc': ('list', False),
    'list-types': ('list-types', False), 'lt': ('list-types', False),
    'reload-libraries': ('reload-libraries', False),
}


def parse_command(args):
    """``args`` without program name -> (command, names, restore) or None for bad usage (pure)."""
    if not args or args[0] not in COMMANDS:
        return None
    command, needs_names = COMMANDS[args[0]]
    rest = list(args[1:])
    restore = False
    if command == 'reload-libraries':
        restore = '--restore' in rest
        rest = [a for a in rest if a != '--restore']
    if needs_names and not rest:
        return None
    return command, rest, restore


def execute(command, names, restore=False):
    """Run one parsed command; True when every operation succeeded."""
    from controller_manager import controller_manager_interface as cmi
    if command == 'list':
        return cmi.list_controllers()
    if command == 'list-types':
        return cmi.list_controller_types()
    if command == 'reload-libraries':
        return cmi.reload_libraries(True, restore=restore)
    ok = True
    if command in ('load', 'spawn'):
        for name in names:
            ok = cmi.load_controller(name) and ok
    if command == 'unload':
        for name in names:
            ok = cmi.unload_controller(name) and ok
    if command in ('start', 'spawn'):
        for name in names:
            ok = cmi.start_controller(name) and ok
    if command in ('stop', 'kill'):
        for name in names:
            ok = cmi.stop_controller(name) and ok
    if command == 'kill':
        for name in names:
            ok = cmi.unload_controller(name) and ok
    return ok


def main(argv=None):
    import rospy
    args = rospy.myargv(argv=sys.argv if argv is None else argv)[1:]
    if args and args[0] in ('-h', '--help', 'help'):
        print(USAGE)
        return 0
    parsed = parse_command(args)
    if parsed is None:
        print(USAGE)
        return 2 if args else 0
    try:
        return 0 if execute(*parsed) else 1
    except rospy.ROSInterruptException:
        return 1
    except (rospy.ServiceException, rospy.ROSException) as exc:
        print('controller_manager: service call failed: %s' % exc, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130


def run():
    """Entry point of scripts/controller_manager."""
    sys.exit(main())
