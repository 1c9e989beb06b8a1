"""ControlHook: what a robot's control loop offers the Simulator, which runs it inline every world update.

No ROS here. gazebo_ros_control's plugin (gazebo_ros_control/gazebo_ros_control_plugin.py) is one: it sets
itself as `Robot.control` when the robot is created, and Simulator._step then does, per robot, what the
plugin's Update() does on WorldUpdateBegin:

    control.read(world)                                     # RobotHWSim::readSim
    if control.last_update is None or now - control.last_update >= control.control_period:
        control.cm.update(now, period)                      # ControllerManager::update
        control.last_update = now
    control.write(world, step_size)                         # RobotHWSim::writeSim

These run thousands of times a second, so the Simulator calls the attributes directly: `read` and `write` may
be any callables (the plugin binds its RobotHWSim's own methods there, no layer between).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Protocol, runtime_checkable

if TYPE_CHECKING:
    from racebot_sim_bridge.engine.physics import PhysicsWorld


@runtime_checkable
class ControllerUpdate(Protocol):
    """What the hook's `cm` offers: controller_manager's update(time, period), both in seconds of sim time."""

    def update(self, time: float, period: float) -> None: ...


@runtime_checkable
class ControlHook(Protocol):
    """A robot's control loop as the Simulator runs it (see the module's note).

    control_period: seconds of sim time between two controller manager updates (at least one physics step).
    last_update: the sim time of the last update, None before the first; the Simulator sets it, and sets it to
    0.0 on reset_world (the plugin's Reset()).
    cm: the controller manager (ControllerUpdate)."""

    control_period: float
    last_update: float | None
    cm: ControllerUpdate

    def read(self, world: PhysicsWorld) -> None:
        """The joints' state into the hardware interface, before the update."""

    def write(self, world: PhysicsWorld, dt: float) -> None:
        """The hardware interface's commands onto the joints for the coming step of `dt` seconds."""

    def reset_joint_readings(self, world: PhysicsWorld) -> None:
        """After the joints were moved from outside (set_model_configuration): readings start again from where
        the joints are."""

    def close(self) -> None:
        """The robot goes or the world closes: stop the controllers and their services."""
