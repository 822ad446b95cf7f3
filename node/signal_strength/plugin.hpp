// The signal-strength sensor model as a plugin (sensor_model.kind: signal_strength): threshold
// detection by Oh et al. eq. (5) and neighbour centre-of-mass fusion by eq. (6).
#pragma once

#include "node/sensor_model_registry.hpp"

namespace wsn::node::signal_strength {

SensorModelSpec sensorModelSpec();

}  // namespace wsn::node::signal_strength
