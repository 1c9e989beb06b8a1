"""gazebo_ros.physics_reconfigure's mapping between PhysicsConfig and the physics services' messages.
Pure: no master."""
from gazebo_msgs.srv import GetPhysicsPropertiesResponse, SetPhysicsPropertiesRequest

from racebot_sim_bridge.gazebo_ros_api import physics_config as PhysicsConfig
from racebot_sim_bridge.gazebo_ros_api.physics_reconfigure import FIELDS, changed, config_of, fill_request


def sample():
    """A configuration with a different value in every parameter."""
    return {name: (i % 2 == 1) if kind is bool else kind(i + 2) for i, (name, _p, kind) in enumerate(FIELDS)}


def test_every_physics_config_parameter_is_mapped_once():
    assert sorted(name for name, _p, _k in FIELDS) == sorted(PhysicsConfig.defaults)


def test_request_and_response_round_trip():
    config = sample()
    request = fill_request(config, SetPhysicsPropertiesRequest())
    response = GetPhysicsPropertiesResponse(time_step=request.time_step, max_update_rate=request.max_update_rate,
                                            gravity=request.gravity, ode_config=request.ode_config)
    assert config_of(response) == config
    assert (request.gravity.z, request.ode_config.max_contacts) == (config['gravity_z'], config['max_contacts'])


def test_changed_names_what_differs():
    world = sample()
    config = dict(world, gravity_z=world['gravity_z'] + 1, sor_pgs_iters=world['sor_pgs_iters'] + 1)
    assert changed(config, world) == ['gravity_z', 'sor_pgs_iters']
    assert changed(dict(world), world) == []
