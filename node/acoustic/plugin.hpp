// The acoustic Doppler sensor model as a plugin (sensor_model.kind: acoustic_doppler): An et al.
// 2014 eq. (1)-(4) with the environmental noise of An et al. 2013.
#pragma once

#include "node/sensor_model_registry.hpp"

namespace wsn::node::acoustic {

SensorModelSpec sensorModelSpec();

}  // namespace wsn::node::acoustic
