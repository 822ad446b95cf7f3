// The magnetometer sensor model as a plugin (sensor_model.kind: magnetometer): Oh et al. 2005
// §VIII's testbed, two-axis magnetometers detecting passing magnets by eq. (11), reports not fused.
#pragma once

#include "node/sensor_model_registry.hpp"

namespace wsn::node::magnetometer {

SensorModelSpec sensorModelSpec();

}  // namespace wsn::node::magnetometer
