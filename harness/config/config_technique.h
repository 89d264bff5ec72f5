#pragma once
// [[technique]] tables of a sweep config: the technique's name, the scenes it runs on, its
// parameters as values or lists (combined as a Cartesian product) and `sets` of paired
// values. Every setting is checked against the plugin before the first cell: ranges, and the
// plugin's own cross-parameter validate() (technique/technique.h).
#include <string>
#include <vector>

#include "config/config.h"
#include "config/config_toml.h"
#include "core/params.h"

namespace rl {

TechniqueSweep parse_technique(const toml::table& t, const Src& src, const toml::node& node);

// Every parameter setting of the sweep, defaults filled in, in a stable order: the product
// of the lists (parameters in declaration order), each combined with every set.
std::vector<ParamValues> parameter_settings(const TechniqueSweep& ts);

// Fails (ConfigError naming the [[technique]]) when the technique names an unknown scene,
// runs on a scene asking for effects it cannot simulate or drawn as a box it cannot render,
// or when the plugin rejects one of its settings.
void check_technique_sweep(const TechniqueSweep& ts, const std::vector<SceneDesc>& scenes);

}  // namespace rl
