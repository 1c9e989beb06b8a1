"""gzclient: the 3D window in a process of its own (PyBullet's GUI over a copy of the world), the world
server's attach point for windows, and `gazebo` (server and client together)."""
