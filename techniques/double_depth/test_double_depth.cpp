// Double depth maps (chapter 5, Listing 5.3's pair of depths) on the weave against the mesh it
// stands for: between multilayer relief and a heightfield.
#include <cstdio>

#include <gtest/gtest.h>

#include "support/test_support.h"

namespace rl {
namespace {

TEST(DoubleDepth, CapsTheExtrusionButFillsUnderTheCrossings) {
  // Chapter 5's double depth keeps one solid per texel, from the first to the last surface:
  // the gaps between threads stay open (no curtains down to the floor, unlike a heightfield),
  // but where a thread crosses over another the space between them is filled.
  const SceneDesc scene = test::weave_scene(128, TruthLevel::Mesh);
  for (double el : {60.0, 30.0}) {
    SCOPED_TRACE(el);
    const ParamValues steps = {{"linear_steps", 32}};
    const double ml =
        test::measure(scene, "multilayer", steps, View{el, 30}, 128).metrics.at("wrong_pct");
    const test::Measured dd = test::measure(scene, "double_depth", steps, View{el, 30}, 128);
    const double hf =
        test::measure(scene, "relief", steps, View{el, 30}, 128).metrics.at("wrong_pct");
    EXPECT_EQ(dd.metrics.at("nonfinite_px"), 0);
    EXPECT_LT(ml, dd.metrics.at("wrong_pct"));
    EXPECT_LT(dd.metrics.at("wrong_pct"), hf);
    std::printf("weave %2.0f deg: wrong multilayer %.2f%%, double depth %.2f%%, relief %.2f%%\n",
                el, ml, dd.metrics.at("wrong_pct"), hf);
  }
}

}  // namespace
}  // namespace rl
