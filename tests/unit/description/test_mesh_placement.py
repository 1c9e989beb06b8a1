"""meshes.read_parts places each mesh instance of a file as trimesh's Scene.dump does (the same points, faces
reversed where a node mirrors), without dump's copies of the meshes and of their textures. trimesh's own dump is
the reference here."""
import numpy as np
import pytest
import trimesh

from racebot_sim_bridge.description import meshes


def scene_of_instances():
    """One mesh placed three times (as it is, turned and moved, mirrored), a second mesh, and a point cloud."""
    box = trimesh.creation.box(extents=[1.0, 2.0, 3.0])
    cone = trimesh.creation.cone(radius=0.5, height=1.0, sections=12)
    scene = trimesh.Scene()
    scene.add_geometry(box, geom_name='box', node_name='plain')
    turned = trimesh.transformations.rotation_matrix(0.7, [0.3, 0.2, 0.9])
    turned[:3, 3] = [1.5, -2.0, 0.25]
    scene.add_geometry(box, geom_name='box', node_name='turned', transform=turned)
    scene.add_geometry(box, geom_name='box', node_name='mirrored', transform=np.diag([-1.0, 1.0, 1.0, 1.0]))
    scene.add_geometry(cone, geom_name='cone', node_name='cone', transform=trimesh.transformations.translation_matrix(
        [0.0, 0.0, 4.0]))
    scene.add_geometry(trimesh.PointCloud([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]), geom_name='points', node_name='points')
    return scene


def test_each_instance_is_placed_as_scene_dump_places_it():
    scene = scene_of_instances()
    dumped = [m for m in scene.dump(concatenate=False) if hasattr(m, 'faces')]
    placed = meshes._placed(scene)
    assert len(placed) == len(dumped) == 4  # the point cloud has nothing to collide with or draw
    for (vertices, faces, _), reference in zip(placed, dumped):
        assert np.array_equal(np.asarray(vertices), np.asarray(reference.vertices))
        assert np.array_equal(np.asarray(faces), np.asarray(reference.faces))
    by_node = dict(zip([n for n in scene.graph.nodes_geometry if n != 'points'], placed))
    assert not np.array_equal(by_node['mirrored'][1], scene.geometry['box'].faces)  # winding kept outward
    assert np.array_equal(by_node['plain'][1], scene.geometry['box'].faces)


@pytest.mark.parametrize('ext', ['.dae', '.stl', '.obj'])
def test_read_parts_of_a_file_matches_scene_dump(tmp_path, ext):
    box = trimesh.creation.box(extents=[1.0, 2.0, 3.0])
    box.apply_translation([0.5, 0.0, 1.5])
    path = tmp_path / ('box' + ext)
    data = trimesh.exchange.dae.export_collada(box) if ext == '.dae' else box.export(file_type=ext[1:])
    path.write_bytes(data.encode() if isinstance(data, str) else data)
    parts, _ = meshes.read_parts(str(path))
    scene = trimesh.load(str(path), file_type=ext[1:], force='scene', process=False)
    reference = [m for m in scene.dump(concatenate=False) if len(getattr(m, 'faces', ()))]
    assert len(parts) == len(reference)
    for (vertices, faces), m in zip(parts, reference):
        assert np.array_equal(vertices, np.asarray(m.vertices, dtype=np.float64))
        assert np.array_equal(faces, np.asarray(m.faces, dtype=np.int64))
