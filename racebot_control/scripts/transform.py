#!/usr/bin/env python3
from racebot_control.transform_node import main

main()
