"""One-call helpers around the controller_manager services.

The function names and return values follow ros_control's module of the same name (each prints
what happened and returns True/False), so scripts written against it keep working. Service
names are relative (``controller_manager/...``): they resolve in the caller's namespace
(ROS_NAMESPACE, ``__ns:=``, or the node's namespace), or under ``namespace`` when given.
"""


import rospy
from controller_manager_msgs.srv import (
    ListControllerTypes, ListControllers, LoadController, ReloadControllerLibraries,
    SwitchController, SwitchControllerRequest, UnloadController)

#: After this many seconds of waiting for a service, say what is probably wrong (then keep waiting).
HINT_AFTER = 5.0


def _service(name, namespace=None):
    prefix = namespace or ''
    if prefix and not prefix.endswith('/'):
        prefix += '/'
    return prefix + 'controller_manager/' + name


def _proxy(name, srv_type, namespace=None):
    """Wait for the service (hinting at the usual causes if slow) and return a proxy."""
    service = _service(name, namespace)
    try:
        rospy.wait_for_service(service, timeout=HINT_AFTER)
    except rospy.ROSInterruptException:
        raise
    except rospy.ROSException:
        print('Waiting for %s ... (is the simulator running? Is ROS_NAMESPACE or __ns:= set to '
              'the robot namespace, e.g. ROS_NAMESPACE=/racebot?)' % rospy.resolve_name(service))
        rospy.wait_for_service(service)
    return rospy.ServiceProxy(service, srv_type)


def list_controller_types(namespace=None):
    resp = _proxy('list_controller_types', ListControllerTypes, namespace)()
    for type_name in resp.types:
        print(type_name)
    return True


def list_controllers(namespace=None):
    resp = _proxy('list_controllers', ListControllers, namespace)()
    if not resp.controller:
        print('No controllers are loaded in mechanism control')
        return True
    for c in resp.controller:
        interfaces = sorted(set(r.hardware_interface for r in c.claimed_resources))
        print('%s - %s ( %s )' % (c.name, '+'.join(interfaces), c.state))
    return True


def load_controller(name, namespace=None):
    if _proxy('load_controller', LoadController, namespace)(name).ok:
        print('Loaded', name)
        return True
    print('Error when loading', name)
    return False


def unload_controller(name, namespace=None):
    if _proxy('unload_controller', UnloadController, namespace)(name).ok:
        print('Unloaded %s successfully' % name)
        return True
    print('Error when unloading', name)
    return False


def start_stop_controllers(names, start, namespace=None):
    """Start (``start`` True) or stop the named controllers with one STRICT switch."""
    names = list(names)
    request = SwitchControllerRequest(
        start_controllers=names if start else [], stop_controllers=[] if start else names,
        strictness=SwitchControllerRequest.STRICT, start_asap=False, timeout=0.0)
    ok = _proxy('switch_controller', SwitchController, namespace)(request).ok
    if ok:
        print('%s %s successfully' % ('Started' if start else 'Stopped', names))
    else:
        print('Error when %s %s' % ('starting' if start else 'stopping', names))
    return ok


def start_controller(name, namespace=None):
    return start_stop_controllers([name], True, namespace)


def start_controllers(names, namespace=None):
    return start_stop_controllers(names, True, namespace)


def stop_controller(name, namespace=None):
    return start_stop_controllers([name], False, namespace)


def stop_controllers(names, namespace=None):
    return start_stop_controllers(names, False, namespace)


def reload_libraries(force_kill, restore=False, namespace=None):
    """Reload controller libraries; with ``restore``, reload and restart what was there before."""
    reload_srv = _proxy('reload_controller_libraries', ReloadControllerLibraries, namespace)
    before = None
    if restore:
        before = _proxy('list_controllers', ListControllers, namespace)().controller
    ok = reload_srv(force_kill).ok
    if ok:
        print('Successfully reloaded libraries')
    else:
        print('Failed to reload libraries. Do you still have controllers loaded?')
    if restore and before:
        load = _proxy('load_controller', LoadController, namespace)
        for c in before:
            load(c.name)
        running = [c.name for c in before if c.state == 'running']
        switch = _proxy('switch_controller', SwitchController, namespace)
        switch(SwitchControllerRequest(start_controllers=running, stop_controllers=[],
                                       strictness=SwitchControllerRequest.BEST_EFFORT,
                                       start_asap=False, timeout=0.0))
        print('Controllers restored to original state')
    return ok
