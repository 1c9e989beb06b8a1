#!/usr/bin/env python3
from racebot_control.servo_commands_node import main

main()
