"""make bench: racebot_sim_bridge's speed against the physics ceiling, and its fidelity.

tools/run_bench.py is the command; these modules are its parts:
  common        paths, worlds, processes (/proc), launches on private masters
  stats         medians, percentiles, the median of repeated pairs with its spread (min-max)
  ceiling       bare PyBullet stepping of the racebot: the speed ceiling
  inprocess     the simulator without ROS: hinge step response, scripted runs (determinism), its
                real-time factor and where its Python time goes (cProfile)
  plugin_cost   a compiled Gazebo model plugin's cost per world update beside the same work in Python
  controller_cost  a compiled ros_control controller's cost per update beside racebot's Python one (a scenario)
  update_cost   what those two share: the spinner robot, a ground world, interleaved timing, the figures
  scenarios     the measurements that need ROS, each run in a child process with its own master
  ros_node      the bench's ROS node: the world server's pid, /gazebo services, real-time factor windows
  fleet         the fleet part: many robots beside bare PyBullet (a scenario, with its own ceiling)
  plot          PNG plots with matplotlib (Agg backend, no display)
  report        the table of figures and targets
  kept_figures  the figures kept in the repository (last_figures.json, written by --save) and
                each new figure beside its kept one
"""
