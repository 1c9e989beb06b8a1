"""libgazebo_ros_velodyne_gpu_laser.so (velodyne_gazebo_plugins): GazeboRosVelodyneLaser built with GAZEBO_GPU_RAY,
for a gpu_ray sensor (in a ray sensor it throws, as the CPU one does in a gpu_ray sensor). Everything else is
gazebo_ros_velodyne_laser.py's: the rays are cast the same way here.
"""
from racebot_sim_bridge.gazebo_plugins.gazebo_ros_velodyne_laser import VelodyneLaser


class VelodyneGpuLaser(VelodyneLaser, libraries=('libgazebo_ros_velodyne_gpu_laser.so',), sensor_types=('gpu_ray',)):
    """GazeboRosVelodyneGpuLaser: VelodyneLaser on a gpu_ray sensor."""
