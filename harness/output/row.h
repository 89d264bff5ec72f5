#pragma once
// One result row: column name -> value, in column order.
#include <nlohmann/json.hpp>

namespace rl {
using Row = nlohmann::ordered_json;
}
