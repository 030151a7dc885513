// The whole configuration file: what the SLAM library reads (slam/app_config.h Config) and
// the evaluation's sections above it (eval/compare's compare.*), each section defined beside
// the code that owns it. config/default.yaml mirrors it field by field; the loader is
// app/app_config_io.h. The command line loads it and gives each job the part it needs, so the
// SLAM library never sees a section of the evaluation.
#pragma once

#include "eval/compare/compare_config.h"
#include "slam/app_config.h"

namespace uwbsar {

struct AppConfig : Config {
  CompareConfig compare;

  /// Config's sections (Config::Visit), then the evaluation's: each section is listed once.
  template <class V>
  void Visit(V& v) {
    Config::Visit(v);
    v("compare", compare);
  }
};

}  // namespace uwbsar
