"""ros_control: hardware interfaces, the controller manager, controller_interface's base classes, and
control_toolbox's PID.

hardware_interface.py and pid.py run every world update for every joint: CMakeLists.txt compiles them with
Cython into the devel (or install) space's copy of this folder, which therefore comes first on this
package's path; without the build they run as plain Python with the same results."""
from pkgutil import extend_path

__path__ = [p for p in extend_path([], __name__) if p not in __path__] + list(__path__)
