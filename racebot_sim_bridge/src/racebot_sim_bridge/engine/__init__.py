"""The running world: the PyBullet client's owner, the physics world, the simulator (time, robots, hooks,
the step), world copies for other processes, sim time on whole nanoseconds."""
