"""gzserver (and debug): racebot's world server started with gzserver's command line.

    rosrun gazebo_ros gzserver [-u] [-r] [--verbose] [-e ENGINE] [gzserver options] [WORLD]

gazebo_ros's gzserver script sources Gazebo's setup.sh, which puts Gazebo's own resource folder
(/usr/share/gazebo-11, holding worlds/empty.world) first on GAZEBO_RESOURCE_PATH, and then runs
gzserver with its ROS plugins. Here this package is that folder (it holds worlds/empty.world) and the
world server is racebot_sim_bridge's; the world name is looked up in the resource path as Gazebo does,
and a world file that cannot be loaded falls back on worlds/empty.world, as gzserver's Server::ParseArgs.
"""
import os

RESOURCE_PATH_VARIABLE = 'GAZEBO_RESOURCE_PATH'


def resource_path(own_folder, current):
    """GAZEBO_RESOURCE_PATH with `own_folder` first (once), as Gazebo's setup.sh prepends its own."""
    rest = [p for p in (current or '').split(os.pathsep) if p and p != own_folder]
    return os.pathsep.join([own_folder] + rest)


def package_folder():
    """This package's share folder (the source folder in a devel space), or None."""
    import rospkg
    try:
        return rospkg.RosPack().get_path('gazebo_ros')
    except rospkg.ResourceNotFound:
        return None


def main(debugger=False):
    """`debugger`: started as `debug` (empty_world.launch debug:=true), which runs gzserver under gdb
    in Gazebo; the world server says so in its log and runs without one."""
    folder = package_folder()
    if folder:
        os.environ[RESOURCE_PATH_VARIABLE] = resource_path(folder, os.environ.get(RESOURCE_PATH_VARIABLE))
    from racebot_sim_bridge.world_server import main as world_server_main
    world_server_main(debugger=debugger, fallback_to_empty=True)
