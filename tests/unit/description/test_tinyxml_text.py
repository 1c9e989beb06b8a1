"""Text read as Gazebo 11's TinyXML reads it (issue 37 item 4): sdformat 9 parses SDF, and a URDF's <gazebo> blocks,
with TinyXML 2.6.2, whose TiXmlBase::ReadText (condenseWhiteSpace, on by default) trims the white space at either
end of a text and makes every run of it inside one space; a CDATA section is kept as written, attributes too.
So `<jointName>a, b,\\n  c</jointName>` is 'a, b, c' for a plugin. Checked at each parse racebot makes of such a
document: world files (xml_document), the spawn services' (spawn_xml), the URDF reader's (urdf_root)."""
import pytest

from racebot_sim_bridge.description import sdf_reader, spawn_xml, urdf_reader, xml_document

from urdf_fixture import with_body

JOINTS = 'a, b,\n   c'


def minimal_urdf(extra):
    return with_body('<link name="base"/>' + extra)


@pytest.mark.parametrize('text, expected', [
    ('  plain  ', 'plain'),
    ('a, b,\n   c', 'a, b, c'),
    ('\t1 \r\n\t 2  3\t', '1 2 3'),
    ('\n \n', None),                 # a blank text is no text node in TinyXML
    ('\xa0x\xa0', '\xa0x\xa0'),      # isspace() in the C locale: a no-break space is no white space
])
def test_a_text_is_trimmed_and_its_runs_of_white_space_are_one_space(text, expected):
    root = xml_document.fromstring('<a><b>%s</b></a>' % text)
    assert root.find('b').text == expected


def test_cdata_is_kept_as_written_and_the_text_around_it_condensed():
    root = xml_document.fromstring('<a><b>\n <![CDATA[  keep\n  me ]]>\n</b><c> x <![CDATA[ y ]]>  z </c>'
                                   '<d>\n  one\n  two </d></a>')
    assert root.find('b').text == '  keep\n  me '
    assert root.find('c').text == 'x y z'  # three text nodes, 'x', ' y ', 'z'
    assert root.find('d').text == 'one two'


def test_attributes_keep_their_spaces():
    assert xml_document.fromstring('<a name="  x  y "/>').get('name') == '  x  y '


def test_a_world_files_plugin_parameters_and_values_are_condensed():
    world = sdf_reader.parse_world(
        '<sdf version="1.6"><world name="w"><model name="m"><link name="l"><collision name="c"><geometry><box>'
        '<size>\n 1\n 1\n 1\n</size></box></geometry></collision></link>'
        '<plugin name="p" filename="libgazebo_ros_joint_state_publisher.so"><jointName>%s</jointName></plugin>'
        '</model></world></sdf>' % JOINTS)
    model = world.models[0]
    assert model.links[0].collisions[0].shape.size == (1.0, 1.0, 1.0)
    assert '<jointName>a, b, c</jointName>' in model.plugins[0]


URDF_PLUGIN = ('<gazebo><plugin name="jsp" filename="libgazebo_ros_joint_state_publisher.so">'
               '<jointName>%s</jointName><updateRate>\n  50\n</updateRate></plugin></gazebo>' % JOINTS)


def test_a_spawned_urdfs_gazebo_plugin_parameters_are_condensed():
    root = spawn_xml.parse(minimal_urdf(URDF_PLUGIN))
    plugin = urdf_reader.parse_urdf(root).plugins[0]
    assert plugin.params['jointName'] == 'a, b, c'
    assert plugin.element.find('jointName').text == 'a, b, c'  # what a plugin reads from its element, too


def test_a_robot_description_read_by_the_urdf_reader_is_condensed():
    plugin = urdf_reader.parse_urdf(minimal_urdf(URDF_PLUGIN)).plugins[0]
    assert plugin.params['jointName'] == 'a, b, c' and plugin.params['updateRate'] == '50'


def test_a_spawned_sdfs_plugin_parameters_are_condensed():
    root = spawn_xml.parse('<sdf version="1.6"><model name="m"><plugin name="p" filename="x.so">'
                           '<jointName>%s</jointName></plugin></model></sdf>' % JOINTS)
    assert root.find('model/plugin/jointName').text == 'a, b, c'
