#!/usr/bin/env python3
from racebot_gazebo.keyboard_teleop import main

main()
