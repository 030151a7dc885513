// Which radar a live run drives: live.radar_model names a model in a registry of creators.
// The registry is built on first use (a function-local static, so registering never depends
// on the order of static initialisation) and starts with the models of this folder: "lt102"
// (drivers/live/lt102_radar.h). RegisterRadarModel adds another (a new radar's driver, a
// test's fake) before the configuration naming it is validated and the run starts. Every
// function is safe from any thread.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "drivers/live/radar_device.h"

namespace uwbsar::live {

using RadarCreator = std::function<std::unique_ptr<RadarDevice>(const RadarDeviceArgs& args)>;

/// Adds `model` (or replaces its creator). `model` must not be empty and `creator` set.
void RegisterRadarModel(const std::string& model, RadarCreator creator);

/// The registered models, sorted by name.
std::vector<std::string> RadarModels();
bool IsRadarModel(const std::string& model);

/// Throws ConfigError naming live.radar_model and the known models unless `model` is
/// registered.
void RequireRadarModel(const std::string& model);

/// Creates a radar of `model`; throws as RequireRadarModel.
std::unique_ptr<RadarDevice> CreateRadar(const std::string& model, const RadarDeviceArgs& args);

}  // namespace uwbsar::live
