#include "core/parallel.h"

#include <sched.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace rl {
namespace {

// The cores in this process's affinity mask; 0 if it cannot be read.
size_t cores_in_affinity_mask() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;  // more CPUs than cpu_set_t holds
  return size_t(CPU_COUNT(&set));
}

// The least quota of this process's cgroup v2 and the cgroups above it, in cores; 0 for none.
// Inside a container /proc/self/cgroup names "/", the container's own cgroup.
size_t cores_of_cgroup_quota() {
  std::ifstream cgroups("/proc/self/cgroup");
  std::string line, path;
  while (std::getline(cgroups, line))
    if (line.rfind("0::", 0) == 0) path = line.substr(3);  // the v2 hierarchy's entry
  if (path.empty() || path[0] != '/') return 0;
  size_t least = 0;
  for (;;) {
    std::ifstream cpu_max("/sys/fs/cgroup" + (path == "/" ? std::string() : path) + "/cpu.max");
    if (std::string limit; std::getline(cpu_max, limit))
      if (const size_t cores = cores_of_cpu_max(limit); cores > 0 && (least == 0 || cores < least))
        least = cores;
    if (path == "/") return least;
    path.erase(path.find_last_of('/'));
    if (path.empty()) path = "/";
  }
}

}  // namespace

size_t cores_of_cpu_max(const std::string& line) {
  std::istringstream in(line);
  std::string quota;
  double period = 0;
  if (!(in >> quota >> period) || !(period > 0) || quota == "max") return 0;
  char* end = nullptr;
  const double q = std::strtod(quota.c_str(), &end);
  if (end == quota.c_str() || *end != '\0' || !(q > 0) || !(q / period < 1e6)) return 0;
  return size_t(std::ceil(q / period));
}

size_t parallel_workers() {
  static const size_t workers = [] {
    size_t cores = cores_in_affinity_mask();
    if (cores == 0) cores = std::thread::hardware_concurrency();
    if (const size_t quota = cores_of_cgroup_quota(); quota > 0)
      cores = cores > 0 ? std::min(cores, quota) : quota;
    return std::max<size_t>(1, cores);
  }();
  return workers;
}

}  // namespace rl
