"""spawn_xml.referenced_packages: the package names spawn_urdf_model checks before a spawn."""
from racebot_sim_bridge.description.spawn_xml import referenced_packages


def test_names_in_order_with_repeats():
    xml = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="package://pkg_a/m/a.dae"/>'
           '</geometry></visual><collision><geometry><mesh filename="package://nopkg/m/b.stl"/></geometry>'
           '</collision></link><gazebo><uri>package://pkg_a/x</uri></gazebo></robot>')
    assert referenced_packages(xml) == ['pkg_a', 'nopkg', 'pkg_a']


def test_comments_are_left_out():
    xml = '<robot name="r"><!-- <mesh filename="package://nopkg/a.stl"/> --><link name="a"/></robot>'
    assert referenced_packages(xml) == []


def test_a_prefix_without_slash_ends_the_search():
    assert referenced_packages('package://p/q package://broken') == ['p']
    # as upstream, the name runs to the next '/' wherever it is, here the tag's end
    assert referenced_packages('<robot name="r"><y a="package://broken"/></robot>') == ['broken"']


def test_empty_name_is_reported():
    assert referenced_packages('<robot name="r"><m f="package:///abs.stl"/></robot>') == ['']
