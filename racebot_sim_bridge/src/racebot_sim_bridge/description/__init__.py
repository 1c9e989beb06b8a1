"""What a robot or world is, as Gazebo's loader (sdformat) reads it: URDF and SDF models and their readers,
fixed-joint lumping, meshes, materials, model paths and assets. No rospy, no PyBullet."""
