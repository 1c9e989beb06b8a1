"""Gazebo's standard material script names (media/materials/scripts/gazebo.material) as colours.

No rospy, no pybullet. URDFs name these in <gazebo reference="link"><material>Gazebo/Red</material>
and SDF visuals in <material><script><name>Gazebo/Red</name></script>. Each maps to the script's
diffuse colour (what a lit surface mostly shows); textured and glowing/transparent effects become
their base colour. Names not listed here keep the visual's own colour (with a warning).
"""
from __future__ import annotations

from typing import Tuple

__all__ = ['GAZEBO_MATERIALS', 'gazebo_material_rgba', 'Rgba']

Rgba = Tuple[float, float, float, float]  # red, green, blue, alpha in [0, 1]

GAZEBO_MATERIALS = {
    'Gazebo/Grey': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/Gray': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/DarkGrey': (0.175, 0.175, 0.175, 1.0),
    'Gazebo/DarkGray': (0.175, 0.175, 0.175, 1.0),
    'Gazebo/LightGrey': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/White': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/FlatBlack': (0.1, 0.1, 0.1, 1.0),
    'Gazebo/Black': (0.0, 0.0, 0.0, 1.0),
    'Gazebo/Red': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/RedBright': (0.87, 0.26, 0.07, 1.0),
    'Gazebo/Green': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/Blue': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/SkyBlue': (0.13, 0.44, 0.70, 1.0),
    'Gazebo/Yellow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/ZincYellow': (0.9725, 0.9529, 0.2078, 1.0),
    'Gazebo/DarkYellow': (0.7, 0.7, 0.0, 1.0),
    'Gazebo/Purple': (1.0, 0.0, 1.0, 1.0),
    'Gazebo/Turquoise': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/Orange': (1.0, 0.5088, 0.0468, 1.0),
    'Gazebo/Indigo': (0.33, 0.0, 0.5, 1.0),
    'Gazebo/WhiteGlow': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/RedGlow': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/GreenGlow': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/BlueGlow': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/YellowGlow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/PurpleGlow': (1.0, 0.0, 1.0, 1.0),
    'Gazebo/TurquoiseGlow': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/RedTransparent': (1.0, 0.0, 0.0, 0.5),
    'Gazebo/GreenTransparent': (0.0, 1.0, 0.0, 0.5),
    'Gazebo/BlueTransparent': (0.0, 0.0, 1.0, 0.5),
    'Gazebo/GreyTransparent': (0.5, 0.5, 0.5, 0.5),
    'Gazebo/BlackTransparent': (0.0, 0.0, 0.0, 0.5),
    'Gazebo/YellowTransparent': (1.0, 1.0, 0.0, 0.5),
    'Gazebo/DarkMagentaTransparent': (0.6, 0.0, 0.6, 0.5),
    'Gazebo/Wood': (1.0, 0.8, 0.6, 1.0),
    'Gazebo/WoodFloor': (0.6, 0.45, 0.3, 1.0),
    'Gazebo/WoodPallet': (0.6, 0.45, 0.3, 1.0),
    'Gazebo/Bricks': (0.6, 0.3, 0.2, 1.0),
    'Gazebo/Residential': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Asphalt': (0.3, 0.3, 0.3, 1.0),
    'Gazebo/Road': (0.3, 0.3, 0.3, 1.0),
    'Gazebo/Grass': (0.3, 0.5, 0.2, 1.0),
}


def gazebo_material_rgba(name: str | None) -> Rgba | None:
    """The colour of a Gazebo material script name (surrounding blanks ignored), or None."""
    return GAZEBO_MATERIALS.get((name or '').strip())
