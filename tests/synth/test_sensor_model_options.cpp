// The sensor model's parameters: check() names the option of a bad value, the command-line
// options parse into the model and refuse NaN and out-of-range values.
#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "host/core/error.hpp"
#include "synth/sensor/sensor_options.hpp"
#include "synth/sensor/sensor_params.hpp"

using namespace binpick;

namespace {

std::string check_message(const std::function<void(SensorModel&)>& change) {
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  change(m);
  try {
    check(m);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Parses args with the sensor options; returns the model, or throws CLI's error.
SensorModel parse(std::vector<std::string> args) {
  CLI::App app;
  SensorModel m;
  cli::add_sensor_options(&app, m);
  std::reverse(args.begin(), args.end());
  app.parse(args);
  return m;
}

std::string parse_error(const std::vector<std::string>& args) {
  try {
    parse(args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SensorModelOptions, DefaultsPass) {
  EXPECT_NO_THROW(check(SensorModel{}));
  const RenderCamera cam{64, 48, 70, 70, 31.5, 23.5, 100, 5000};
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  const SensorParams p = sensor_params(cam, m, 0);
  EXPECT_EQ(p.flags, kSensorEffects | kSensorShadows);
  EXPECT_GT(p.proj_width, 32u);
  EXPECT_NEAR(p.cos_grazing, std::cos(75 * M_PI / 180), 1e-6);
}

TEST(SensorModelOptions, CheckNamesTheOption) {
  const std::vector<std::pair<std::string, std::function<void(SensorModel&)>>> cases = {
      {"--baseline", [](SensorModel& m) { m.baseline_mm = NAN; }},
      {"--baseline", [](SensorModel& m) { m.baseline_mm = 5000; }},
      {"--projector-scale", [](SensorModel& m) { m.projector_scale = 0; }},
      {"--shadow-tolerance", [](SensorModel& m) { m.shadow_tolerance_mm = -1; }},
      {"--grazing-limit", [](SensorModel& m) { m.grazing_limit_deg = 0; }},
      {"--grazing-limit", [](SensorModel& m) { m.grazing_limit_deg = 91; }},
      {"--edge-jump", [](SensorModel& m) { m.edge_jump_mm = NAN; }},
      {"--specular-cone", [](SensorModel& m) { m.specular_cone_deg = 50; }},
      {"--specular-cone", [](SensorModel& m) { m.specular_cone_deg = NAN; }},
      {"--edge-radius", [](SensorModel& m) { m.edge_radius_px = 6; }},
      {"--noise-a", [](SensorModel& m) { m.noise_a_mm = INFINITY; }},
      {"--noise-b", [](SensorModel& m) { m.noise_b_per_mm = -1e-7; }},
      {"--noise", [](SensorModel& m) { m.added_sigma_mm = NAN; }},
      {"--quantisation", [](SensorModel& m) { m.quantisation_mm = NAN; }},
      {"--quantisation-ref", [](SensorModel& m) { m.quantisation_ref_mm = -1; }},
      {"--range", [](SensorModel& m) { m.min_range_mm = 2000, m.max_range_mm = 1000; }},
      {"--range", [](SensorModel& m) { m.min_range_mm = 0; }},
      {"--range", [](SensorModel& m) { m.max_range_mm = NAN; }},
      {"--dropout-share", [](SensorModel& m) { m.dropout_share = NAN; }},
      {"--dropout-share", [](SensorModel& m) { m.dropout_share = -0.1; }},
      {"--dropout-share", [](SensorModel& m) { m.dropout_share = 0.96; }},
      {"--dropout-share", [](SensorModel& m) { m.dropout_share = 0.5, m.kind = SensorModel::Kind::ideal; }},
      {"--dropout-patch", [](SensorModel& m) { m.dropout_patch_mm = 0; }},
      {"--dropout-patch", [](SensorModel& m) { m.dropout_patch_mm = -5; }},
      {"--dropout-patch", [](SensorModel& m) { m.dropout_patch_mm = NAN; }},
      {"--dropout-patch", [](SensorModel& m) { m.dropout_patch_mm = 1001; }},
  };
  for (const auto& [option, change] : cases) {
    const std::string message = check_message(change);
    EXPECT_NE(message.find(option), std::string::npos) << option << ": '" << message << "'";
  }
  EXPECT_THROW(parse_sensor_kind("tof"), InputError);
  // A raster too large to allocate is refused, not attempted.
  SensorModel m;
  m.kind = SensorModel::Kind::structured_light;
  m.baseline_mm = 2000, m.projector_scale = 4, m.min_range_mm = 1e-3;
  EXPECT_THROW(sensor_params(RenderCamera{1600, 900, 1500, 1500, 800, 450, 10, 2000}, m, 0), InputError);
}

TEST(SensorModelOptions, CommandLineParses) {
  const SensorModel m = parse({"--sensor-model", "structured-light", "--baseline", "-120",
                               "--projector-scale", "0.25", "--grazing-limit", "80", "--edge-jump",
                               "8", "--edge-radius", "2", "--noise-a", "0.1", "--noise-b", "2e-7",
                               "--quantisation", "0.1", "--quantisation-ref", "0", "--range",
                               "500,2500", "--shadow-tolerance", "3", "--specular-cone", "4",
                               "--dropout-share", "0.7", "--dropout-patch", "35"});
  EXPECT_EQ(m.kind, SensorModel::Kind::structured_light);
  EXPECT_EQ(m.baseline_mm, -120);
  EXPECT_EQ(m.projector_scale, 0.25);
  EXPECT_EQ(m.grazing_limit_deg, 80);
  EXPECT_EQ(m.edge_jump_mm, 8);
  EXPECT_EQ(m.edge_radius_px, 2);
  EXPECT_EQ(m.noise_a_mm, 0.1);
  EXPECT_EQ(m.noise_b_per_mm, 2e-7);
  EXPECT_EQ(m.quantisation_mm, 0.1);
  EXPECT_EQ(m.quantisation_ref_mm, 0);
  EXPECT_EQ(m.min_range_mm, 500);
  EXPECT_EQ(m.max_range_mm, 2500);
  EXPECT_EQ(m.shadow_tolerance_mm, 3);
  EXPECT_EQ(m.specular_cone_deg, 4);
  EXPECT_EQ(m.dropout_share, 0.7);
  EXPECT_EQ(m.dropout_patch_mm, 35);
  EXPECT_NO_THROW(check(m));
  EXPECT_EQ(parse({}).kind, SensorModel::Kind::ideal);
  EXPECT_EQ(parse({}).dropout_share, 0);
  EXPECT_EQ(sensor_model_json(m)["kind"], "structured-light");
  // The patches are in the manifest when on (a changed share or size is not resumed), and
  // absent when off (manifests from before them still match).
  EXPECT_EQ(sensor_model_json(m)["dropout_share"], 0.7);
  EXPECT_EQ(sensor_model_json(m)["dropout_patch_mm"], 35);
  SensorModel off = m;
  off.dropout_share = 0;
  EXPECT_FALSE(sensor_model_json(off).contains("dropout_share"));
  EXPECT_FALSE(sensor_model_json(off).contains("dropout_patch_mm"));
}

TEST(SensorModelOptions, CommandLineRefusesBadValues) {
  for (const auto& [option, value] :
       {std::pair<std::string, std::string>{"--baseline", "nan"}, {"--baseline", "3000"},
        {"--projector-scale", "0"}, {"--grazing-limit", "NaN"}, {"--grazing-limit", "0"},
        {"--edge-jump", "-1"}, {"--edge-radius", "9"}, {"--noise-a", "inf"}, {"--noise-b", "abc"},
        {"--quantisation", "-0.1"}, {"--range", "nan,100"}, {"--range", "100"},
        {"--sensor-model", "tof"}, {"--shadow-tolerance", "nan"}, {"--quantisation-ref", "-5"},
        {"--specular-cone", "90"}, {"--dropout-share", "nan"}, {"--dropout-share", "-0.1"},
        {"--dropout-share", "0.96"}, {"--dropout-patch", "0"}, {"--dropout-patch", "-3"},
        {"--dropout-patch", "NaN"}, {"--dropout-patch", "2000"}}) {
    const std::string message = parse_error({option, value});
    EXPECT_FALSE(message.empty()) << option << " " << value;
    if (option != "--range" || value != "100") {
      EXPECT_NE(message.find(option), std::string::npos) << option << " " << value << ": " << message;
    }
  }
}
