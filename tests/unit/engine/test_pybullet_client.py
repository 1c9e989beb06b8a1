"""PybulletClient: one owner per PyBullet client, its functions bound to that client."""
import pybullet as pb
import pytest

from racebot_sim_bridge.engine.physics import PhysicsWorld
from racebot_sim_bridge.engine.pybullet_client import PybulletClient


def _box(client):
    shape = client.createCollisionShape(pb.GEOM_BOX, halfExtents=[0.1, 0.1, 0.1])
    return client.createMultiBody(1.0, shape, basePosition=[0, 0, 1])


@pytest.fixture
def clients():
    made = []
    yield lambda: made.append(PybulletClient()) or made[-1]
    for client in made:
        client.close()


def test_each_client_acts_on_its_own_world(clients):
    a, b = clients(), clients()
    assert a.id != b.id
    _box(a)
    _box(a)
    _box(b)
    assert (a.getNumBodies(), b.getNumBodies()) == (2, 1)
    a.setGravity(0, 0, -9.8)  # gravity in a only
    for _ in range(10):
        a.stepSimulation()
        b.stepSimulation()
    assert a.getBasePositionAndOrientation(0)[0][2] < 1.0
    assert b.getBasePositionAndOrientation(0)[0][2] == 1.0


def test_a_function_is_bound_once_and_kept():
    client = PybulletClient()
    try:
        step = client.stepSimulation
        assert client.stepSimulation is step
        assert step.keywords == {'physicsClientId': client.id}
    finally:
        client.close()


def test_constants_and_unknown_names_are_not_attributes(clients):
    client = clients()
    for name in ('GEOM_BOX', 'error', 'no_such_function', '_private', 'connect', 'disconnect'):
        with pytest.raises(AttributeError, match='PybulletClient has no PyBullet function'):
            getattr(client, name)


def test_passing_the_client_by_hand_says_what_to_do(clients):
    client = clients()
    with pytest.raises(TypeError, match='pass no physicsClientId'):
        pb.stepSimulation(physicsClientId=client)


def test_close_never_lets_an_old_binding_reach_the_next_client():
    # PyBullet gives a freed id to the next client: a function bound to the old id would act on it.
    old = PybulletClient()
    old.getNumBodies()  # bound while connected
    old.close()
    old.close()  # a second close does nothing
    new = PybulletClient()
    try:
        _box(new)
        assert new.id >= 0 and not old.connected
        with pytest.raises(pb.error):
            old.getNumBodies()
    finally:
        new.close()


def test_physics_world_owns_a_client_and_closes_it():
    world = PhysicsWorld()
    client = world.client
    assert isinstance(client, PybulletClient) and client.connected
    world.close()
    assert not client.connected
    world.close()  # again: nothing left to close
