# Types for pid.py when it is compiled (CMakeLists.txt): Cython reads this beside the .py, whose code
# stays the one source; without the build, pid.py runs as plain Python, the same results.
cimport cython

cdef double _INF, _MAX


cdef class Pid:
    cdef double _p, _i, _d, _i_min, _i_max
    cdef bint _antiwindup, _has_previous
    cdef double _previous_error, _p_error, _i_error, _d_error, _p_term, _i_term, _d_term, _command

    @cython.locals(e=double, error_dot=double)
    cpdef double compute(self, error, dt)

    @cython.locals(i_term=double, command=double, low=double, high=double)
    cdef double _update(self, double error, double error_dot, double dt)

    cdef double _saturated(self)
