"""make deps: the ROS 1 packages a workspace or package needs that neither Debian nor racebot provides, fetched
at their Noetic release and built in an underlay (docs/DEPS.md)."""
