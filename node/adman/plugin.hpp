// Registers ADMAN (received signal strength, two-stage GLRT, MLMC localisation) as a sensor model.
#pragma once

#include "node/sensor_model_registry.hpp"

namespace wsn::node::adman {

SensorModelSpec sensorModelSpec();

}  // namespace wsn::node::adman
