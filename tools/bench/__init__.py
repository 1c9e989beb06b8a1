"""make bench: racebot_sim_bridge's speed against the physics ceiling, and its fidelity.

tools/bench.py is the command; these modules are its parts:
  common      paths, worlds, processes (/proc), launches on private masters, statistics
  ceiling     bare PyBullet stepping of the racebot: the speed ceiling
  inprocess   the simulator without ROS: hinge step response, deterministic runs
  scenarios   the measurements that need ROS, each run in a child process with its own master
  plot        PNG plots without matplotlib (zlib + a 5x7 font)
  report      the table
"""
