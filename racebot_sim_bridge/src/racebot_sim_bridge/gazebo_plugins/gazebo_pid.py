"""Gazebo 11's common::PID (gazebo/common/PID.cc), which its plugins (ElevatorPlugin, HarnessPlugin) drive joints
with: command = -(p * error + i-term + d * d(error)/dt), the i-term held within [imin, imax], the command clamped to
[cmd_min, cmd_max] only when cmd_max >= cmd_min (the default cmd_max -1 < cmd_min 0: no clamp). Its sign is Gazebo's:
error = position - target, so the command pushes back. Not control_toolbox's Pid (ros_control/pid.py).
"""
import math


class GazeboPid:
    def __init__(self, p=0.0, i=0.0, d=0.0, imax=0.0, imin=0.0, cmd_max=-1.0, cmd_min=0.0):
        self.p, self.i, self.d = p, i, d
        self.imax, self.imin, self.cmd_max, self.cmd_min = imax, imin, cmd_max, cmd_min
        self.reset()

    def reset(self):
        self.p_err_last = self.i_err = self.d_err = self.cmd = 0.0

    def update(self, error, dt):
        if dt == 0 or not math.isfinite(error):
            return 0.0
        self.i_err += dt * error
        i_term = self.i * self.i_err
        if i_term > self.imax or i_term < self.imin:  # held at the bound, the error with it
            i_term = self.imax if i_term > self.imax else self.imin
            self.i_err = i_term / self.i if self.i else 0.0
        self.d_err = (error - self.p_err_last) / dt
        self.p_err_last = error
        self.cmd = -self.p * error - i_term - self.d * self.d_err
        if self.cmd_max >= self.cmd_min:
            self.cmd = min(max(self.cmd, self.cmd_min), self.cmd_max)
        return self.cmd
