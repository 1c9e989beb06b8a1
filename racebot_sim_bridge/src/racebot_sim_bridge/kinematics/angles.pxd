# Types for angles.py when it is compiled (CMakeLists.txt): Cython reads this beside the .py, whose code stays
# the one source; without the build, angles.py runs as plain Python, the same results. hardware_interface.pxd
# cimports these, so that the compiled hardware_interface calls them as C functions.
cimport cython

cdef double _PI

cpdef double shortest_angular_distance(double a, double b)

@cython.locals(delta=double, other=double)
cpdef double shortest_angular_distance_with_limits(double current, double target, double lower, double upper)
