"""PybulletClient: the one owner of one PyBullet physics client.

No ROS here. PyBullet keeps its clients in one process-wide table and every call takes
`physicsClientId` (0 when left out: whichever client connected first). Code that passes the id by
hand can silently act on the wrong world when a process holds several (the tests do; the render
worker and the window hold a copy of the world each). A PybulletClient connects once, disconnects
once (close), and its attributes are PyBullet's functions already bound to its client:

    client = PybulletClient()                  # DIRECT; PybulletClient(pybullet.GUI) opens a window
    client.stepSimulation()                    # pybullet.stepSimulation(physicsClientId=client.id)
    client.getJointStates(body, [0, 1])

Each function is bound (functools.partial) the first time it is asked for and kept as an attribute
of the instance, so later calls cost what a direct call with the keyword costs (measured: within
noise, ~1.5 us per getBasePositionAndOrientation either way). Constants, pybullet.error and the
pure maths (multiplyTransforms, ...) are read from the pybullet module itself.
"""
from __future__ import annotations

import functools

import pybullet as pb

MODE_NAMES = {pb.DIRECT: 'DIRECT', pb.GUI: 'GUI'}


class PybulletClient:
    def __init__(self, mode: int = pb.DIRECT, options: str = '') -> None:
        """Connects a new client (`mode` pybullet.DIRECT or pybullet.GUI; `options` PyBullet's
        connect options). Raises pybullet.error when PyBullet cannot start it (GUI: no display)."""
        self.mode = mode
        self.id = pb.connect(mode, options=options)
        if self.id < 0:
            raise pb.error('could not start a PyBullet client (%s mode)' % MODE_NAMES.get(mode, mode))

    def __getattr__(self, name):
        # Only reached when `name` is not bound yet; bound once, then found in the instance's dict.
        function = getattr(pb, name, None) if not name.startswith('_') else None
        if not callable(function) or isinstance(function, type) or name in ('connect', 'disconnect'):
            raise AttributeError("PybulletClient has no PyBullet function %r (constants and pybullet.error come "
                                 "from the pybullet module; close() disconnects)" % name)
        bound = functools.partial(function, physicsClientId=self.id)
        setattr(self, name, bound)
        return bound

    def __index__(self):
        # PyBullet reads physicsClientId through __index__: say what to do instead of passing the object.
        raise TypeError('pass no physicsClientId: call the function on the PybulletClient itself '
                        '(world.client.getLinkState(body, link), not pybullet.getLinkState(..., physicsClientId=...))')

    @property
    def connected(self) -> bool:
        return self.id >= 0

    def close(self) -> None:
        """Disconnects (once; later calls do nothing). Functions asked for afterwards raise
        pybullet.error ('Not connected to physics server'); do not keep bound ones past close()."""
        if self.id < 0:
            return
        try:
            pb.disconnect(physicsClientId=self.id)
        except pb.error:
            pass  # already gone (the GUI's window was closed)
        self.id = -1
        # PyBullet reuses a freed id for the next client: a function still bound to it would act on that one.
        for name in [n for n, value in vars(self).items() if isinstance(value, functools.partial)]:
            delattr(self, name)

    def __repr__(self):
        return '<PybulletClient %s id %d>' % (MODE_NAMES.get(self.mode, self.mode), self.id)
