# Types for differential.py when it is compiled (CMakeLists.txt): Cython reads this beside the .py, whose
# code stays the one source; without the build, differential.py runs as plain Python, the same results.
cimport cython


@cython.locals(x=double, y=double, theta=double, radius=double, sl=double, sr=double, ssum=double, sdiff=double,
               heading=double, dx=double, dy=double, dtheta=double)
cpdef tuple encoder_step(pose, double left_velocity, double right_velocity, double diameter, double separation,
                         double dt)


cdef class EncoderOdometry:
    cdef public object read_wheels, wheels
    cdef public double diameter, separation, x, y, theta, v, w
    cdef public long long last_ns, wheels_ns

    @cython.locals(dt=double)
    cpdef update(self, long long now)
