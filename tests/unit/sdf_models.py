"""Model-library fixtures written as the community writes them (model.config + model.sdf per model), and a
world of nested models and includes (ROOM)."""
import textwrap


TABLE = """\
<?xml version="1.0" ?>
<sdf version="1.6">
  <model name="table">
    <static>true</static>
    <link name="link">
      <pose>0 0 0.5 0 0 0</pose>
      <collision name="surface">
        <geometry><box><size>1.2 0.8 0.04</size></box></geometry>
      </collision>
      <visual name="visual">
        <geometry><box><size>1.2 0.8 0.04</size></box></geometry>
        <material><script><name>Gazebo/Wood</name></script></material>
      </visual>
    </link>
  </model>
</sdf>
"""


# A wheel as a model library ships one: two links, a joint whose axis is in the model's frame, a plugin naming it.
WHEEL = """\
<?xml version="1.0" ?>
<sdf version="1.6">
  <model name="wheel">
    <link name="rim">
      <inertial><mass>0.5</mass></inertial>
      <collision name="collision">
        <geometry><cylinder><radius>0.1</radius><length>0.04</length></cylinder></geometry>
      </collision>
    </link>
    <link name="hub">
      <pose>0 0 0.05 0 0 0</pose>
      <inertial><mass>0.1</mass></inertial>
      <collision name="collision"><geometry><sphere><radius>0.02</radius></sphere></geometry></collision>
    </link>
    <joint name="spin" type="revolute">
      <parent>rim</parent>
      <child>hub</child>
      <axis>
        <xyz>1 0 0</xyz>
        <use_parent_model_frame>true</use_parent_model_frame>
      </axis>
    </joint>
    <plugin name="wheel_state" filename="libgazebo_ros_joint_state_publisher.so">
      <jointName>
        spin
      </jointName>
    </plugin>
  </model>
</sdf>
"""


def model_config(name, sdf='model.sdf'):
    return textwrap.dedent("""\
        <?xml version="1.0"?>
        <model>
          <name>%s</name>
          <version>1.0</version>
          <sdf version="1.6">%s</sdf>
          <author><name>someone</name><email>someone@example.com</email></author>
          <description>A %s.</description>
        </model>
        """) % (name, sdf, name)


def write_model(models_dir, name, sdf_text, config=None):
    folder = models_dir / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / 'model.sdf').write_text(sdf_text)
    (folder / 'model.config').write_text(config or model_config(name))
    return folder


def world(body):
    return '<?xml version="1.0" ?>\n<sdf version="1.6">\n<world name="default">\n%s\n</world>\n</sdf>\n' % body


ROOM = world("""
  <include><uri>model://ground_plane</uri></include>
  <model name="room">
    <static>true</static>
    <pose>10 0 0 0 0 1.5707963267948966</pose>
    <link name="floor">
      <collision name="collision"><geometry><box><size>4 4 0.1</size></box></geometry></collision>
    </link>
    <include>
      <uri>model://table</uri>
      <name>table_a</name>
      <pose>1 0 0 0 0 0</pose>
    </include>
    <include>
      <uri>model://table</uri>
      <name>table_b</name>
      <pose>-1 0 0 0 0 1.5707963267948966</pose>
    </include>
    <model name="shelf">
      <pose>0 2 0 0 0 0</pose>
      <static>true</static>
      <link name="board">
        <pose>0 0 1 0 0 0</pose>
        <collision name="collision"><geometry><box><size>1 0.3 0.02</size></box></geometry></collision>
      </link>
      <model name="box">
        <pose>0.2 0 0 0 0 1.5707963267948966</pose>
        <link name="link">
          <pose>0.1 0 1.1 0 0 0</pose>
          <collision name="collision"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision>
        </link>
      </model>
    </model>
  </model>
""")
