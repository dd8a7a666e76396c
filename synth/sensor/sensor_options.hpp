// The command-line options of the sensor model, declared once for every verb that renders
// bins (`binpick synth`, and whichever verb the lead wires next): --sensor-model and the
// structured-light parameters. Values are checked as they are parsed (finite, in range, with
// the option's name in the message); check(model) repeats the checks that involve two options.
#pragma once

#include "host/core/cli_fwd.hpp"
#include <nlohmann/json.hpp>

#include "synth/sensor/sensor_model.hpp"

namespace binpick::cli {

// Binds the options to `model`, whose current values are the defaults shown in --help.
void add_sensor_options(CLI::App* verb, SensorModel& model);

}  // namespace binpick::cli

namespace binpick {

// The model as JSON (every field, kind as on the command line; the patch fields only when the
// share is above 0, so manifests from before them still match): for a dataset's manifest, so
// a rerun with other sensor options is noticed.
nlohmann::json sensor_model_json(const SensorModel& model);

}  // namespace binpick
