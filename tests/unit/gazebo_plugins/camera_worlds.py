"""A world with a camera robot for the triggered and prosilica camera plugins."""


WORLD = """<sdf version="1.6"><world name="default">
<model name="ground_plane"><static>true</static><link name="link"><collision name="collision"><geometry>
<plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision>
<visual name="visual"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></visual></link>
</model>
<model name="obstacle"><static>true</static><pose>1.2 0 0.3 0 0 0</pose><link name="link">
<collision name="collision"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></collision>
<visual name="visual"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></visual></link></model>
</world></sdf>"""


CAMERA = """<camera name="%s"><pose>0 %s 0 0 0 0</pose><horizontal_fov>1.0</horizontal_fov>
 <image><width>64</width><height>48</height><format>R8G8B8</format></image><clip><near>0.05</near><far>20</far></clip>
</camera>"""
