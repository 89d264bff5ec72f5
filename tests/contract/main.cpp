// The contract suite's main: techniques built outside the tree, named by
// $RELIEFLAB_PLUGIN_PATH, are loaded before the registry is iterated, so a plugin is held to its
// own declaration like a built-in technique. `relieflab contract --plugins DIR` runs it so,
// installed as lib/relieflab/relieflab-contract (in the build tree, tests/relieflab-contract).
#include <gtest/gtest.h>

#include "technique/plugins.h"

int main(int argc, char** argv) {
  rl::load_plugins(rl::plugin_paths_from_environment());
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
