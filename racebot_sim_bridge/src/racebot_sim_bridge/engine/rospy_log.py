"""`RospyLog`: the log the simulator, its plugins, sensors and windows write to (error, warn, info), as rospy's
logerr, logwarn and loginfo. rospy is handed in (the world server's, or a test's stand-in): no rospy import here."""
from __future__ import annotations

from types import ModuleType
from typing import Any


class RospyLog:
    def __init__(self, rospy: ModuleType | Any) -> None:
        self.info, self.warn, self.error = rospy.loginfo, rospy.logwarn, rospy.logerr
