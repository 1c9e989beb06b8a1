# Types for hardware_interface.py when it is compiled (CMakeLists.txt): Cython reads this beside the .py, whose
# code stays the one source; without the build, hardware_interface.py runs as plain Python, the same results.
# The angle helpers are kinematics/angles.py's, compiled there: cimported, they are called as C functions.
cimport cython
from racebot_sim_bridge.kinematics.angles cimport shortest_angular_distance, shortest_angular_distance_with_limits

cdef double _PI
cdef int _EFFORT_MODE, _VELOCITY_MODE, _POSITION_MODE, _OTHER


cdef class JointHandle:
    cdef public object name, kind, interface
    cdef readonly object lower, upper, max_effort, max_velocity
    cdef public double position, velocity, effort, command
    cdef readonly bint has_position_limits
    cdef double _raw_position
    cdef bint _has_raw, _wraps, _angular
    cdef int _mode
    cdef double _lower, _upper, _effort_limit, _velocity_limit

    @cython.locals(previous=double, step=double)
    cpdef read(self, double raw_position, double velocity)

    cpdef double clamped_position(self, double value)

    @cython.locals(cmd=double, lo=double, hi=double, mode=int)
    cpdef double limited_command(self)


cpdef double position_error(JointHandle joint, double target)

@cython.locals(h=JointHandle)
cpdef read_joint_states(list handles, states)

@cython.locals(h=JointHandle, e=double, efforts=list)
cpdef list limited_efforts(list handles)
