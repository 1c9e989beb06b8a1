"""racebot's hector_gazebo_plugins C++ headers (upstream_compat/hector_gazebo_plugins/include): hector's sensor error
model and update timer, as hector_quadrotor_gazebo_plugins builds against them. A program compiled against them reads
SDF parameters the way upstream names them and applies reading = value * scaleError + offset + drift + noise."""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
INCLUDES = [ROOT / 'upstream_compat' / 'hector_gazebo_plugins' / 'include', ROOT / 'devel' / 'include',
            ROOT / 'upstream_compat' / 'gazebo_dev' / 'include', Path('/usr/include/sdformat-12.3'),
            Path('/usr/include/ignition/math6'), Path('/usr/include/ignition/utils1')]
PROGRAM = r'''
#include <iostream>
#include <hector_gazebo_plugins/sensor_model.h>
#include <hector_gazebo_plugins/update_timer.h>

int main()
{
  sdf::ElementPtr sdf(new sdf::Element);
  sdf->SetName("plugin");
  auto add = [&sdf](const std::string &_name, const std::string &_value) {
    sdf::ElementPtr e(new sdf::Element);  // a plugin's child: no schema, a string value (as a URDF <plugin>'s)
    e->SetName(_name);
    e->AddValue("string", _value, false);
    e->GetValue()->SetFromString(_value);
    sdf->InsertElement(e);
  };
  add("offset", "0.5");
  add("scaleError", "2");
  add("accelOffset", "0.1 0.2 0.3");
  add("accelGaussianNoise", "0 0 0");
  gazebo::SensorModel baro;
  baro.Load(sdf);
  gazebo::SensorModel3 accel;
  accel.Load(sdf, "accel");
  hector_gazebo_plugins::SensorModelConfig config;
  baro.dynamicReconfigureCallback(config, 0);  // reads the model into the config
  gazebo::UpdateTimer timer;  // instantiated: the propulsion plugin's clock
  std::cout << baro(1.0, 0.01) << " " << accel(ignition::math::Vector3d(1, 1, 1), 0.01) << " "
            << config.offset << " " << config.scale_error << " " << timer.getUpdateRate() << std::endl;
  return 0;
}
'''


@pytest.mark.skipif(shutil.which('g++') is None, reason='no C++ compiler')
def test_hectors_sensor_model_reads_its_sdf_and_applies_its_error(tmp_path):
    if not (ROOT / 'devel' / 'include' / 'hector_gazebo_plugins' / 'SensorModelConfig.h').is_file():
        pytest.fail('SensorModelConfig.h is missing: run `make build`')
    source = tmp_path / 'probe.cc'
    source.write_text(PROGRAM)
    binary = tmp_path / 'probe'
    cmd = ['g++', '-std=c++17', str(source), '-o', str(binary)] + ['-I%s' % p for p in INCLUDES] + \
        ['-lsdformat12', '-L%s' % (ROOT / 'devel' / 'lib'), '-lgazebo', '-lroscpp', '-lrosconsole', '-lboost_system',
         '-Wl,-rpath,%s' % (ROOT / 'devel' / 'lib')]
    built = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    assert built.returncode == 0, built.stdout[-4000:]
    out = subprocess.run([str(binary)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         timeout=30, env=dict(os.environ)).stdout.split()
    # drift 0 and no noise: 1 * 2 + 0.5; the vector model: 1 * 1 + its per-axis offsets
    assert float(out[0]) == pytest.approx(2.5)
    assert [float(v) for v in out[1:4]] == pytest.approx([1.1, 1.2, 1.3])
    assert float(out[4]) == pytest.approx(0.5) and float(out[5]) == pytest.approx(2.0)
    assert float(out[6]) == 0.0  # no <updateRate>: every step
