// The field sensors of ONERA Table I as a plugin (sensor_model.kind: field_sensors): acoustic
// antennas and beacons, magnetic detectors, PIR, radars and cameras, each placed by a sensors.list
// item and reporting its own measurement kind.
#pragma once

#include "node/sensor_model_registry.hpp"

namespace wsn::node::field_sensors {

SensorModelSpec sensorModelSpec();

}  // namespace wsn::node::field_sensors
