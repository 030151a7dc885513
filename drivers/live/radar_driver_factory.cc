#include "drivers/live/radar_driver_factory.h"

#include <cassert>
#include <map>
#include <mutex>
#include <utility>

#include "core/config_io.h"
#include "drivers/live/lt102_radar.h"

namespace uwbsar::live {
namespace {

/// The models and their creators, seeded with this folder's models.
struct Registry {
  Registry() { creators["lt102"] = CreateLt102Radar; }
  std::mutex mutex;
  std::map<std::string, RadarCreator> creators;
};

Registry& TheRegistry() {
  static Registry registry;  // built on first use, from any thread
  return registry;
}

ConfigError UnknownModel(const std::string& model) {
  std::string known;
  for (const std::string& m : RadarModels()) known += (known.empty() ? "" : ", ") + m;
  return ConfigError("'live.radar_model' is '" + model + "', not a known radar model (" + known +
                     ")");
}

}  // namespace

void RegisterRadarModel(const std::string& model, RadarCreator creator) {
  assert(!model.empty() && creator);
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.creators[model] = std::move(creator);
}

std::vector<std::string> RadarModels() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> out;
  for (const auto& [name, creator] : r.creators) out.push_back(name);
  return out;
}

bool IsRadarModel(const std::string& model) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.creators.count(model) > 0;
}

void RequireRadarModel(const std::string& model) {
  if (!IsRadarModel(model)) throw UnknownModel(model);
}

std::unique_ptr<RadarDevice> CreateRadar(const std::string& model, const RadarDeviceArgs& args) {
  RadarCreator creator;
  {
    Registry& r = TheRegistry();
    std::lock_guard<std::mutex> lock(r.mutex);
    auto it = r.creators.find(model);
    if (it != r.creators.end()) creator = it->second;
  }
  if (!creator) throw UnknownModel(model);
  return creator(args);
}

}  // namespace uwbsar::live
